// robotd's C++ messages as the C API's plain structs. Texts longer than a field are cut at a
// UTF-8 character boundary; arrays hold at most ROBOTD_MAX_JOINTS joints.
#pragma once

#include "robotd/messages.hpp"
#include "robotd/robotd.h"

namespace robotd::c {

void to_c(const DeviceInfo& info, robotd_device_info& out);
void to_c(const JointState& state, robotd_joint_state& out);
void to_c(const DeviceStatus& status, robotd_device_status& out);
void to_c(const TickState& state, robotd_tick_state& out);
void to_c(const SessionInfo& info, robotd_session_info& out);
/// What robotd_session_answer needs of a robotd_tick_state: its device and tick.
TickState tick_of(const robotd_tick_state& state);

}  // namespace robotd::c
