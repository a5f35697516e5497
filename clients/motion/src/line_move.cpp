// MoveCart: the tool on a straight line (see cartesian_move.hpp), solved into joints sample by
// sample and stopped, with where, before anything the arm cannot do.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "arm_joints.hpp"
#include "describe.hpp"
#include "move_checks.hpp"
#include "named_planners.hpp"
#include "robotd/motion/cartesian_move.hpp"

namespace robotd::motion {
namespace {

using detail::degrees;
using detail::fixed;
using detail::number;
using kinematics::ArmJoints;
using kinematics::ArmModel;

// A line shorter and smaller than this is already there (a pose read back from the joints differs
// from them by rounding only).
constexpr double kNullTravelM = 1e-9;
constexpr double kNullTurnRad = 1e-9;
// A line stops where the Jacobian's smallest singular value falls below the threshold and below
// this fraction of its value at the line's start.
constexpr double kApproachFraction = 0.5;
// A joint too fast where the smallest singular value has fallen below this fraction of the
// largest it had on the line is near a singularity.
constexpr double kSingularFraction = 0.35;

/// The tool's line: position linear, orientation slerped, both at the same fraction s.
class ToolLine {
 public:
  ToolLine(const Eigen::Isometry3d& start, const Eigen::Isometry3d& goal)
      : start_position_(start.translation()),
        travel_(goal.translation() - start.translation()),
        start_rotation_(start.linear()),
        goal_rotation_(goal.linear()) {}

  Eigen::Isometry3d at(double s) const {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = start_rotation_.slerp(s, goal_rotation_).toRotationMatrix();
    pose.translation() = start_position_ + s * travel_;
    return pose;
  }

  double length_m() const { return travel_.norm(); }
  double turn_rad() const { return start_rotation_.angularDistance(goal_rotation_); }

  /// "42 % along the line (63.0 of 150.0 mm, 12.6 of 30.0°)".
  std::string where(double s) const {
    std::string text =
        fixed(100 * s) + " % along the line (" + fixed(1e3 * s * length_m()) + " of " + fixed(1e3 * length_m()) + " mm";
    if (turn_rad() > kNullTurnRad)
      text += ", " + fixed(degrees(s * turn_rad())) + " of " + fixed(degrees(turn_rad())) + "°";
    return text + ")";
  }

 private:
  Eigen::Vector3d start_position_;
  Eigen::Vector3d travel_;
  Eigen::Quaterniond start_rotation_;
  Eigen::Quaterniond goal_rotation_;
};

std::optional<std::string> options_problem(const LineOptions& options, const MoveTiming& timing) {
  if (timing.speed_percent || timing.acceleration_percent) {
    return std::string("a straight line takes t (or its tool speed), not v or a");
  }
  const auto positive = [](double value) { return std::isfinite(value) && value > 0; };
  if (!positive(options.linear_speed_m_s) || !positive(options.angular_speed_rad_s)) {
    return "the line's tool speed and turning speed must be positive, got " + number(options.linear_speed_m_s) +
           " m/s and " + number(options.angular_speed_rad_s) + " rad/s";
  }
  if (!std::isfinite(options.min_singular_value) || options.min_singular_value < 0) {
    return "the singularity margin must be 0 or more, got " + number(options.min_singular_value);
  }
  return std::nullopt;
}

/// Why no sample within the limits reaches `pose`: a joint past its limit (when the model's own
/// range reaches it), or out of reach or stuck at a singularity (how close the best try is to one
/// tells which).
std::string unreachable(const ArmModel& model, const Eigen::Isometry3d& pose, const ArmJoints& seed,
                        const JointLimits& limits, const kinematics::IkSolution& best) {
  // Without any joint limit (a full turn either way): does a limit stand in the way?
  kinematics::ArmJoints turn_min{};
  kinematics::ArmJoints turn_max{};
  turn_min.fill(-2 * std::numbers::pi);
  turn_max.fill(2 * std::numbers::pi);
  const kinematics::IkSolution unlimited = kinematics::inverse_kinematics(model, pose, seed, turn_min, turn_max);
  if (unlimited.converged) {
    if (auto past = detail::outside_limits(detail::to_joints(unlimited.q_rad, model.dof), limits, "would need")) {
      return *past;
    }
  }
  return "out of reach within the joint limits, or too close to a singularity (the closest is " +
         fixed(1e3 * best.position_error_m) + " mm and " + fixed(degrees(best.orientation_error_rad)) +
         "° off, where the Jacobian's smallest singular value is " +
         number(kinematics::smallest_singular_value(model, best.q_rad)) + ")";
}

/// Central differences of the positions; at rest at both ends.
std::vector<Joints> velocities_of(const std::vector<Joints>& positions, double dt_s) {
  std::vector<Joints> velocities(positions.size(), Joints(positions.front().size(), 0.0));
  for (std::size_t k = 1; k + 1 < positions.size(); ++k) {
    for (std::size_t j = 0; j < positions[k].size(); ++j) {
      velocities[k][j] = (positions[k + 1][j] - positions[k - 1][j]) / (2 * dt_s);
    }
  }
  return velocities;
}

}  // namespace

namespace detail {

Result<Trajectory> plan_line_move_as(std::string_view what, const ArmModel& model, const Joints& from,
                                     const Eigen::Isometry3d& goal, const MoveTiming& timing, const JointLimits& limits,
                                     double dt_s, const LineOptions& options) {
  const auto fail = [what](const std::string& message) {
    return Error{ErrorCode::kInvalidArgument, std::string(what) + ": " + message};
  };
  auto problem = model_problem(model, from, limits);
  if (!problem) problem = timing_problem(timing, dt_s);
  if (!problem) problem = options_problem(options, timing);
  if (!problem && !goal.matrix().allFinite()) problem = "the goal pose must be finite";
  if (problem) return fail(*problem);

  const ToolLine line(kinematics::tool_pose(model, to_arm(from)), goal);
  Shape shape = Shape::kTrapezoid;
  std::size_t count = 0;
  std::string how =
      "straight line of " + fixed(1e3 * line.length_m()) + " mm and " + fixed(degrees(line.turn_rad())) + "°, ";
  if (timing.duration_s) {
    shape = timing.shape.value_or(Shape::kPolynomial);
    count = intervals(*timing.duration_s, dt_s);
    how += shape == Shape::kPolynomial ? "quintic polynomial" : "trapezoid in thirds";
    how += " over " + number(static_cast<double>(count) * dt_s) + " s (t given)";
  } else {
    if (line.length_m() < kNullTravelM && line.turn_rad() < kNullTurnRad) {
      return Trajectory{.dt_s = dt_s,
                        .positions = {from},
                        .velocities = {Joints(from.size(), 0.0)},
                        .shape = Shape::kTrapezoid,
                        .duration_s = 0,
                        .how = "already there"};
    }
    shape = timing.shape.value_or(Shape::kTrapezoid);
    const double cruise_s =
        std::max(line.length_m() / options.linear_speed_m_s, line.turn_rad() / options.angular_speed_rad_s);
    count = intervals_covering(peak_rate_factor(shape) * cruise_s, dt_s);
    if (static_cast<double>(count) > kMaxSamples) {
      return fail("at " + number(1e3 * options.linear_speed_m_s) +
                  " mm/s the line would take more than a million samples");
    }
    how += shape == Shape::kPolynomial ? "quintic polynomial" : "trapezoid in thirds";
    how += " peaking at " + number(1e3 * options.linear_speed_m_s) + " mm/s or " +
           number(degrees(options.angular_speed_rad_s)) + "°/s, " + number(static_cast<double>(count) * dt_s) + " s";
  }
  const PathProfile profile = PathProfile::over(shape, static_cast<double>(count) * dt_s);
  const ArmJoints min_rad = to_arm(limits.min_rad);
  const ArmJoints max_rad = to_arm(limits.max_rad);

  std::vector<Joints> positions{from};
  positions.reserve(count + 1);
  ArmJoints previous = to_arm(from);
  double previous_s = 0;
  const double start_margin = kinematics::smallest_singular_value(model, previous);
  double widest_margin = start_margin;
  for (std::size_t k = 1; k <= count; ++k) {
    const double s = profile.position(static_cast<double>(k) * dt_s);
    const Eigen::Isometry3d pose = line.at(s);
    const kinematics::IkSolution solution = kinematics::inverse_kinematics(model, pose, previous, min_rad, max_rad);
    if (!solution.converged) {
      return fail("no joint solution " + line.where(s) + ": " + unreachable(model, pose, previous, limits, solution));
    }
    // The commander's rule: a line that comes close to a singularity stops there. Close: the
    // Jacobian's smallest singular value below the threshold and below half what it was where
    // the line started, so that a line may start at one and leave it (the commander's examples
    // start their Cartesian moves from MoveJoint(90, -90, 180, 0, 0, 180), a straight wrist).
    const double margin = kinematics::smallest_singular_value(model, solution.q_rad);
    if (margin < options.min_singular_value && margin < kApproachFraction * start_margin) {
      return fail("stops before a singularity " + line.where(s) + " (the Jacobian's smallest singular value there is " +
                  number(margin) + ", below " + number(options.min_singular_value) + "); it is clear up to " +
                  line.where(previous_s));
    }
    // Nearer one than that, or at the edge of the workspace, the joints speed up without bound:
    // the line stops before a joint would turn faster than its maximum, and says whether a
    // singularity is why (the singular values' scale differs from arm to arm, so relative to the
    // largest on the line).
    for (std::size_t j = 0; j < model.dof; ++j) {
      const double speed = std::abs(solution.q_rad[j] - previous[j]) / dt_s;
      if (speed <= limits.max_speed_rad_s[j] * (1 + kLimitMargin)) continue;
      const std::string turning = joint_name(j) + " would turn at " + number(speed) + " rad/s (max " +
                                  number(limits.max_speed_rad_s[j]) + ") " + line.where(s);
      if (margin < options.min_singular_value || margin < kSingularFraction * widest_margin) {
        return fail("stops before a singularity: " + turning + ", where the Jacobian's smallest singular value is " +
                    number(margin) + " (it was " + number(widest_margin) + " earlier on the line); it is clear up to " +
                    line.where(previous_s));
      }
      return fail(turning +
                  ": near the edge of the workspace, or too fast a move (a longer t would do); it is clear "
                  "up to " +
                  line.where(previous_s));
    }
    widest_margin = std::max(widest_margin, margin);
    positions.push_back(to_joints(solution.q_rad, model.dof));
    previous = solution.q_rad;
    previous_s = s;
  }
  std::vector<Joints> velocities = velocities_of(positions, dt_s);
  return Trajectory{.dt_s = dt_s,
                    .positions = std::move(positions),
                    .velocities = std::move(velocities),
                    .shape = shape,
                    .duration_s = static_cast<double>(count) * dt_s,
                    .how = std::move(how)};
}

}  // namespace detail

Result<Trajectory> plan_line_move(const ArmModel& model, const Joints& from, const Eigen::Isometry3d& goal,
                                  const MoveTiming& timing, const JointLimits& limits, double dt_s,
                                  const LineOptions& options) {
  return detail::plan_line_move_as("line move", model, from, goal, timing, limits, dt_s, options);
}

}  // namespace robotd::motion
