// The SDK's "judge_flag" check of a SocketCAN interface before use: it exists, it is a CAN
// interface, it is up, and (for a real controller) it runs at the expected bitrate. Errors say
// what is wrong and the command that fixes it.
#pragma once

#include <cstdint>
#include <string>

#include "robotd/result.hpp"

namespace robotd::transport {

/// `bitrate` 0 skips the bitrate check. A virtual CAN (vcan) passes: it has no bitrate and
/// reports its state as "unknown".
Result<void> check_can_interface(const std::string& name, std::uint32_t bitrate);

}  // namespace robotd::transport
