#include "path_progress.hpp"

#include <algorithm>
#include <cmath>

namespace robotd::xarm::sim {
namespace {

/// Guards the divisions: a speed or acceleration of 0 would take forever.
constexpr double kSmallest = 1e-9;

}  // namespace

Trapezoid::Trapezoid(double distance, double max_speed, double acceleration)
    : distance_(std::max(distance, 0.0)), acceleration_(std::max(acceleration, kSmallest)) {
  max_speed = std::max(max_speed, kSmallest);
  if (distance_ * acceleration_ >= max_speed * max_speed) {  // reaches the speed
    peak_speed_ = max_speed;
    ramp_s_ = max_speed / acceleration_;
    cruise_s_ = distance_ / max_speed - ramp_s_;
  } else {  // a triangle: half the distance accelerating
    ramp_s_ = std::sqrt(distance_ / acceleration_);
    peak_speed_ = acceleration_ * ramp_s_;
  }
}

double Trapezoid::position(double t_s) const {
  if (t_s <= 0) return 0;
  if (t_s >= duration_s()) return distance_;
  if (t_s < ramp_s_) return 0.5 * acceleration_ * t_s * t_s;
  const double left_s = duration_s() - t_s;
  if (left_s < ramp_s_) return distance_ - 0.5 * acceleration_ * left_s * left_s;
  return 0.5 * peak_speed_ * ramp_s_ + peak_speed_ * (t_s - ramp_s_);
}

double Trapezoid::speed(double t_s) const {
  if (t_s <= 0 || t_s >= duration_s()) return 0;
  if (t_s < ramp_s_) return acceleration_ * t_s;
  const double left_s = duration_s() - t_s;
  if (left_s < ramp_s_) return acceleration_ * left_s;
  return peak_speed_;
}

PathProgress::PathProgress(double length, double max_speed, double acceleration)
    : length_(std::max(length, 0.0)),
      max_speed_(max_speed),
      acceleration_(std::max(acceleration, kSmallest)),
      profile_(length_, max_speed, acceleration_) {}

void PathProgress::advance(double dt_s) {
  if (phase_ == Phase::kHalted) return;
  elapsed_s_ += dt_s;
  update();
}

void PathProgress::update() {
  if (phase_ == Phase::kProfile) {
    position_ = phase_start_ + profile_.position(elapsed_s_);
    speed_ = profile_.speed(elapsed_s_);
    return;
  }
  const double stop_s = brake_speed_ / acceleration_;
  const double t_s = std::min(elapsed_s_, stop_s);
  position_ = std::min(length_, phase_start_ + brake_speed_ * t_s - 0.5 * acceleration_ * t_s * t_s);
  speed_ = brake_speed_ - acceleration_ * t_s;
  if (elapsed_s_ >= stop_s) {
    phase_ = Phase::kHalted;
    speed_ = 0;
  }
}

void PathProgress::brake() {
  if (phase_ != Phase::kProfile || done()) return;
  phase_ = Phase::kBraking;
  phase_start_ = position_;
  brake_speed_ = speed_;
  elapsed_s_ = 0;
  update();
}

void PathProgress::resume() {
  if (phase_ == Phase::kProfile) return;
  phase_ = Phase::kProfile;
  phase_start_ = position_;
  profile_ = Trapezoid(length_ - position_, max_speed_, acceleration_);
  elapsed_s_ = 0;
  update();
}

}  // namespace robotd::xarm::sim
