// A minimum-jerk move of several joints from rest to rest, all arriving together: position
// follows start + (target - start) · s(t/T) with s(τ) = 10τ³ − 15τ⁴ + 6τ⁵, so velocity and
// acceleration are zero at both ends. T is the shortest duration for which no joint's speed
// exceeds the limit (a joint's peak speed is 1.875 · distance / T).
#pragma once

#include <vector>

namespace robotctl {

class MinimumJerkMove {
 public:
  /// `start_rad` and `target_rad` have one value per joint; `max_speed_rad_s` > 0.
  MinimumJerkMove(std::vector<double> start_rad, std::vector<double> target_rad, double max_speed_rad_s);

  /// 0 when every joint is already at its target.
  double duration_s() const { return duration_s_; }
  /// Positions at `time_s` after the start; before 0 the start, after duration_s() the target.
  std::vector<double> positions_at(double time_s) const;

 private:
  std::vector<double> start_rad_;
  std::vector<double> target_rad_;
  double duration_s_ = 0;
};

}  // namespace robotctl
