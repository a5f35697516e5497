#include "robotd/motion/sampled_trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace robotd::motion {
namespace {

Error invalid(const std::string& message) { return make_error(ErrorCode::kInvalidArgument, message); }

std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

std::string sample_problem(const std::vector<std::vector<double>>& samples, const char* what, std::size_t joint_count) {
  for (std::size_t k = 0; k < samples.size(); ++k) {
    if (samples[k].size() != joint_count) {
      return std::string(what) + "[" + std::to_string(k) + "] has " + std::to_string(samples[k].size()) +
             " values: expected " + std::to_string(joint_count) + ", one per joint of the session";
    }
    for (std::size_t j = 0; j < joint_count; ++j) {
      if (!std::isfinite(samples[k][j])) {
        return std::string(what) + "[" + std::to_string(k) + "][" + std::to_string(j) + "] is " +
               number_text(samples[k][j]) + ": expected a finite number";
      }
    }
  }
  return "";
}

// a + (b − a)·fraction, per joint.
std::vector<double> interpolate(const std::vector<double>& a, const std::vector<double>& b, double fraction) {
  std::vector<double> out(a.size());
  for (std::size_t j = 0; j < a.size(); ++j) out[j] = a[j] + (b[j] - a[j]) * fraction;
  return out;
}

}  // namespace

Result<void> check_trajectory(const SampledTrajectory& trajectory, std::size_t joint_count) {
  if (!(trajectory.dt_s > 0) || !std::isfinite(trajectory.dt_s)) {
    return invalid("trajectory dt_s is " + number_text(trajectory.dt_s) + ": expected a step > 0 s");
  }
  if (trajectory.positions.empty()) return invalid("the trajectory has no samples: expected at least one");
  if (trajectory.velocities.size() != trajectory.positions.size()) {
    return invalid("the trajectory has " + std::to_string(trajectory.positions.size()) + " position samples and " +
                   std::to_string(trajectory.velocities.size()) + " velocity samples: expected as many of each");
  }
  if (std::string problem = sample_problem(trajectory.positions, "positions", joint_count); !problem.empty()) {
    return invalid(problem);
  }
  if (std::string problem = sample_problem(trajectory.velocities, "velocities", joint_count); !problem.empty()) {
    return invalid(problem);
  }
  return {};
}

SampledTrajectory resample(const SampledTrajectory& trajectory, double period_s) {
  SampledTrajectory out;
  out.dt_s = period_s;
  const double duration = trajectory.duration_s();
  const auto last = trajectory.positions.size() - 1;
  // Steps of period_s, then one to the end unless the last step lands on it (to a rounding error).
  const auto steps = static_cast<std::size_t>(std::ceil(duration / period_s - 1e-9));
  for (std::size_t k = 0; k <= steps; ++k) {
    const double time = std::min(static_cast<double>(k) * period_s, duration);
    const double index = time / trajectory.dt_s;
    const auto before = std::min(static_cast<std::size_t>(std::floor(index)), last);
    const auto after = std::min(before + 1, last);
    const double fraction = before == after ? 0 : index - static_cast<double>(before);
    out.positions.push_back(interpolate(trajectory.positions[before], trajectory.positions[after], fraction));
    out.velocities.push_back(interpolate(trajectory.velocities[before], trajectory.velocities[after], fraction));
  }
  return out;
}

}  // namespace robotd::motion
