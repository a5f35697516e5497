// What the RBTscript device tests hold a finished program to: the 0.5 mm and 0.1°.
#pragma once

#include <numbers>

namespace robotd::testing {

inline constexpr double kDeg = std::numbers::pi / 180.0;
inline constexpr double kPositionToleranceM = 0.5e-3;
inline constexpr double kAngleToleranceRad = 0.1 * kDeg;

}  // namespace robotd::testing
