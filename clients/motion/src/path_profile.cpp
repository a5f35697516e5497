#include "robotd/motion/path_profile.hpp"

namespace robotd::motion {

PathProfile PathProfile::polynomial(double duration_s) noexcept { return {Shape::kPolynomial, duration_s, 0.0}; }

PathProfile PathProfile::trapezoid(double duration_s, double ramp_s) noexcept {
  return {Shape::kTrapezoid, duration_s, ramp_s};
}

PathProfile PathProfile::over(Shape shape, double duration_s) noexcept {
  return shape == Shape::kPolynomial ? polynomial(duration_s) : trapezoid(duration_s, duration_s / 3.0);
}

double PathProfile::position(double t_s) const noexcept {
  if (t_s <= 0) return 0.0;
  if (t_s >= duration_s_) return 1.0;
  if (shape_ == Shape::kPolynomial) {
    const double tau = t_s / duration_s_;
    return tau * tau * tau * (10.0 + tau * (-15.0 + 6.0 * tau));
  }
  const double cruise_rate = peak_rate();
  const double acceleration = cruise_rate / ramp_s_;
  if (t_s < ramp_s_) return 0.5 * acceleration * t_s * t_s;
  if (t_s <= duration_s_ - ramp_s_) return 0.5 * cruise_rate * ramp_s_ + cruise_rate * (t_s - ramp_s_);
  const double left = duration_s_ - t_s;
  return 1.0 - 0.5 * acceleration * left * left;
}

double PathProfile::rate(double t_s) const noexcept {
  if (t_s <= 0 || t_s >= duration_s_) return 0.0;
  if (shape_ == Shape::kPolynomial) {
    const double tau = t_s / duration_s_;
    return 30.0 * tau * tau * (1.0 - tau) * (1.0 - tau) / duration_s_;
  }
  const double cruise_rate = peak_rate();
  if (t_s < ramp_s_) return cruise_rate * t_s / ramp_s_;
  if (t_s <= duration_s_ - ramp_s_) return cruise_rate;
  return cruise_rate * (duration_s_ - t_s) / ramp_s_;
}

double PathProfile::peak_rate() const noexcept {
  // A trapezoid covers 1 = rate · (duration − ramp).
  return shape_ == Shape::kPolynomial ? kQuinticPeakRate / duration_s_ : 1.0 / (duration_s_ - ramp_s_);
}

double PathProfile::peak_acceleration() const noexcept {
  return shape_ == Shape::kPolynomial ? kQuinticPeakAcceleration / (duration_s_ * duration_s_) : peak_rate() / ramp_s_;
}

}  // namespace robotd::motion
