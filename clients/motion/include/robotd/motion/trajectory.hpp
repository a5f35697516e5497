// A planned move, sampled every dt: joint positions and velocities, so that a streamer can track
// the positions (RBTscript's default) or only the speed curve (its `speed` argument).
#pragma once

#include <string>
#include <vector>

#include "robotd/motion/path_profile.hpp"

namespace robotd::motion {

/// Joint values of an arm, one per joint (rad, rad/s, ...).
using Joints = std::vector<double>;

struct Trajectory {
  double dt_s = 0;
  /// positions[k][j]: joint j at k·dt (rad); front() is where the move starts, back() its goal.
  std::vector<Joints> positions;
  /// velocities[k][j] (rad/s) at the same times; zero at both ends.
  std::vector<Joints> velocities;
  Shape shape = Shape::kTrapezoid;
  /// (samples − 1) · dt: a requested duration rounded up to whole samples.
  double duration_s = 0;
  /// How the timing was chosen, for people, e.g. "trapezoid, leading joint J3 at 50 % speed ...".
  std::string how;
};

}  // namespace robotd::motion
