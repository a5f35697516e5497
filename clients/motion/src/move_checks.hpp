// The argument checks every planner shares: each returns what is wrong, or nothing.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "robotd/kinematics/arm_model.hpp"
#include "robotd/motion/joint_move.hpp"

namespace robotd::motion::detail {

/// A limit is exceeded only beyond this relative margin: a move planned exactly at a limit stays valid.
inline constexpr double kLimitMargin = 1e-9;
/// More samples than this is a unit mistake, not a move (10⁴ s at 10 ms).
inline constexpr double kMaxSamples = 1e6;

/// `limits` describe `dof` joints (dof ≥ 1), all finite, speeds and accelerations positive, min ≤ max.
std::optional<std::string> limits_problem(const JointLimits& limits, std::size_t dof);
/// `q` (called `what`) has the limits' joint count and finite values.
std::optional<std::string> joints_problem(const Joints& q, const JointLimits& limits, std::string_view what);
/// The first joint of `q` (called `what`) outside its position limits.
std::optional<std::string> outside_limits(const Joints& q, const JointLimits& limits, std::string_view what);
/// `model` has 1 … 7 joints, `limits` as many, and `from` is a finite position of them.
std::optional<std::string> model_problem(const kinematics::ArmModel& model, const Joints& from,
                                         const JointLimits& limits);
/// dt and t positive, t at most kMaxSamples samples, v and a in (0, 100].
std::optional<std::string> timing_problem(const MoveTiming& timing, double dt_s);

/// How many intervals of dt make a requested duration, rounded up (one a hair over a whole number
/// of samples counts as that number); at least one.
std::size_t intervals(double duration_s, double dt_s);
/// The fewest intervals of dt that last at least `duration_s` (a duration a limit sets); at least one.
std::size_t intervals_covering(double duration_s, double dt_s);

}  // namespace robotd::motion::detail
