// Motion registers (spec §4.1, seed Part II, III): planned moves queued in the command cache,
// servo_j, and the motion limits the planning uses.
#include <algorithm>
#include <cmath>
#include <string>

#include <spdlog/spdlog.h>

#include "controller.hpp"
#include "joint_limits.hpp"

namespace robotd::xarm::sim {
namespace {

/// +∞ in a target (SDK ≥ 2.4.101) keeps that component where the move starts; NaN is no value.
Result<void> take_unspecified(double& value, double start, const std::string& name) {
  if (std::isnan(value)) return make_error(ErrorCode::kInvalidArgument, name + " is NaN");
  if (std::isinf(value)) value = start;
  return {};
}

}  // namespace

Controller::Outcome Controller::move_line(const Request& request) {
  const auto parsed = parse_line_move(request.frame.reg, request.frame.body);
  if (!parsed) return parameter_error(request, parsed.error().message);
  LineMove move = parsed.value();
  if (auto speed = check_tcp_speed(move.speed_m_s, model_); !speed)
    return parameter_error(request, speed.error().message);
  if (auto acc = check_tcp_acc(move.acc_m_s2); !acc) return parameter_error(request, acc.error().message);
  if (!can_queue()) return not_ready();
  if (!kinematics_.solves_poses()) {
    return no_solution(request, "a " + std::to_string(model_.dof) +
                                    "-joint arm cannot follow an arbitrary TCP line in robotd-xarm-sim");
  }
  const JointValues from = cache_.next_start(joints_);
  const Pose start = tcp_pose(from);
  for (std::size_t i = 0; i < 3; ++i) {
    const auto position = take_unspecified(move.pose.position_m[i], start.position_m[i], "a target coordinate");
    const auto angle = take_unspecified(move.pose.rpy_rad[i], start.rpy_rad[i], "a target angle");
    if (!position || !angle) return parameter_error(request, (position ? angle : position).error().message);
  }
  auto path = PlannedPath::tcp_line(kinematics_, tcp_offset(), from, isometry_of(move.pose));
  if (!path) return no_solution(request, path.error().message);
  return queue(request, CachedCommand{.origin = {},
                                      .path = std::move(path).value(),
                                      .speed = move.speed_m_s,
                                      .acceleration = std::min(move.acc_m_s2, config_.tcp_max_acc_m_s2),
                                      .sleep_s = 0});
}

Controller::Outcome Controller::move_joint(const Request& request) {
  const auto parsed = parse_joint_move(request.frame.body);  // move_jointb: its radius is the mvtime slot
  if (!parsed) return parameter_error(request, parsed.error().message);
  JointMove move = parsed.value();
  const JointValues from = cache_.next_start(joints_);
  for (std::size_t j = 0; j < kMaxDof; ++j) {
    if (j >= model_.dof) {
      move.joints_rad[j] = 0;  // the unused tail
    } else if (auto taken = take_unspecified(move.joints_rad[j], from[j], "joint " + std::to_string(j + 1)); !taken) {
      return parameter_error(request, taken.error().message);
    }
  }
  return queue_joint_move(request, move.joints_rad, move.speed_rad_s, move.acc_rad_s2);
}

Controller::Outcome Controller::move_gohome(const Request& request) {
  const auto parsed = parse_gohome(request.frame.body);
  if (!parsed) return parameter_error(request, parsed.error().message);
  return queue_joint_move(request, home_joints(model_), parsed.value().speed_rad_s, parsed.value().acc_rad_s2);
}

Controller::Outcome Controller::queue_joint_move(const Request& request, const JointValues& target, double speed_rad_s,
                                                 double acc_rad_s2) {
  if (auto speed = check_joint_speed(speed_rad_s); !speed) return parameter_error(request, speed.error().message);
  if (auto acc = check_joint_acc(acc_rad_s2); !acc) return parameter_error(request, acc.error().message);
  if (!can_queue()) return not_ready();
  const auto within = within_limits(target, model_);
  if (!within) {
    if (!options_.quiet) spdlog::info("{}: {}", register_name(request.frame.reg), within.error().message);
    latch_error(23);  // the seed: "If any error encountered, system will go to STOPPED state"
    return Outcome{};
  }
  return queue(request,
               CachedCommand{.origin = {},
                             .path = PlannedPath::joint_line(cache_.next_start(joints_), within.value(), model_.dof),
                             .speed = speed_rad_s,
                             .acceleration = std::min(acc_rad_s2, config_.joint_max_acc_rad_s2),
                             .sleep_s = 0});
}

Controller::Outcome Controller::sleep_instruction(const Request& request) {
  const auto parsed = parse_scalar_param(request.frame.reg, request.frame.body);
  if (!parsed) return parameter_error(request, parsed.error().message);
  if (auto valid = check_sleep(parsed.value()); !valid) return parameter_error(request, valid.error().message);
  if (!can_queue()) return not_ready();
  return queue(
      request,
      CachedCommand{.origin = {}, .path = std::nullopt, .speed = 0, .acceleration = 0, .sleep_s = parsed.value()});
}

Controller::Outcome Controller::servo_j(const Request& request) {
  const auto parsed = parse_joint_params(request.frame.reg, request.frame.body);
  if (!parsed) return parameter_error(request, parsed.error().message);
  for (std::size_t j = 0; j < model_.dof; ++j) {
    if (!std::isfinite(parsed.value()[j]))
      return parameter_error(request, "joint " + std::to_string(j + 1) + " is not a number");
  }
  if (mode_ != kModeServo || !can_move() || state_ == kStatePaused) {
    servo_.ignore();
    return Outcome{};
  }
  switch (servo_.offer(parsed.value(), advanced_ns_, model_)) {
    case ServoStream::Verdict::kAccepted:
      break;
    case ServoStream::Verdict::kBeyondLimit:
      latch_error(23);
      break;
    case ServoStream::Verdict::kTooFast:
      latch_error(24);
      break;
  }
  return Outcome{};
}

Controller::Outcome Controller::set_motion_limit(const Request& request) {
  const std::uint8_t reg = request.frame.reg;
  const auto parsed = parse_scalar_param(reg, request.frame.body);
  if (!parsed) return parameter_error(request, parsed.error().message);
  const double value = parsed.value();
  Result<void> valid;
  double* setting = nullptr;
  switch (static_cast<Register>(reg)) {
    case Register::kSetTcpJerk:
      valid = check_tcp_jerk(value);
      setting = &config_.tcp_jerk_m_s3;
      break;
    case Register::kSetTcpMaxAcc:
      valid = check_tcp_acc(value);
      setting = &config_.tcp_max_acc_m_s2;
      break;
    case Register::kSetJointJerk:
      valid = check_joint_jerk(value);
      setting = &config_.joint_jerk_rad_s3;
      break;
    default:
      valid = check_joint_acc(value);
      setting = &config_.joint_max_acc_rad_s2;
      break;
  }
  if (!valid) return parameter_error(request, valid.error().message);
  if (state_ == kStateStopped) return failed();  // seed Part III
  *setting = value;
  return Outcome{};
}

}  // namespace robotd::xarm::sim
