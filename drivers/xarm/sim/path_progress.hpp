// How far along a path a planned move is: a trapezoidal speed profile from rest to rest at a
// maximum speed and acceleration (a triangle when the path is too short to reach the speed),
// which can brake to rest on the path at that acceleration (pause, decelerated stop) and start
// again from rest over what is left (resume). Units are the path's (rad or m).
#pragma once

namespace robotd::xarm::sim {

/// Rest to rest over `distance`: accelerate, cruise at `max_speed`, decelerate.
class Trapezoid {
 public:
  Trapezoid() = default;
  Trapezoid(double distance, double max_speed, double acceleration);
  double duration_s() const { return 2 * ramp_s_ + cruise_s_; }
  double position(double t_s) const;
  double speed(double t_s) const;

 private:
  double distance_ = 0;
  double acceleration_ = 0;
  double peak_speed_ = 0;
  double ramp_s_ = 0;
  double cruise_s_ = 0;
};

class PathProgress {
 public:
  PathProgress(double length, double max_speed, double acceleration);

  double position() const { return position_; }
  double speed() const { return speed_; }
  /// At the end of the path.
  bool done() const { return phase_ == Phase::kProfile && elapsed_s_ >= profile_.duration_s(); }
  /// Braked to a halt (or never started again after one).
  bool halted() const { return phase_ == Phase::kHalted; }

  void advance(double dt_s);
  /// Decelerates to rest at the path's acceleration, then halts.
  void brake();
  /// From rest, a new profile over what is left of the path.
  void resume();

 private:
  enum class Phase { kProfile, kBraking, kHalted };
  void update();

  double length_;
  double max_speed_;
  double acceleration_;
  Phase phase_ = Phase::kProfile;
  Trapezoid profile_;
  double phase_start_ = 0;  // path position where the phase began
  double brake_speed_ = 0;  // speed when braking began
  double elapsed_s_ = 0;    // in the phase
  double position_ = 0;
  double speed_ = 0;
};

}  // namespace robotd::xarm::sim
