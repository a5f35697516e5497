#include "arm.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace robotd::realman::sim {
namespace {

constexpr double kLimitToleranceRad = 1e-6;  // a millidegree target exactly at a limit is within it
constexpr double kStillRad = 1e-6;           // a disabled joint "moves" when its target differs more
constexpr double kVelocityFilterS = 0.01;

std::string degrees(double rad) {
  std::array<char, 32> text{};
  std::snprintf(text.data(), text.size(), "%.3f°", rad * 180.0 / std::numbers::pi);
  return text.data();
}

}  // namespace

std::string_view status_text(ArmStatus status) {
  switch (status) {
    case ArmStatus::kIdle:
      return "idle";
    case ArmStatus::kMoveJ:
      return "move_J";
    case ArmStatus::kMoveL:
      return "move_L";
    case ArmStatus::kMoveThroughJoint:
      return "move_through_joint";
    case ArmStatus::kStop:
      return "stop";
    case ArmStatus::kSlowStop:
      return "slow_stop";
    case ArmStatus::kPause:
      return "pause";
  }
  return "idle";
}

Arm::Arm(std::string product_version, const ArmModel& model, std::int64_t now_ns)
    : product_version_(std::move(product_version)),
      model_(model),
      kinematics_(ArmKinematics::for_product(product_version_, model_)),
      trajectories_([this](const Segment& segment, const JointValues& from) { return plan_path(segment, from); }),
      advanced_ns_(now_ns) {
  enabled_.fill(true);
}

JointValues Arm::target() const {
  if (auto planned = trajectories_.final_target()) return *planned;
  if (stream_target_) return *stream_target_;
  return position_;
}

std::optional<EulerPose> Arm::flange_pose() const {
  if (!kinematics_) return std::nullopt;
  return euler_pose_of(kinematics_->flange(position_));
}

ArmStatus Arm::status(std::int64_t now_ns) const {
  if (emergency_stop_) return ArmStatus::kStop;
  if (trajectories_.slowing()) return ArmStatus::kSlowStop;
  if (trajectories_.paused()) return ArmStatus::kPause;
  if (const Segment* active = trajectories_.active()) {
    return active->type == "movel" ? ArmStatus::kMoveL : ArmStatus::kMoveJ;
  }
  if (stream_target_ && now_ns - last_accepted_ns_ < kStreamingNs) return ArmStatus::kMoveThroughJoint;
  return stopped_ ? ArmStatus::kStop : ArmStatus::kIdle;
}

Result<void> Arm::check_limits(const JointValues& joints) const {
  for (std::size_t j = 0; j < dof(); ++j) {
    if (joints[j] < model_.min_rad[j] - kLimitToleranceRad || joints[j] > model_.max_rad[j] + kLimitToleranceRad) {
      return make_error(ErrorCode::kRefused, "joint " + std::to_string(j + 1) + " target " + degrees(joints[j]) +
                                                 " is outside " + degrees(model_.min_rad[j]) + " … " +
                                                 degrees(model_.max_rad[j]) + " (" + system_error_text(0x1002) + ")");
    }
  }
  return {};
}

Result<JointValues> Arm::solve(const EulerPose& pose) const {
  if (!cartesian()) {
    return make_error(ErrorCode::kRefused, "Cartesian planning is not emulated for " + product_version_);
  }
  auto joints = kinematics_->solve(isometry_of(pose), trajectories_.next_start(position_));
  if (!joints) return make_error(ErrorCode::kRefused, system_error_text(0x1003) + ": no joint solution for the pose");
  return *joints;
}

Result<void> Arm::ready_to_move() const {
  if (!powered_) return make_error(ErrorCode::kRefused, "the arm is powered off (set_arm_power with arm_power 1)");
  if (emergency_stop_) {
    return make_error(ErrorCode::kRefused, "the emergency stop is engaged (set_arm_emergency_stop false releases it)");
  }
  if (!system_errors_.empty()) {
    return make_error(ErrorCode::kRefused, "the controller is in error " + system_error_text(system_errors_.front()) +
                                               " (clear_system_err clears it)");
  }
  if (trajectories_.busy()) {
    return make_error(ErrorCode::kRefused,
                      "a trajectory is in progress (wait for its current_trajectory_state, or stop it)");
  }
  return {};
}

Result<void> Arm::check_disabled(const JointValues& to, const JointValues& from) const {
  for (std::size_t j = 0; j < dof(); ++j) {
    if (!enabled_[j] && std::abs(to[j] - from[j]) > kStillRad) {
      return make_error(ErrorCode::kRefused, "joint " + std::to_string(j + 1) + " is disabled and would have to move");
    }
  }
  return {};
}

Result<PlannedPath> Arm::plan_path(const Segment& segment, const JointValues& from) const {
  if (segment.type != "movel") {
    if (auto still = check_disabled(segment.joints, from); !still) return still.error();
    return PlannedPath::joint_line(from, segment.joints, dof(), segment.speed_percent);
  }
  if (!cartesian()) {
    return make_error(ErrorCode::kRefused, "Cartesian planning is not emulated for " + product_version_);
  }
  auto path = PlannedPath::cartesian_line(*kinematics_, from, *segment.pose, segment.speed_percent);
  if (!path) return path.error();
  if (auto still = check_disabled(path.value().end(), from); !still) return still.error();
  return path;
}

Result<void> Arm::plan(Segment segment, bool connect) {
  if (auto ready = ready_to_move(); !ready) return ready;
  if (segment.type != "movel") {  // a line's joints are solved within the limits
    if (auto within = check_limits(segment.joints); !within) return within;
  }
  auto path = plan_path(segment, trajectories_.next_start(position_));
  if (!path) return path.error();
  segment.joints = path.value().end();
  hold();
  stopped_ = false;
  trajectories_.add(std::move(segment), connect, position_, ends_);
  return {};
}

Result<Eigen::Isometry3d> Arm::next_start_flange() const {
  if (!cartesian()) {
    return make_error(ErrorCode::kRefused, "Cartesian planning is not emulated for " + product_version_);
  }
  return kinematics_->flange(next_start());
}

void Arm::malformed_frame(std::string why, std::int64_t now_ns) {
  ++counters_.frames;
  intervals_.arrived(now_ns, !stream_target_);
  reject_frame(counters_.malformed, std::move(why));
}

void Arm::reject_frame(std::uint64_t& counter, std::string why) {
  ++counter;
  counters_.last_rejection = std::move(why);
}

void Arm::pass_through(const PassThroughFrame& frame, std::int64_t now_ns) {
  ++counters_.frames;
  counters_.follow = frame.follow;
  const bool streaming = stream_target_.has_value();
  intervals_.arrived(now_ns, !streaming);
  if (auto ready = ready_to_move(); !ready) return reject_frame(counters_.refused, ready.error().message);
  if (auto within = check_limits(frame.joints); !within) return reject_frame(counters_.ignored, within.error().message);
  const JointValues& previous = streaming ? *stream_target_ : position_;
  double largest_step_rad = 0;
  std::size_t largest_joint = 0;
  for (std::size_t j = 0; j < dof(); ++j) {
    const double step = enabled_[j] ? std::abs(frame.joints[j] - previous[j]) : 0.0;
    if (step > largest_step_rad) {
      largest_step_rad = step;
      largest_joint = j;
    }
  }
  const std::string joint = "joint " + std::to_string(largest_joint + 1);
  if (largest_step_rad > kMaxFrameStepRad + kLimitToleranceRad) {
    raise_error(0x1007);
    return reject_frame(counters_.ignored, joint + " would move " + degrees(largest_step_rad) +
                                               " in one frame (at most 10°): " + system_error_text(0x1007));
  }
  // The commanded step at the rate the client streams, not at the frame's arrival interval,
  // which batching and jitter make meaningless.
  const auto period_s = intervals_.stream_period_s();
  if (streaming && period_s) {
    const double speed = largest_step_rad / *period_s;
    if (speed > kMaxFrameSpeedRadS) {
      raise_error(0x1007);
      return reject_frame(counters_.ignored, joint + " would turn at " + degrees(speed) +
                                                 "/s (at most 180°/s): " + system_error_text(0x1007));
    }
  }
  JointValues target = frame.joints;
  for (std::size_t j = 0; j < dof(); ++j) {
    if (!enabled_[j]) target[j] = position_[j];  // a disabled joint does not move
  }
  stream_target_ = target;
  stream_follow_ = frame.follow;
  last_accepted_ns_ = now_ns;
  stopped_ = false;
  ++counters_.accepted;
}

void Arm::hold() { stream_target_.reset(); }

void Arm::stop() {
  trajectories_.abort(ends_);
  hold();
  stopped_ = true;
}

void Arm::slow_stop() {
  trajectories_.slow_stop(ends_);
  hold();
  stopped_ = true;
}

void Arm::pause() { trajectories_.pause(); }

void Arm::resume() { trajectories_.resume(position_, ends_); }

Result<void> Arm::delete_current() { return trajectories_.delete_current(ends_); }

Result<void> Arm::delete_all() { return trajectories_.delete_all(ends_); }

void Arm::set_emergency_stop(bool engaged) {
  if (engaged) stop();
  emergency_stop_ = engaged;
}

Result<void> Arm::set_enabled(std::size_t joint, bool enable) {
  if (enable && !powered_) return make_error(ErrorCode::kRefused, "the arm is powered off");
  if (!enable && enabled_[joint]) {
    trajectories_.abort(ends_);  // whatever was planned counted on this joint
    if (stream_target_) (*stream_target_)[joint] = position_[joint];
  }
  enabled_[joint] = enable;
  return {};
}

void Arm::set_power(bool on) {
  if (!on) {
    trajectories_.abort(ends_);
    hold();
  }
  powered_ = on;
  for (std::size_t j = 0; j < dof(); ++j) enabled_[j] = on;
}

void Arm::raise_error(std::uint16_t code) {
  if (std::find(system_errors_.begin(), system_errors_.end(), code) == system_errors_.end()) {
    system_errors_.push_back(code);
  }
  trajectories_.abort(ends_);
  hold();
}

Result<void> Arm::teleport(const JointValues& joints) {
  if (trajectories_.busy()) return make_error(ErrorCode::kRefused, "a trajectory is in progress");
  if (auto within = check_limits(joints); !within) return within;
  position_ = joints;
  velocity_ = {};
  hold();
  return {};
}

void Arm::advance(std::int64_t now_ns) {
  const double dt_s = static_cast<double>(now_ns - advanced_ns_) * 1e-9;
  if (dt_s <= 0) return;
  advanced_ns_ = now_ns;
  const JointValues before = position_;
  if (auto on_path = trajectories_.advance(dt_s, ends_)) {
    position_ = *on_path;
  } else if (stream_target_) {
    const double approach = stream_follow_ ? 1.0 : 1.0 - std::exp(-dt_s / kLowFollowLagS);
    for (std::size_t j = 0; j < dof(); ++j) position_[j] += approach * ((*stream_target_)[j] - position_[j]);
  }
  const double smoothing = 1.0 - std::exp(-dt_s / kVelocityFilterS);
  for (std::size_t j = 0; j < dof(); ++j) {
    velocity_[j] += smoothing * ((position_[j] - before[j]) / dt_s - velocity_[j]);
  }
}

std::vector<TrajectoryEnd> Arm::take_ends() {
  std::vector<TrajectoryEnd> ends;
  ends.swap(ends_);
  return ends;
}

}  // namespace robotd::realman::sim
