// The commander's move timing (MoveJoint / MovePose / MoveCart): a path parameter s(t) that goes
// from 0 at rest to 1 at rest, trapezoidal (roboticstoolbox `trapezoidal`: with only a duration,
// 1/3 accelerating, 1/3 cruising, 1/3 decelerating) or quintic (`quintic` / `jtraj`, zero speed
// and acceleration at both ends), sampled every dt. Joint moves scale one s(t) per joint so all
// arrive together; Cartesian moves run it along a line and a slerp, solved by IK per sample.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "ik_solver.hpp"
#include "parol6_kinematics.hpp"

namespace robotd::parol6 {
namespace {

// Peak ds/dt · T and peak d²s/dt² · T² of the two shapes over a duration T.
constexpr double kThirdsPeakRate = 1.5;                         // trapezoid, ramps of T/3
constexpr double kThirdsPeakAcceleration = 4.5;                 // 1.5 / (T/3)
constexpr double kQuinticPeakRate = 1.875;                      // s = 10τ³ − 15τ⁴ + 6τ⁵ at τ = 1/2
constexpr double kQuinticPeakAcceleration = 5.773502691896258;  // 10/√3, at τ = (3 − √3)/6

// Without a duration, a Cartesian move turns the tool at most this fast (the commander's
// Cartesian angular maximum, 25°/s).
constexpr double kCartesianAngularSpeedRadS = 25.0 * std::numbers::pi / 180.0;

// A Cartesian move shorter and smaller than this is already there (a pose read back from the
// joints differs from them by rounding only).
constexpr double kNullTravelM = 1e-9;
constexpr double kNullTurnRad = 1e-9;

// A limit is exceeded only beyond this relative margin: a move planned exactly at a limit stays valid.
constexpr double kLimitMargin = 1e-9;
// Durations within this fraction of a whole number of samples count as that number.
constexpr double kSampleSlack = 1e-6;
constexpr double kMaxSamples = 1e6;  // 10⁴ s at 10 ms: more is a unit mistake, not a move

/// s(t) over [0, duration]: 0 → 1, at rest at both ends.
class PathProfile {
 public:
  static PathProfile trapezoid(double duration_s, double ramp_s) {
    return PathProfile(Profile::kTrapezoid, duration_s, ramp_s);
  }
  static PathProfile polynomial(double duration_s) { return PathProfile(Profile::kPolynomial, duration_s, 0.0); }

  double at(double t_s) const {
    if (t_s <= 0) return 0.0;
    if (t_s >= duration_s_) return 1.0;
    if (shape_ == Profile::kPolynomial) {
      const double tau = t_s / duration_s_;
      return tau * tau * tau * (10.0 + tau * (-15.0 + 6.0 * tau));
    }
    const double rate = peak_rate();
    const double acceleration = rate / ramp_s_;
    if (t_s < ramp_s_) return 0.5 * acceleration * t_s * t_s;
    if (t_s <= duration_s_ - ramp_s_) return 0.5 * rate * ramp_s_ + rate * (t_s - ramp_s_);
    const double left = duration_s_ - t_s;
    return 1.0 - 0.5 * acceleration * left * left;
  }

  double duration_s() const { return duration_s_; }
  double peak_rate() const {  // 1/s
    return shape_ == Profile::kPolynomial ? kQuinticPeakRate / duration_s_ : 1.0 / (duration_s_ - ramp_s_);
  }
  double peak_acceleration() const {  // 1/s²
    return shape_ == Profile::kPolynomial ? kQuinticPeakAcceleration / (duration_s_ * duration_s_)
                                          : peak_rate() / ramp_s_;
  }

 private:
  PathProfile(Profile shape, double duration_s, double ramp_s)
      : shape_(shape), duration_s_(duration_s), ramp_s_(ramp_s) {}

  Profile shape_;
  double duration_s_;
  double ramp_s_;  // trapezoid: time to reach the cruise rate, ≤ duration / 2
};

/// The profile of `shape` over `duration_s` with the commander's thirds for a trapezoid.
PathProfile profile_over(Profile shape, double duration_s) {
  return shape == Profile::kPolynomial ? PathProfile::polynomial(duration_s)
                                       : PathProfile::trapezoid(duration_s, duration_s / 3.0);
}

double peak_rate_factor(Profile shape) { return shape == Profile::kPolynomial ? kQuinticPeakRate : kThirdsPeakRate; }
double peak_acceleration_factor(Profile shape) {
  return shape == Profile::kPolynomial ? kQuinticPeakAcceleration : kThirdsPeakAcceleration;
}

/// How many intervals of dt make up a requested duration, rounded up (a duration a hair over a
/// whole number of samples is that number): at least one, at most kMaxSamples + 1 (which callers
/// refuse).
std::size_t intervals(double duration_s, double dt_s) {
  const double count = std::ceil(duration_s / dt_s - kSampleSlack);
  return static_cast<std::size_t>(std::clamp(count, 1.0, kMaxSamples + 1));
}

/// The fewest intervals of dt that last at least `duration_s`, for a duration that a limit sets.
std::size_t intervals_covering(double duration_s, double dt_s) {
  double count = std::max(1.0, std::ceil(duration_s / dt_s));
  if (count * dt_s < duration_s) count += 1;
  return static_cast<std::size_t>(std::min(count, kMaxSamples + 1));
}

bool positive(double value) { return std::isfinite(value) && value > 0; }
bool all_finite(const JointVector& values) {
  return std::all_of(values.begin(), values.end(), [](double value) { return std::isfinite(value); });
}
bool all_positive(const JointVector& values) { return std::all_of(values.begin(), values.end(), positive); }

/// The arguments every plan shares; an empty string when they are usable.
std::string timing_problem(const MoveTiming& timing, double dt_s) {
  if (!positive(dt_s)) return "the sample period must be positive";
  if (timing.duration_s) {
    if (!positive(*timing.duration_s)) return "the duration must be positive";
    if (*timing.duration_s / dt_s > kMaxSamples) return "the duration is longer than a million samples";
  }
  return {};
}

std::vector<JointVector> fail(std::string& error, const std::string& message) {
  error = message;
  return {};
}

/// Samples of `profile` every dt from `from` to `to`, both ends exact.
std::vector<JointVector> sample_joint_path(const JointVector& from, const JointVector& to, const PathProfile& profile,
                                           std::size_t count, double dt_s) {
  std::vector<JointVector> samples;
  samples.reserve(count + 1);
  for (std::size_t k = 0; k < count; ++k) {
    const double s = profile.at(static_cast<double>(k) * dt_s);
    JointVector q{};
    for (std::size_t j = 0; j < q.size(); ++j) q[j] = from[j] + (to[j] - from[j]) * s;
    samples.push_back(q);
  }
  samples.push_back(to);
  return samples;
}

/// A profile and the number of dt intervals it lasts.
struct Timeline {
  PathProfile profile;
  std::size_t count;
};

/// The shortest duration of `shape` in which every joint keeps to its speed and acceleration
/// (`speed`, `acceleration`), for the distances `distance`. A trapezoid's ramp comes with it:
/// with c = T − ramp, each joint needs c ≥ d/v and c·ramp ≥ d/a; T = c + ramp is least at
/// c = max(max d/v, √(max d/a)), ramp = (max d/a) / c (a triangle when the ramp equals c).
/// The duration is then rounded up to whole samples, which only lowers the rates.
Timeline fastest_timeline(Profile shape, const JointVector& distance, const JointVector& speed,
                          const JointVector& acceleration, double dt_s) {
  double cruise_s = 0;      // max d/v
  double ramp_area_s2 = 0;  // max d/a
  for (std::size_t j = 0; j < distance.size(); ++j) {
    cruise_s = std::max(cruise_s, distance[j] / speed[j]);
    ramp_area_s2 = std::max(ramp_area_s2, distance[j] / acceleration[j]);
  }
  if (shape == Profile::kPolynomial) {
    const double duration = std::max(kQuinticPeakRate * cruise_s, std::sqrt(kQuinticPeakAcceleration * ramp_area_s2));
    const std::size_t count = intervals_covering(duration, dt_s);
    return {.profile = PathProfile::polynomial(static_cast<double>(count) * dt_s), .count = count};
  }
  const double c = std::max(cruise_s, std::sqrt(ramp_area_s2));
  const double ramp = ramp_area_s2 / c;
  const std::size_t count = intervals_covering(c + ramp, dt_s);
  return {.profile = PathProfile::trapezoid(static_cast<double>(count) * dt_s, ramp), .count = count};
}

std::string joint_name(std::size_t j) { return "J" + std::to_string(j + 1); }

/// Where on a path sample k lies, for error messages: "sample 57 of 200 (28% of the path)".
std::string where(std::size_t k, std::size_t count, double s) {
  std::ostringstream text;
  text.setf(std::ios::fixed);
  text.precision(0);
  text << "sample " << k << " of " << count << " (" << 100.0 * s << "% of the path)";
  return text.str();
}

}  // namespace

std::vector<JointVector> plan_joint_move(const JointVector& from, const JointVector& to, const MoveTiming& timing,
                                         const JointVector& max_speed, const JointVector& max_acceleration, double dt_s,
                                         std::string& error) {
  error.clear();
  if (const std::string problem = timing_problem(timing, dt_s); !problem.empty()) {
    return fail(error, "joint move: " + problem);
  }
  if (!all_finite(from) || !all_finite(to)) return fail(error, "joint move: the joint positions must be finite");
  if (!all_positive(max_speed) || !all_positive(max_acceleration)) {
    return fail(error, "joint move: the speed and acceleration limits must be positive");
  }
  JointVector distance{};
  for (std::size_t j = 0; j < distance.size(); ++j) distance[j] = std::abs(to[j] - from[j]);
  const bool moves = std::any_of(distance.begin(), distance.end(), [](double d) { return d > 0; });

  if (timing.duration_s) {
    const std::size_t count = intervals(*timing.duration_s, dt_s);
    const PathProfile profile = profile_over(timing.profile, static_cast<double>(count) * dt_s);
    // The joint that needs the longest duration names the problem, with what would do.
    double needed_s = 0;
    std::size_t worst = 0;
    for (std::size_t j = 0; j < distance.size(); ++j) {
      const double joint_needs =
          std::max(peak_rate_factor(timing.profile) * distance[j] / max_speed[j],
                   std::sqrt(peak_acceleration_factor(timing.profile) * distance[j] / max_acceleration[j]));
      if (joint_needs > needed_s) {
        needed_s = joint_needs;
        worst = j;
      }
    }
    if (needed_s > profile.duration_s() * (1 + kLimitMargin)) {
      std::ostringstream text;
      text.precision(3);
      text << "joint move: " << joint_name(worst) << " would reach " << distance[worst] * profile.peak_rate()
           << " rad/s and " << distance[worst] * profile.peak_acceleration() << " rad/s² (max " << max_speed[worst]
           << " rad/s, " << max_acceleration[worst] << " rad/s²) in " << profile.duration_s()
           << " s; this move needs at least " << needed_s << " s";
      return fail(error, text.str());
    }
    return sample_joint_path(from, to, profile, count, dt_s);
  }

  const auto fraction_ok = [](double f) { return std::isfinite(f) && f > 0 && f <= 1; };
  if (!fraction_ok(timing.speed_fraction) || !fraction_ok(timing.acceleration_fraction)) {
    return fail(error, "joint move: the speed and acceleration fractions must be in (0, 1]");
  }
  if (!moves) return {from};
  JointVector speed{};
  JointVector acceleration{};
  for (std::size_t j = 0; j < speed.size(); ++j) {
    speed[j] = timing.speed_fraction * max_speed[j];
    acceleration[j] = timing.acceleration_fraction * max_acceleration[j];
  }
  const Timeline timeline = fastest_timeline(timing.profile, distance, speed, acceleration, dt_s);
  if (static_cast<double>(timeline.count) > kMaxSamples) {
    return fail(error, "joint move: the move would take more than a million samples");
  }
  return sample_joint_path(from, to, timeline.profile, timeline.count, dt_s);
}

std::vector<JointVector> plan_cartesian_move(const JointVector& from, const Pose& target, const MoveTiming& timing,
                                             const JointVector& min_rad, const JointVector& max_rad,
                                             const JointVector& max_speed, double linear_speed_m_s, double dt_s,
                                             std::string& error) {
  error.clear();
  if (const std::string problem = timing_problem(timing, dt_s); !problem.empty()) {
    return fail(error, "Cartesian move: " + problem);
  }
  const std::array<double, 6> target_values{target.x_m,      target.y_m,       target.z_m,
                                            target.roll_rad, target.pitch_rad, target.yaw_rad};
  if (!all_finite(from) || !all_finite(target_values) || !all_finite(min_rad) || !all_finite(max_rad)) {
    return fail(error, "Cartesian move: the joint positions, limits and target must be finite");
  }
  if (!all_positive(max_speed)) return fail(error, "Cartesian move: the speed limits must be positive");

  const Eigen::Isometry3d start = tool_transform(from);
  const Eigen::Isometry3d goal = transform_of(target);
  const Eigen::Vector3d start_position = start.translation();
  const Eigen::Vector3d travel = goal.translation() - start_position;
  const Eigen::Quaterniond start_rotation(start.linear());
  const Eigen::Quaterniond goal_rotation(goal.linear());

  double duration_s = 0;
  if (timing.duration_s) {
    duration_s = *timing.duration_s;
  } else {
    if (!positive(linear_speed_m_s)) return fail(error, "Cartesian move: the linear speed must be positive");
    const double turn_rad = start_rotation.angularDistance(goal_rotation);
    if (travel.norm() < kNullTravelM && turn_rad < kNullTurnRad) return {from};
    const double cruise_s = std::max(travel.norm() / linear_speed_m_s, turn_rad / kCartesianAngularSpeedRadS);
    duration_s = peak_rate_factor(timing.profile) * cruise_s;
    if (duration_s / dt_s > kMaxSamples) {
      return fail(error, "Cartesian move: the move would take more than a million samples");
    }
  }
  // A requested duration is kept (to the sample); one from the speed is rounded up, never down.
  const std::size_t count = timing.duration_s ? intervals(duration_s, dt_s) : intervals_covering(duration_s, dt_s);
  const PathProfile profile = profile_over(timing.profile, static_cast<double>(count) * dt_s);

  std::vector<JointVector> samples;
  samples.reserve(count + 1);
  samples.push_back(from);
  for (std::size_t k = 1; k <= count; ++k) {
    const double s = profile.at(static_cast<double>(k) * dt_s);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = start_rotation.slerp(s, goal_rotation).toRotationMatrix();
    pose.translation() = start_position + s * travel;
    const IkResult solution = detail::solve_ik(pose, samples.back(), min_rad, max_rad);
    if (!solution.converged) {
      std::ostringstream text;
      text.precision(3);
      text << "Cartesian move: no joint solution at " << where(k, count, s) << ", best "
           << solution.position_error_m * 1e3 << " mm and " << solution.orientation_error_rad
           << " rad away: out of reach or past a joint limit";
      return fail(error, text.str());
    }
    for (std::size_t j = 0; j < solution.q_rad.size(); ++j) {
      const double speed = std::abs(solution.q_rad[j] - samples.back()[j]) / dt_s;
      if (speed > max_speed[j] * (1 + kLimitMargin)) {
        std::ostringstream text;
        text.precision(3);
        text << "Cartesian move: " << joint_name(j) << " would turn at " << speed << " rad/s (max " << max_speed[j]
             << ") at " << where(k, count, s)
             << ": too close to a singularity or the edge of the workspace, or the move is too fast";
        return fail(error, text.str());
      }
    }
    samples.push_back(solution.q_rad);
  }
  return samples;
}

}  // namespace robotd::parol6
