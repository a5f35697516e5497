// One tick of robotd's 1 kHz loop, for the tests of the per-joint control law.
#pragma once

namespace robotd::control {

inline constexpr double kDt = 0.001;  // s

}  // namespace robotd::control
