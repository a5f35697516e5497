// Joint moves by the RBTscript rules (MoveJoint, and MovePose after its IK), for arms of any
// number of joints. The path is a straight line in joint space; one path parameter s(t) drives
// every joint, so all of them arrive together. How s(t) is timed:
//   - t (duration_s) given: it overrides v and a. Shape "poly" unless told "trap"; the
//     trapezoid then spends 1/3 of t accelerating, 1/3 cruising, 1/3 decelerating. A t too short
//     for a joint's maximum speed or acceleration is refused, with the shortest t that would do.
//   - v and/or a given (percent): a trapezoid (whatever the shape says, as the commander does).
//     The leading joint, the one whose limit binds, moves at v % of its maximum speed and
//     accelerates at a % of its maximum acceleration; the others, scaled onto the same s(t),
//     stay at or under v % and a % of theirs. When the path is too short to reach that speed at
//     that acceleration, the trapezoid falls back to thirds, at a % acceleration.
//   - neither: the same with the conservative defaults below (a trapezoid, or the polynomial if
//     the shape says "poly").
// A percent not given takes its default. Durations are rounded up to whole samples.
#pragma once

#include <optional>
#include <vector>

#include "robotd/motion/path_profile.hpp"
#include "robotd/motion/trajectory.hpp"
#include "robotd/result.hpp"

namespace robotd::motion {

/// The commander's "small conservative speed and acceleration" when a move names neither.
inline constexpr double kDefaultSpeedPercent = 20.0;
inline constexpr double kDefaultAccelerationPercent = 20.0;

/// Per joint; all four the arm's joint count long.
struct JointLimits {
  Joints min_rad, max_rad;
  Joints max_speed_rad_s, max_acceleration_rad_s2;
};

/// RBTscript's t, v, a and func; each optional.
struct MoveTiming {
  std::optional<double> duration_s{};            // t > 0
  std::optional<double> speed_percent{};         // v, in (0, 100]
  std::optional<double> acceleration_percent{};  // a, in (0, 100]
  std::optional<Shape> shape{};                  // func
};

/// From `from` to `to` (both within joint count of `limits`; `to` within the position limits),
/// sampled every `dt_s`.
Result<Trajectory> plan_joint_move(const Joints& from, const Joints& to, const MoveTiming& timing,
                                   const JointLimits& limits, double dt_s);

}  // namespace robotd::motion
