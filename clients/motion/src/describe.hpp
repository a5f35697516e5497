// Numbers and names in error messages and in Trajectory::how.
#pragma once

#include <cstddef>
#include <string>

namespace robotd::motion::detail {

/// "J1" for joint 0: how the commander and the drivers' ops name joints.
std::string joint_name(std::size_t joint);
/// `value` with at most `significant` significant digits: 0.5, 2.31, 1.2e+03.
std::string number(double value, int significant = 3);
/// Radians in degrees, for people.
double degrees(double rad);
/// `value` with `decimals` digits after the point: 42.0.
std::string fixed(double value, int decimals = 1);

}  // namespace robotd::motion::detail
