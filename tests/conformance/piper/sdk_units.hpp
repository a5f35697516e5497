#pragma once

// The SDK's integer units (0.001°, 0.001 mm, 0.1°, 0.001 rad/s, …) to and from robotd's SI values,
// for the PiPER conformance replay. Counts are exact integers on the SDK side, so a value goes
// out as SI and comes back as the nearest count.

#include <cmath>
#include <cstdint>
#include <numbers>

namespace robotd::piper::conformance {

inline constexpr double kMilliDegPerRad = 180000.0 / std::numbers::pi;
inline constexpr double kDeciDegPerRad = 1800.0 / std::numbers::pi;

inline double rad_of_milli_deg(double counts) { return counts / kMilliDegPerRad; }
inline double rad_of_deci_deg(double counts) { return counts / kDeciDegPerRad; }
inline double metres_of_micrometres(double counts) { return counts * 1e-6; }

inline std::int64_t milli_deg_of(double rad) { return std::llround(rad * kMilliDegPerRad); }
inline std::int64_t deci_deg_of(double rad) { return std::llround(rad * kDeciDegPerRad); }
inline std::int64_t micrometres_of(double m) { return std::llround(m * 1e6); }
inline std::int64_t counts_of(double value, double unit) { return std::llround(value / unit); }

}  // namespace robotd::piper::conformance
