// What robotd reports as this device's fault: the controller's error code in its own words, or
// a problem of robotd's servo streaming.
#pragma once

#include <cstdint>

#include "robotd/driver/types.hpp"

namespace robotd::xarm {

/// Fault codes robotd reports for this driver that are not the controller's own (those are
/// 1 … 255, spec §6.1).
inline constexpr std::int32_t kNotConnectedFault = -1;
inline constexpr std::int32_t kLinkLostFault = -2;
inline constexpr std::int32_t kArmStoppedFault = -3;    // stopped under a streaming session
inline constexpr std::int32_t kServoRefusedFault = -4;  // servo mode could not be entered

/// The controller's error when it has one ("C23 joint angle exceeds limit"), else
/// `servo_fault` (code 0 when nothing is wrong). The e-stop errors (C1–C3) are no fault: the
/// driver reports them as the device's e-stop input, which engages robotd's e-stop. Not
/// real-time (builds text).
driver::FaultInfo arm_fault(int error_code, const driver::FaultInfo& servo_fault);

}  // namespace robotd::xarm
