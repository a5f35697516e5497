#include "servo_stream.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "joint_limits.hpp"

namespace robotd::xarm::sim {

ServoStream::Verdict ServoStream::offer(const JointValues& requested, std::int64_t now_ns, const ArmModel& model) {
  const auto within = within_limits(requested, model);
  if (!within) {
    ++ignored_;
    return Verdict::kBeyondLimit;
  }
  const JointValues& target = within.value();
  if (target_) {
    const std::int64_t interval_ns = now_ns - accepted_ns_;
    const double allowed_rad =
        kMaxJointSpeedRadS * static_cast<double>(std::max(interval_ns, kMinIntervalNs)) * 1e-9 * kSpeedMargin;
    for (std::size_t j = 0; j < model.dof; ++j) {
      if (std::abs(target[j] - (*target_)[j]) > allowed_rad) {
        ++ignored_;
        return Verdict::kTooFast;
      }
    }
    max_interval_ns_ = std::max(max_interval_ns_, interval_ns);
  }
  target_ = target;
  last_target_ = target;
  accepted_ns_ = now_ns;
  ++frames_;
  return Verdict::kAccepted;
}

bool ServoStream::step(JointValues& joints, std::size_t dof, double dt_s) const {
  if (!target_) return true;
  const double reach_rad = kMaxJointSpeedRadS * dt_s;
  bool arrived = true;
  for (std::size_t j = 0; j < dof; ++j) {
    const double left = (*target_)[j] - joints[j];
    const bool reached = std::abs(left) <= reach_rad;
    // Taking the target itself (not joints + left, which can round a hair off it) leaves the
    // joint exactly on it, so drive_velocity() sees it there.
    joints[j] = reached ? (*target_)[j] : joints[j] + std::copysign(reach_rad, left);
    arrived = arrived && reached;
  }
  return arrived;
}

JointValues ServoStream::drive_velocity(const JointValues& joints, std::size_t dof) const {
  JointValues velocity{};
  if (!target_) return velocity;
  for (std::size_t j = 0; j < dof; ++j) {
    const double left = (*target_)[j] - joints[j];
    if (left != 0) velocity[j] = std::copysign(kMaxJointSpeedRadS, left);
  }
  return velocity;
}

nlohmann::json ServoStream::statistics(std::size_t dof) const {
  return {{"frames", frames_},
          {"ignored", ignored_},
          {"max_interval_us", max_interval_ns_ / 1000},
          {"last_target_rad",
           std::vector<double>(last_target_.begin(), last_target_.begin() + static_cast<std::ptrdiff_t>(dof))}};
}

}  // namespace robotd::xarm::sim
