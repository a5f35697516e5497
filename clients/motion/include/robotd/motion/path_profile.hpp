// The path parameter of a move: s(t) goes from 0 at rest to 1 at rest over a duration. Every joint
// of a joint move (and the tool along a Cartesian line) follows from + (to − from)·s(t), so all of
// them start, cruise and arrive together. Two shapes, as the PAROL6 commander defines them:
// a quintic polynomial (zero speed and acceleration at both ends) and a trapezoid (constant
// acceleration, cruise, constant deceleration; with only a duration, 1/3 each).
#pragma once

#include <cstdint>

namespace robotd::motion {

enum class Shape : std::uint8_t {
  kPolynomial,  // RBTscript func "poly": s = 10τ³ − 15τ⁴ + 6τ⁵, τ = t / duration
  kTrapezoid,   // RBTscript func "trap"
};

/// Peak ds/dt · T and peak d²s/dt² · T² over a duration T.
inline constexpr double kQuinticPeakRate = 1.875;                      // at τ = 1/2
inline constexpr double kQuinticPeakAcceleration = 5.773502691896258;  // 10/√3, at τ = (3 − √3)/6
inline constexpr double kThirdsPeakRate = 1.5;                         // 1 / (T − T/3)
inline constexpr double kThirdsPeakAcceleration = 4.5;                 // 1.5 / (T/3)

class PathProfile {
 public:
  static PathProfile polynomial(double duration_s) noexcept;
  /// Accelerates for `ramp_s`, cruises, decelerates for `ramp_s`; 0 < ramp_s ≤ duration_s / 2.
  static PathProfile trapezoid(double duration_s, double ramp_s) noexcept;
  /// The commander's profile over a given duration: the polynomial, or the trapezoid in thirds.
  static PathProfile over(Shape shape, double duration_s) noexcept;

  /// s(t), 0 before the start and 1 after the end.
  double position(double t_s) const noexcept;
  /// ds/dt (1/s), 0 outside the move.
  double rate(double t_s) const noexcept;

  Shape shape() const noexcept { return shape_; }
  double duration_s() const noexcept { return duration_s_; }
  /// Trapezoid: how long it accelerates (and decelerates); 0 for the polynomial.
  double ramp_s() const noexcept { return ramp_s_; }
  double peak_rate() const noexcept;          // 1/s
  double peak_acceleration() const noexcept;  // 1/s²

 private:
  PathProfile(Shape shape, double duration_s, double ramp_s) noexcept
      : shape_(shape), duration_s_(duration_s), ramp_s_(ramp_s) {}

  Shape shape_;
  double duration_s_;
  double ramp_s_;
};

/// Peak ds/dt · T of the commander's profile of `shape` over any duration T.
constexpr double peak_rate_factor(Shape shape) noexcept {
  return shape == Shape::kPolynomial ? kQuinticPeakRate : kThirdsPeakRate;
}
/// Peak d²s/dt² · T² of the commander's profile of `shape` over any duration T.
constexpr double peak_acceleration_factor(Shape shape) noexcept {
  return shape == Shape::kPolynomial ? kQuinticPeakAcceleration : kThirdsPeakAcceleration;
}

}  // namespace robotd::motion
