#include "controller.hpp"

#include <cmath>

#include <spdlog/spdlog.h>

#include "joint_limits.hpp"

namespace robotd::xarm::sim {
namespace {

constexpr double kVelocityFilterS = 0.01;
/// The joint torques reported: a viscous 2 N·m per rad/s of the joint's speed (0 when disabled).
constexpr double kTorquePerRadS = 2.0;
constexpr int kFirstServoError = 10;
constexpr int kLastServoError = 17;
/// Straight down in the base frame, what the SDK assumes until a report says otherwise (a floor
/// mount): set_gravity_dir (51) is not emulated.
constexpr std::array<double, 3> kGravityDirection{0, 0, -1};

bool disables_motors(int error) {
  return is_estop_error(error) || (error >= kFirstServoError && error <= kLastServoError);
}

/// The data the getters of §4.2 this simulator does not emulate answer, in bytes (0 for the
/// others): check_verify 3, get_report_tau_or_i 5, get_tcp_rotation_radius 6,
/// get_allow_approx_motion 7, get_reduced_state 53 (the long form the SDK reads from firmware
/// 1.2.11 on), get_joint_tau 55, get_dh_params 67, get_movement 69.
std::size_t getter_reply_bytes(std::uint8_t reg) {
  static const std::map<std::uint8_t, std::size_t> sizes = {{3, 1},   {5, 1},   {6, 4},    {7, 4},
                                                            {53, 79}, {55, 28}, {67, 112}, {69, 1}};
  const auto found = sizes.find(reg);
  return found == sizes.end() ? 0 : found->second;
}

std::uint8_t bit_mask(const std::array<bool, kMaxDof>& bits, std::size_t dof) {
  std::uint8_t mask = 0;
  for (std::size_t j = 0; j < dof; ++j) {
    if (bits[j]) mask = static_cast<std::uint8_t>(mask | (1U << j));
  }
  return mask;
}

}  // namespace

Controller::Controller(const SimOptions& options, const ArmModel& model, std::int64_t now_ns)
    : options_(options),
      model_(model),
      kinematics_(ArmKinematics::for_model(model)),
      joints_(home_joints(model)),
      started_ns_(now_ns),
      advanced_ns_(now_ns) {}

const std::map<std::uint8_t, Controller::Handler>& Controller::handlers() {
  using C = Controller;
  static const std::map<std::uint8_t, Handler> table = {
      {number(Register::kGetVersion), &C::get_version},
      {number(Register::kGetRobotSn), &C::get_robot_sn},
      {number(Register::kMotionEnable), &C::motion_enable},
      {number(Register::kSetState), &C::set_state},
      {number(Register::kGetState), &C::get_state},
      {number(Register::kGetCmdnum), &C::get_cmdnum},
      {number(Register::kGetErrCode), &C::get_err_code},
      {number(Register::kCleanErr), &C::clean_err},
      {number(Register::kCleanWar), &C::clean_war},
      {number(Register::kSetBrake), &C::set_brake},
      {number(Register::kSetMode), &C::set_mode},
      {number(Register::kMoveLine), &C::move_line},
      {number(Register::kMoveLineB), &C::move_line},
      {number(Register::kMoveJoint), &C::move_joint},
      {number(Register::kMoveJointB), &C::move_joint},
      {number(Register::kMoveGohome), &C::move_gohome},
      {number(Register::kSleepInstruction), &C::sleep_instruction},
      {number(Register::kServoJ), &C::servo_j},
      {number(Register::kSetTcpJerk), &C::set_motion_limit},
      {number(Register::kSetTcpMaxAcc), &C::set_motion_limit},
      {number(Register::kSetJointJerk), &C::set_motion_limit},
      {number(Register::kSetJointMaxAcc), &C::set_motion_limit},
      {number(Register::kSetTcpOffset), &C::set_tcp_offset},
      {number(Register::kSetLoadParam), &C::set_load_param},
      {number(Register::kSetCollisionSensitivity), &C::set_sensitivity},
      {number(Register::kSetTeachSensitivity), &C::set_sensitivity},
      {number(Register::kCleanConf), &C::clean_conf},
      {number(Register::kSaveConf), &C::save_conf},
      {number(Register::kGetTcpPose), &C::get_tcp_pose},
      {number(Register::kGetJointPos), &C::get_joint_pos},
      {number(Register::kGetIk), &C::get_ik},
      {number(Register::kGetFk), &C::get_fk},
      {number(Register::kIsJointLimit), &C::is_joint_limit},
      {number(Register::kGetReducedMode), &C::get_reduced_mode},
      {number(Register::kSetReducedMode), &C::set_reduced_mode},
      {number(Register::kServoGetDbmsg), &C::servo_get_dbmsg},
      {number(Register::kToolModbus), &C::tool_modbus},
      {number(Register::kToolGpioError), &C::tool_gpio_error},
      {number(Register::kToolWrite16), &C::tool_write},
      {number(Register::kToolRead16), &C::tool_read},
      {number(Register::kToolWrite32), &C::tool_write},
      {number(Register::kToolRead32), &C::tool_read},
      {number(Register::kFeedbackCheck), &C::feedback_check},
      {number(Register::kSetFeedbackType), &C::set_feedback_type},
  };
  return table;
}

Frame Controller::handle(const Frame& request, ClientId client) {
  const std::string name = register_name(request.reg);
  ++command_counts_[name];
  command_last_ns_[name] = advanced_ns_;  // its arrival (advance() came first)
  if (request.protocol != kProtocolPrivate && request.protocol != kProtocolKeepAlive) {
    if (!options_.quiet) {
      spdlog::info("{}: protocol id {} is not the private protocol (2 or 3)", register_name(request.reg),
                   request.protocol);
    }
    return reply_frame(request.transaction_id, request.protocol, request.reg, status_byte(true, false));
  }
  const Request context{.frame = request, .client = client};
  const auto handler = handlers().find(request.reg);
  Outcome outcome = handler == handlers().end() ? not_emulated(context) : (this->*handler->second)(context);
  // Registers answered "state + count" (§4.1) carry the count whatever happened.
  const bool counted = is_queued_motion(request.reg) || (request.reg >= number(Register::kSetTcpJerk) &&
                                                         request.reg <= number(Register::kSetJointMaxAcc));
  if (counted && outcome.data.empty()) outcome.data = encode_cmdnum(static_cast<std::uint16_t>(cache_.size()));
  return reply_frame(request.transaction_id, request.protocol, request.reg,
                     status_byte(outcome.invalid, outcome.refused), outcome.data);
}

std::uint8_t Controller::status_byte(bool invalid, bool refused) const {
  return encode_status(StatusBits{
      .invalid = invalid, .not_ready = refused || !can_move(), .warning = warning_ != 0, .error = error_ != 0});
}

bool Controller::motors_ready() const {
  for (std::size_t j = 0; j < model_.dof; ++j) {
    if (!enabled_[j] || !brake_released_[j]) return false;
  }
  return true;
}

bool Controller::can_move() const {
  return error_ == 0 && state_ != kStateStopped && state_ != kStateReset && motors_ready();
}

bool Controller::can_queue() const { return mode_ == kModePosition && can_move() && !slow_stopping_; }

Controller::Outcome Controller::parameter_error(const Request& request, const std::string& why) {
  warning_ = 12;
  if (!options_.quiet) spdlog::info("{}: {} (W12)", register_name(request.frame.reg), why);
  return failed();
}

Controller::Outcome Controller::not_emulated(const Request& request) {
  warning_ = 13;
  if (!options_.quiet) {
    spdlog::info("{} is not emulated by robotd-xarm-sim (W13)", register_name(request.frame.reg));
  }
  Outcome outcome = failed();
  outcome.data.assign(getter_reply_bytes(request.frame.reg), 0);
  return outcome;
}

Controller::Outcome Controller::no_solution(const Request& request, const std::string& why) {
  warning_ = 14;
  if (!options_.quiet) spdlog::info("{}: {} (W14)", register_name(request.frame.reg), why);
  return failed();
}

void Controller::stop_motion() {
  std::vector<CacheEvent> events;
  cache_.clear(events);
  emit_feedback(events);
  servo_.drop();
  slow_stopping_ = false;
}

void Controller::reset_system() {
  stop_motion();
  state_ = error_ != 0 ? kStateStopped : kStateReset;
}

void Controller::emit_feedback(const std::vector<CacheEvent>& events) {
  const auto controller_time_us = static_cast<std::uint64_t>((advanced_ns_ - started_ns_) / 1000);
  for (const CacheEvent& event : events) {
    if ((event.origin.feedback_types & event.type) == 0) continue;
    const MotionFeedback feedback{.transaction_id = event.origin.transaction_id,
                                  .type = event.type,
                                  .command_reg = event.origin.reg,
                                  .task_id = event.origin.task_id,
                                  .code = event.code,
                                  .controller_time_us = controller_time_us};
    feedback_.push_back(
        Feedback{.client = event.origin.client, .frame = motion_feedback_frame(feedback, event.origin.protocol)});
  }
}

std::vector<Feedback> Controller::take_feedback() {
  std::vector<Feedback> feedback;
  feedback.swap(feedback_);
  return feedback;
}

Controller::Outcome Controller::queue(const Request& request, CachedCommand command) {
  if (cache_.full()) {
    warning_ = 11;
    if (!options_.quiet) spdlog::info("{}: the command cache is full (W11)", register_name(request.frame.reg));
    return failed();
  }
  command.origin = CommandOrigin{.client = request.client,
                                 .transaction_id = request.frame.transaction_id,
                                 .protocol = request.frame.protocol,
                                 .reg = request.frame.reg,
                                 .task_id = next_task_id_,
                                 .feedback_types = feedback_masks_[request.client]};
  next_task_id_ = static_cast<std::uint16_t>(next_task_id_ == 0xFFFF ? 1 : next_task_id_ + 1);
  cache_.push(std::move(command));
  if (state_ == kStateSleeping) {
    state_ = kStateMoving;
    cache_.resume();
  }
  return answer(encode_cmdnum(static_cast<std::uint16_t>(cache_.size())));
}

void Controller::advance(std::int64_t now_ns) {
  const double dt_s = static_cast<double>(now_ns - advanced_ns_) * 1e-9;
  if (dt_s <= 0) return;
  advanced_ns_ = now_ns;
  gripper_.advance(dt_s);
  const JointValues before = joints_;
  if (mode_ == kModePosition && (state_ == kStateMoving || state_ == kStatePaused)) {
    std::vector<CacheEvent> events;
    if (auto on_path = cache_.advance(dt_s, events)) joints_ = *on_path;
    emit_feedback(events);
    if (slow_stopping_ && cache_.at_rest()) {
      stop_motion();
      state_ = kStateStopped;
    } else if (state_ == kStateMoving && cache_.empty()) {
      state_ = kStateSleeping;
    }
  } else if (mode_ == kModeServo && (state_ == kStateMoving || state_ == kStateSleeping) && servo_.active()) {
    state_ = servo_.step(joints_, model_.dof, dt_s) ? kStateSleeping : kStateMoving;
  }
  const double smoothing = 1.0 - std::exp(-dt_s / kVelocityFilterS);
  for (std::size_t j = 0; j < model_.dof; ++j) {
    velocity_[j] += smoothing * ((joints_[j] - before[j]) / dt_s - velocity_[j]);
  }
}

Pose Controller::tcp_pose(const JointValues& joints) const { return pose_of(kinematics_.tcp(joints, tcp_offset())); }

JointValues Controller::joint_efforts() const {
  JointValues efforts{};
  for (std::size_t j = 0; j < model_.dof; ++j) efforts[j] = enabled_[j] ? kTorquePerRadS * velocity_[j] : 0.0;
  return efforts;
}

Report Controller::report(std::int64_t now_ns) const {
  Report report;
  report.state = state_;
  report.mode = mode_;
  report.cmd_num = static_cast<std::uint16_t>(cache_.size());
  report.position_rad = joints_;
  report.has_velocity = true;
  report.velocity_rad_s = velocity_;
  report.effort = joint_efforts();
  report.tcp_pose = tcp_pose(joints_);
  report.has_codes = true;
  report.error_code = error_;
  report.warning_code = warning_;
  report.brake_mask = bit_mask(brake_released_, model_.dof);
  report.enable_mask = bit_mask(enabled_, model_.dof);
  report.has_settings = true;
  report.tcp_offset = config_.tcp_offset;
  report.payload_kg = config_.payload_kg;
  report.payload_centre_m = config_.payload_centre_m;
  report.collision_sensitivity = config_.collision_sensitivity;
  report.teach_sensitivity = config_.teach_sensitivity;
  report.has_gravity_direction = true;
  report.gravity_direction = kGravityDirection;
  report.has_timestamp = true;
  report.timestamp_us = static_cast<std::uint64_t>((now_ns - started_ns_) / 1000);
  report.has_force_torque = options_.report_force_torque;  // no sensor is simulated: zeros
  report.has_rich = true;
  report.rich = rich_fields();
  report.has_targets = true;
  if (const auto& servo_target = servo_.target()) {
    report.target_position_rad = *servo_target;
    report.target_velocity_rad_s = servo_.drive_velocity(joints_, model_.dof);
  } else {
    // Planned moves put the joints on their profile (no tracking error): its target is where
    // they are. With nothing in progress they hold there at rest.
    report.target_position_rad = joints_;
    report.target_velocity_rad_s = cache_.velocity();
  }
  return report;
}

RichFields Controller::rich_fields() const {
  // The minimum accelerations and speeds the SDK assumes until a report says otherwise; the
  // maximum ones are the limits set (or the codec's ranges); rotation limits are not modelled.
  constexpr double kMinTcpAccM_S2 = 0.001;
  constexpr double kMinTcpSpeedM_S = 0.0001;
  constexpr double kMinJointAccRad_S2 = 0.01;
  constexpr double kMinJointSpeedRad_S = 0.0001;
  RichFields fields;
  fields.device_type = model_.type_code;
  fields.axes = static_cast<int>(model_.dof);
  fields.firmware = options_.firmware;
  fields.tcp = MotionLimits{.jerk = config_.tcp_jerk_m_s3,
                            .min_acc = kMinTcpAccM_S2,
                            .max_acc = config_.tcp_max_acc_m_s2,
                            .min_speed = kMinTcpSpeedM_S,
                            .max_speed = model_.max_tcp_speed_m_s};
  fields.joint = MotionLimits{.jerk = config_.joint_jerk_rad_s3,
                              .min_acc = kMinJointAccRad_S2,
                              .max_acc = config_.joint_max_acc_rad_s2,
                              .min_speed = kMinJointSpeedRad_S,
                              .max_speed = kMaxJointSpeedRadS};
  std::copy(servo_status_.begin(), servo_status_.end(), fields.servos.begin());
  return fields;
}

void Controller::latch_error(int code) {
  error_ = code;
  if (code == 0) return;
  stop_motion();
  state_ = kStateStopped;
  if (disables_motors(code)) {
    enabled_.fill(false);
    brake_released_.fill(false);
  }
  if (!options_.quiet) spdlog::info("error {}", controller_error_text(code));
}

void Controller::set_servo_error(std::size_t slot, int code) {
  servo_status_[slot] = ServoStatus{.state = code == 0 ? 0 : 1, .error = code};
  if (code != 0 && slot < model_.dof) latch_error(kFirstServoError + 1 + static_cast<int>(slot));
}

void Controller::set_estop(bool pressed) {
  estop_held_ = pressed;
  if (pressed) latch_error(1);
}

Result<void> Controller::set_joints(const JointValues& joints) {
  if (!cache_.empty()) return make_error(ErrorCode::kRefused, "the command cache holds commands");
  const auto within = within_limits(joints, model_);
  if (!within) return within.error();
  joints_ = within.value();
  velocity_ = {};
  servo_.drop();
  return {};
}

nlohmann::json Controller::state() const {
  const auto first = [this](const auto& values) {
    return std::vector(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(model_.dof));
  };
  const Pose& offset = config_.tcp_offset;
  return {{"ok", true},
          {"model", model_.name},
          {"dof", model_.dof},
          {"state", state_},
          {"mode", mode_},
          {"error", error_},
          {"warning", warning_},
          {"gripper", gripper_.state()},
          {"estop_held", estop_held_},
          {"reduced_mode", reduced_mode_},
          {"enabled", first(enabled_)},
          {"brakes_released", first(brake_released_)},
          {"joints_rad", first(joints_)},
          {"velocity_rad_s", first(velocity_)},
          {"tcp_pose", {{"position_m", tcp_pose(joints_).position_m}, {"rpy_rad", tcp_pose(joints_).rpy_rad}}},
          {"cmdnum", cache_.size()},
          {"tcp_offset",
           {offset.position_m[0], offset.position_m[1], offset.position_m[2], offset.rpy_rad[0], offset.rpy_rad[1],
            offset.rpy_rad[2]}},
          {"payload", {{"mass_kg", config_.payload_kg}, {"centre_m", config_.payload_centre_m}}},
          {"limits",
           {{"tcp_jerk_m_s3", config_.tcp_jerk_m_s3},
            {"tcp_max_acc_m_s2", config_.tcp_max_acc_m_s2},
            {"joint_jerk_rad_s3", config_.joint_jerk_rad_s3},
            {"joint_max_acc_rad_s2", config_.joint_max_acc_rad_s2}}},
          {"collision_sensitivity", config_.collision_sensitivity},
          {"teach_sensitivity", config_.teach_sensitivity},
          {"saved_conf", saved_config_.has_value()},
          {"commands", command_counts_},
          {"commands_last_ns", command_last_ns_},
          {"servo", servo_.statistics(model_.dof)}};
}

}  // namespace robotd::xarm::sim
