// The binary payloads of joint_state and control_command records (docs/recording.md). Joint
// names are not repeated: values are in the order of the device's joint_names in the header.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "robotd/client/session.hpp"

namespace robotctl::recording {

/// The device index of a command whose device robotctl could not tell (no device field, and
/// robotd serves several devices).
inline constexpr std::uint16_t kUnknownDevice = 0xFFFF;

/// device u16, stamp_ns i64, then position, velocity and effort as f64 arrays (u16 count, values).
struct JointStateRecord {
  std::uint16_t device = 0;   // index in the header's devices
  std::int64_t stamp_ns = 0;  // the sample's header stamp: robotd's CLOCK_REALTIME
  std::vector<double> position;
  std::vector<double> velocity;
  std::vector<double> effort;

  bool operator==(const JointStateRecord&) const = default;
};

/// device u16, stamp_ns i64, session u32, motor_ids as an i32 array, then positions, velocities,
/// kp, kd and torques as f32 arrays (u16 count, values).
struct ControlCommandRecord {
  std::uint16_t device = kUnknownDevice;
  std::int64_t stamp_ns = 0;  // the command's header stamp: the sender's CLOCK_REALTIME
  std::uint32_t session = 0;  // the first 8 hex digits of the session uuid (session_tag)
  robotd::Command values;     // as sent: arrays the command left out are empty

  bool operator==(const ControlCommandRecord&) const = default;
};

/// nullopt when an array has more than 65535 values.
std::optional<std::string> encode(const JointStateRecord& record);
std::optional<std::string> encode(const ControlCommandRecord& record);
/// nullopt unless `payload` is exactly one such record.
std::optional<JointStateRecord> decode_joint_state(std::string_view payload);
std::optional<ControlCommandRecord> decode_control_command(std::string_view payload);

/// A session uuid's first 8 hex digits as a number (0 if they are not hex): enough to tell the
/// sessions of a recording apart, too little to command with (the other 90 random bits stay
/// unknown). Unrelated to the public session id /session_status and robotd's log show.
std::uint32_t session_tag(std::string_view uuid);
/// The tag as 8 lowercase hex digits.
std::string session_tag_text(std::uint32_t tag);

}  // namespace robotctl::recording
