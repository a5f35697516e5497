// The longest text and the longest list robotd takes in any field a client sends
// (docs/dds-interface.md, "Limits"). robotd refuses a request or command with a field beyond
// its limit, saying which field, how long it was and the limit. Text limits are in bytes and
// leave room for the NUL of the C client's fixed buffers (ROBOTD_NAME_CAPACITY = 64).
#pragma once

#include <cstddef>

namespace robotd::limits {

inline constexpr std::size_t kUuidBytes = 36;              // a session uuid, 8-4-4-4-12 hex digits
inline constexpr std::size_t kNodeNameBytes = 255;         // node_name (ROS 2 names are at most 255)
inline constexpr std::size_t kDeviceNameBytes = 63;        // device (config names are held to it too)
inline constexpr std::size_t kFrameIdBytes = 255;          // ControlCommand.header.frame_id (robotd ignores it)
inline constexpr std::size_t kPolicyNameBytes = 255;       // RequestControl.policy_name
inline constexpr std::size_t kPolicyFileNameBytes = 1023;  // RequestControl.policy_file_name (a path)
inline constexpr std::size_t kOpBytes = 63;                // DeviceCall.op
inline constexpr std::size_t kReasonBytes = 255;           // Estop.reason
inline constexpr std::size_t kArgsJsonBytes = 65536;       // DeviceCall.args_json
inline constexpr std::size_t kJoints = 64;                 // motor_ids and every per-motor list

}  // namespace robotd::limits
