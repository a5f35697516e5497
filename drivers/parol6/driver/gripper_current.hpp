// The SSG-48's gripping current set point: what the commander's Gripper() accepts (0 … 1300 mA)
// and the cautions its documentation attaches to the ends of that range.
#pragma once

#include <string>

namespace robotd::parol6 {

inline constexpr double kGripperCurrentMinA = 0.0;
inline constexpr double kGripperCurrentMaxA = 1.3;

/// The caution for `current_a` (A) at gripper speed `speed` (0 … 255), or "" if none: above 0.7 A
/// the gripper can damage the object it grasps and hurt a hand in its way, the more so at high
/// speed; below 0.15 A it usually does not move at all.
std::string gripper_current_warning(double current_a, int speed);

}  // namespace robotd::parol6
