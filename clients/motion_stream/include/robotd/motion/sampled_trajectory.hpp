// A trajectory as a planner hands it to the streamer: joint positions and velocities at a fixed
// step. Plain vectors, so that the streamer does not depend on the planner (robotd_motion).
#pragma once

#include <cstddef>
#include <vector>

#include "robotd/result.hpp"

namespace robotd::motion {

struct SampledTrajectory {
  double dt_s = 0;                              // time between samples, > 0
  std::vector<std::vector<double>> positions;   // [sample][joint], rad
  std::vector<std::vector<double>> velocities;  // [sample][joint], rad/s; same shape as positions

  std::size_t joint_count() const { return positions.empty() ? 0 : positions.front().size(); }
  double duration_s() const { return positions.empty() ? 0 : dt_s * static_cast<double>(positions.size() - 1); }
};

/// Ok when `trajectory` has at least one sample, dt_s > 0, `joint_count` values in every sample of
/// both arrays and only finite numbers; otherwise an error (kInvalidArgument) naming the first
/// problem and what is expected.
Result<void> check_trajectory(const SampledTrajectory& trajectory, std::size_t joint_count);

/// `trajectory` (already checked) at `period_s` steps by linear interpolation between its samples:
/// sample k at k·period_s, the last exactly at the trajectory's end (a shorter step), so that the
/// result ends where the trajectory does.
SampledTrajectory resample(const SampledTrajectory& trajectory, double period_s);

}  // namespace robotd::motion
