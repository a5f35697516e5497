#include "trajectory.hpp"

#include <algorithm>
#include <cmath>

namespace robotctl {
namespace {

constexpr double kPeakSpeedFactor = 1.875;  // max of ds/dτ, at τ = 1/2

double blend(double tau) { return tau * tau * tau * (10.0 + tau * (-15.0 + tau * 6.0)); }

}  // namespace

MinimumJerkMove::MinimumJerkMove(std::vector<double> start_rad, std::vector<double> target_rad, double max_speed_rad_s)
    : start_rad_(std::move(start_rad)), target_rad_(std::move(target_rad)) {
  double longest_rad = 0;
  for (std::size_t j = 0; j < start_rad_.size(); ++j) {
    longest_rad = std::max(longest_rad, std::fabs(target_rad_[j] - start_rad_[j]));
  }
  duration_s_ = kPeakSpeedFactor * longest_rad / max_speed_rad_s;
}

std::vector<double> MinimumJerkMove::positions_at(double time_s) const {
  const double s = duration_s_ > 0 ? blend(std::clamp(time_s / duration_s_, 0.0, 1.0)) : 1.0;
  std::vector<double> positions(start_rad_.size());
  for (std::size_t j = 0; j < positions.size(); ++j) {
    positions[j] = start_rad_[j] + (target_rad_[j] - start_rad_[j]) * s;
  }
  return positions;
}

}  // namespace robotctl
