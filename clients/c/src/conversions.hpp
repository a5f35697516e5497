// robotd's C++ messages as the C API's plain structs. Texts longer than a field are cut at a
// UTF-8 character boundary; arrays hold at most ROBOTD_MAX_JOINTS joints.
#pragma once

#include <algorithm>
#include <cstddef>
#include <string_view>

#include "robotd/messages.hpp"
#include "robotd/robotd.h"

namespace robotd::c {

/// `text` into a C text field, cut at its capacity on a UTF-8 character boundary.
template <std::size_t kCapacity>
void copy_text(std::string_view text, char (&field)[kCapacity]) {
  std::size_t length = std::min(text.size(), kCapacity - 1);
  // Never cut inside a UTF-8 sequence: step back over continuation bytes (10xxxxxx).
  if (length < text.size()) {
    while (length > 0 && (static_cast<unsigned char>(text[length]) & 0xC0U) == 0x80U) --length;
  }
  text.copy(field, length);
  field[length] = '\0';
}

void to_c(const DeviceInfo& info, robotd_device_info& out);
void to_c(const JointState& state, robotd_joint_state& out);
void to_c(const DeviceStatus& status, robotd_device_status& out);
void to_c(const TickState& state, robotd_tick_state& out);
void to_c(const SessionInfo& info, robotd_session_info& out);
/// What robotd_session_answer needs of a robotd_tick_state: its device and tick.
TickState tick_of(const robotd_tick_state& state);

}  // namespace robotd::c
