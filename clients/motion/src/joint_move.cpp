// Joint moves by the RBTscript rules (see joint_move.hpp): choose s(t), then sample it onto the
// straight joint-space line from `from` to `to`.
#include "robotd/motion/joint_move.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <string_view>

#include "describe.hpp"
#include "joint_path.hpp"
#include "move_checks.hpp"
#include "named_planners.hpp"

namespace robotd::motion {
namespace {

using detail::joint_name;
using detail::number;

/// t given: the commander's profile over t, refused when a joint would pass its limits.
Result<Trajectory> timed_move(const Joints& from, const Joints& to, const Joints& distance, const MoveTiming& timing,
                              const JointLimits& limits, double dt_s, std::string_view what) {
  const Shape shape = timing.shape.value_or(Shape::kPolynomial);
  const std::size_t count = detail::intervals(*timing.duration_s, dt_s);
  const PathProfile profile = PathProfile::over(shape, static_cast<double>(count) * dt_s);
  // The joint that needs the longest names the problem, with the t that would do.
  double needed_s = 0;
  std::size_t worst = 0;
  for (std::size_t j = 0; j < distance.size(); ++j) {
    const double joint_needs =
        std::max(peak_rate_factor(shape) * distance[j] / limits.max_speed_rad_s[j],
                 std::sqrt(peak_acceleration_factor(shape) * distance[j] / limits.max_acceleration_rad_s2[j]));
    if (joint_needs > needed_s) {
      needed_s = joint_needs;
      worst = j;
    }
  }
  if (needed_s > profile.duration_s() * (1 + detail::kLimitMargin)) {
    return Error{ErrorCode::kInvalidArgument, std::string(what) + ": t = " + number(*timing.duration_s) +
                                                  " s is too short: " + joint_name(worst) + " would reach " +
                                                  number(distance[worst] * profile.peak_rate()) + " rad/s and " +
                                                  number(distance[worst] * profile.peak_acceleration()) +
                                                  " rad/s² (max " + number(limits.max_speed_rad_s[worst]) + " rad/s, " +
                                                  number(limits.max_acceleration_rad_s2[worst]) +
                                                  " rad/s²); this move needs t ≥ " + number(needed_s) + " s"};
  }
  const std::string how = (shape == Shape::kPolynomial ? "quintic polynomial" : "trapezoid in thirds") +
                          std::string(" over ") + number(profile.duration_s()) + " s (t given)";
  return detail::sample_joint_path(from, to, profile, count, dt_s, how);
}

/// The joint that allows the least of `rate` (per joint: percent of its maximum over its distance).
struct Binding {
  double rate = std::numeric_limits<double>::infinity();
  std::size_t joint = 0;
};
Binding binding(const Joints& distance, const Joints& maximum, double fraction) {
  Binding least;
  for (std::size_t j = 0; j < distance.size(); ++j) {
    if (distance[j] <= 0) continue;
    const double rate = fraction * maximum[j] / distance[j];
    if (rate < least.rate) least = {.rate = rate, .joint = j};
  }
  return least;
}

/// No t: the fastest s(t) of the shape in which the leading joint keeps to v % of its maximum
/// speed and a % of its maximum acceleration (so the others keep to less of theirs).
Result<Trajectory> paced_move(const Joints& from, const Joints& to, const Joints& distance, const MoveTiming& timing,
                              const JointLimits& limits, double dt_s, std::string_view what) {
  const bool percent_given = timing.speed_percent || timing.acceleration_percent;
  const Shape shape = percent_given ? Shape::kTrapezoid : timing.shape.value_or(Shape::kTrapezoid);
  const double speed_percent = timing.speed_percent.value_or(kDefaultSpeedPercent);
  const double acceleration_percent = timing.acceleration_percent.value_or(kDefaultAccelerationPercent);
  const Binding speed = binding(distance, limits.max_speed_rad_s, speed_percent / 100);
  const Binding acceleration = binding(distance, limits.max_acceleration_rad_s2, acceleration_percent / 100);
  const std::string pace = number(speed_percent) + " % speed, " + number(acceleration_percent) + " % acceleration";
  // Which joints lead: usually one for both, but a joint with little acceleration may bind that alone.
  const std::string leading = speed.joint == acceleration.joint
                                  ? joint_name(speed.joint) + " at " + pace
                                  : joint_name(speed.joint) + " at " + number(speed_percent) + " % speed, " +
                                        joint_name(acceleration.joint) + " at " + number(acceleration_percent) +
                                        " % acceleration";

  std::string how;
  double duration_s = 0;
  double ramp_s = 0;  // trapezoid with a cruise at V; 0 for the polynomial and for thirds
  if (shape == Shape::kPolynomial) {
    duration_s = std::max(kQuinticPeakRate / speed.rate, std::sqrt(kQuinticPeakAcceleration / acceleration.rate));
    how = "quintic polynomial, leading joint " + leading + " at most";
  } else if (speed.rate * speed.rate / acceleration.rate <= 1) {
    // Accelerating to the cruise rate V at A covers V²/(2A) of the path, and as much to stop.
    ramp_s = speed.rate / acceleration.rate;
    duration_s = 1 / speed.rate + ramp_s;
    how = "trapezoid, leading joint " + leading;
  } else {
    // Too short a path to reach V: thirds, accelerating at A (peak rate √(A/2) < V).
    duration_s = std::sqrt(kThirdsPeakAcceleration / acceleration.rate);
    how = "trapezoid in thirds: too short a path for " + joint_name(speed.joint) + " to reach " + pace;
  }
  const std::size_t count = detail::intervals_covering(duration_s, dt_s);
  if (static_cast<double>(count) > detail::kMaxSamples) {
    return Error{ErrorCode::kInvalidArgument, std::string(what) + ": at " + pace +
                                                  " the move would take more than a million samples of " +
                                                  number(dt_s) + " s"};
  }
  // Whole samples only lengthen the move: the trapezoid keeps its ramp and cruises slower.
  const double sampled_s = static_cast<double>(count) * dt_s;
  const PathProfile profile = shape == Shape::kPolynomial ? PathProfile::polynomial(sampled_s)
                              : ramp_s > 0                ? PathProfile::trapezoid(sampled_s, ramp_s)
                                                          : PathProfile::over(Shape::kTrapezoid, sampled_s);
  return detail::sample_joint_path(from, to, profile, count, dt_s, how + ", " + number(sampled_s) + " s");
}

}  // namespace

namespace detail {

Result<Trajectory> plan_joint_move_as(std::string_view what, const Joints& from, const Joints& to,
                                      const MoveTiming& timing, const JointLimits& limits, double dt_s) {
  auto problem = detail::limits_problem(limits, limits.min_rad.size());
  if (!problem) problem = detail::joints_problem(from, limits, "the start");
  if (!problem) problem = detail::joints_problem(to, limits, "the goal");
  if (!problem) problem = detail::outside_limits(to, limits, "goal");
  if (!problem) problem = detail::timing_problem(timing, dt_s);
  if (problem) return Error{ErrorCode::kInvalidArgument, std::string(what) + ": " + *problem};

  Joints distance(from.size());
  for (std::size_t j = 0; j < distance.size(); ++j) distance[j] = std::abs(to[j] - from[j]);
  if (timing.duration_s) return timed_move(from, to, distance, timing, limits, dt_s, what);
  if (std::all_of(distance.begin(), distance.end(), [](double d) { return d == 0; })) {
    return Trajectory{.dt_s = dt_s,
                      .positions = {from},
                      .velocities = {Joints(from.size(), 0.0)},
                      .shape = Shape::kTrapezoid,
                      .duration_s = 0,
                      .how = "already there"};
  }
  return paced_move(from, to, distance, timing, limits, dt_s, what);
}

}  // namespace detail

Result<Trajectory> plan_joint_move(const Joints& from, const Joints& to, const MoveTiming& timing,
                                   const JointLimits& limits, double dt_s) {
  return detail::plan_joint_move_as("joint move", from, to, timing, limits, dt_s);
}

}  // namespace robotd::motion
