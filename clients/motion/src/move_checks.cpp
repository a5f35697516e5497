#include "move_checks.hpp"

#include <algorithm>
#include <cmath>

#include "describe.hpp"

namespace robotd::motion::detail {
namespace {

// Durations within this fraction of a sample of a whole number of samples count as that number.
constexpr double kSampleSlack = 1e-6;

bool positive(double value) { return std::isfinite(value) && value > 0; }
bool all_finite(const Joints& values) {
  return std::all_of(values.begin(), values.end(), [](double value) { return std::isfinite(value); });
}

std::optional<std::string> size_problem(const Joints& values, std::size_t dof, std::string_view what) {
  if (values.size() == dof) return std::nullopt;
  return std::string(what) + " has " + std::to_string(values.size()) + " values, expected one per joint (" +
         std::to_string(dof) + ")";
}

}  // namespace

std::optional<std::string> limits_problem(const JointLimits& limits, std::size_t dof) {
  if (dof == 0) return "the arm has no joints";
  for (const auto& [values, what] : {std::pair{&limits.min_rad, "min_rad"}, std::pair{&limits.max_rad, "max_rad"},
                                     std::pair{&limits.max_speed_rad_s, "max_speed_rad_s"},
                                     std::pair{&limits.max_acceleration_rad_s2, "max_acceleration_rad_s2"}}) {
    if (auto problem = size_problem(*values, dof, std::string("the joint limit ") + what)) return problem;
    if (!all_finite(*values)) return std::string("the joint limit ") + what + " must be finite";
  }
  for (std::size_t j = 0; j < dof; ++j) {
    if (!positive(limits.max_speed_rad_s[j]) || !positive(limits.max_acceleration_rad_s2[j])) {
      return joint_name(j) + "'s maximum speed and acceleration must be positive";
    }
    if (limits.min_rad[j] > limits.max_rad[j]) return joint_name(j) + "'s min_rad is above its max_rad";
  }
  return std::nullopt;
}

std::optional<std::string> joints_problem(const Joints& q, const JointLimits& limits, std::string_view what) {
  if (auto problem = size_problem(q, limits.min_rad.size(), what)) return problem;
  if (!all_finite(q)) return std::string(what) + " must be finite";
  return std::nullopt;
}

std::optional<std::string> outside_limits(const Joints& q, const JointLimits& limits, std::string_view what) {
  for (std::size_t j = 0; j < q.size(); ++j) {
    if (q[j] < limits.min_rad[j] || q[j] > limits.max_rad[j]) {
      return joint_name(j) + " " + std::string(what) + " " + number(q[j], 4) + " rad is outside its limits [" +
             number(limits.min_rad[j], 4) + ", " + number(limits.max_rad[j], 4) + "] rad";
    }
  }
  return std::nullopt;
}

std::optional<std::string> model_problem(const kinematics::ArmModel& model, const Joints& from,
                                         const JointLimits& limits) {
  if (model.dof == 0 || model.dof > kinematics::kMaxArmJoints) {
    return "the arm model " + std::string(model.name) + " has " + std::to_string(model.dof) +
           " joints, expected 1 to " + std::to_string(kinematics::kMaxArmJoints);
  }
  if (auto problem = limits_problem(limits, model.dof)) return problem;
  return joints_problem(from, limits, "the start");
}

std::optional<std::string> timing_problem(const MoveTiming& timing, double dt_s) {
  if (!positive(dt_s)) return "the sample period must be positive, got " + number(dt_s) + " s";
  if (timing.duration_s) {
    if (!positive(*timing.duration_s)) return "t must be a positive duration, got " + number(*timing.duration_s) + " s";
    if (*timing.duration_s / dt_s > kMaxSamples) {
      return "t = " + number(*timing.duration_s) + " s is more than a million samples of " + number(dt_s) + " s";
    }
  }
  const auto percent_ok = [](double percent) { return std::isfinite(percent) && percent > 0 && percent <= 100; };
  if (timing.speed_percent && !percent_ok(*timing.speed_percent)) {
    return "v must be a percentage in (0, 100], got " + number(*timing.speed_percent);
  }
  if (timing.acceleration_percent && !percent_ok(*timing.acceleration_percent)) {
    return "a must be a percentage in (0, 100], got " + number(*timing.acceleration_percent);
  }
  return std::nullopt;
}

std::size_t intervals(double duration_s, double dt_s) {
  const double count = std::ceil(duration_s / dt_s - kSampleSlack);
  return static_cast<std::size_t>(std::clamp(count, 1.0, kMaxSamples + 1));
}

std::size_t intervals_covering(double duration_s, double dt_s) {
  double count = std::max(1.0, std::ceil(duration_s / dt_s));
  if (count * dt_s < duration_s) count += 1;  // ceil of a rounded quotient can fall a hair short
  return static_cast<std::size_t>(std::min(count, kMaxSamples + 1));
}

}  // namespace robotd::motion::detail
