// The controller's error reports as one robotd fault: system errors (every shape of the arm
// state and push) and the joints' error bitmasks, in the controller's words (spec §7).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "codec/realman_codec.hpp"
#include "robotd/driver/types.hpp"

namespace robotd::realman {

/// Fault codes robotd reports for this driver that are not the controller's own.
inline constexpr std::int32_t kNotConnectedFault = -1;
inline constexpr std::int32_t kLinkLostFault = -2;
/// A joint error is reported as this plus the joint number (1-based) × 0x10000 plus its bits.
inline constexpr std::int32_t kJointFaultBase = 0x100000;

/// Joint bits that are warnings, not faults: "position command step warning" comes and goes
/// while streaming.
inline constexpr std::uint16_t kJointWarningBits = 0x4000;

/// code 0 when nothing is wrong. Not real-time (builds text).
driver::FaultInfo arm_fault(std::span<const std::uint16_t> errors, std::span<const std::uint16_t> joint_errors);

}  // namespace robotd::realman
