// System registers (spec §3, §4.1; seed Part I, III): version, enable and brakes, state and mode,
// errors and warnings, configuration, servo status, motion feedback.
#include <string>
#include <string_view>

#include "controller.hpp"

namespace robotd::xarm::sim {
namespace {

constexpr int kAllJoints = 8;
constexpr int kMaxSensitivity = 5;

// Serial numbers in the controller's format: two letters for the product, four digits for the
// series (the SDK reads them: ≥ 1300 a 1300-series arm or box, 1305 … 8499 the "-1305" joint
// limits), then the unit; get_version carries their first six characters ("6,6,XI1303,AC1303,
// v2.3.0"; UFACTORY's protocol page shows "6,6,XI1202,AC1302,v1.12.10" and SNs "XI120204201B02",
// "AC130202B02L02"). XF, XI, XS are the xArm 5, 6, 7 prefixes seen in the SDK's users' logs; the
// Lite 6 and 850 ones are not public, and the unit part says this is the simulator.
constexpr std::string_view kUnit = "RBTDSIM1";
constexpr std::string_view kControlBoxSeries = "AC1303";

std::string series(const ArmModel& model) {
  const std::string_view name = model.name;
  const std::string_view digits = name.ends_with("-1305") ? "1305" : name == "uf850" ? "8500" : "1303";
  const std::string_view prefix = model.type_code == 9    ? "LI"
                                  : model.type_code == 12 ? "FX"
                                  : model.dof == 5        ? "XF"
                                  : model.dof == 7        ? "XS"
                                                          : "XI";
  return std::string(prefix) + std::string(digits);
}
std::string robot_serial(const ArmModel& model) { return series(model) + std::string(kUnit); }
std::string control_box_serial() { return std::string(kControlBoxSeries) + std::string(kUnit); }

}  // namespace

Controller::Outcome Controller::get_version(const Request& /*request*/) {
  const Version version{.axes = static_cast<int>(model_.dof),
                        .type = model_.type_code,
                        .robot_sn = series(model_),
                        .control_box_sn = std::string(kControlBoxSeries),
                        .firmware = options_.firmware};
  return answer(encode_version(version));
}

Controller::Outcome Controller::get_robot_sn(const Request& /*request*/) {
  return answer(
      encode_robot_sn(SerialNumbers{.robot_sn = robot_serial(model_), .control_box_sn = control_box_serial()}));
}

Controller::Outcome Controller::motion_enable(const Request& request) {
  const auto parsed = parse_motion_enable(request.frame.body);
  if (!parsed) return parameter_error(request, parsed.error().message);
  const JointSwitch change = parsed.value();
  if (auto valid = check_joint_selector(change.joint, model_.dof); !valid) {
    return parameter_error(request, valid.error().message);
  }
  if (change.on && estop_held_) return Outcome{};  // the e-stop cuts the motors' power
  for (std::size_t j = 0; j < model_.dof; ++j) {
    if (change.joint == kAllJoints || static_cast<std::size_t>(change.joint) == j + 1) {
      enabled_[j] = change.on;
      brake_released_[j] = change.on;  // an enabled motor holds the joint; a disabled one needs its brake
    }
  }
  reset_system();
  return Outcome{};
}

Controller::Outcome Controller::set_state(const Request& request) {
  const auto parsed = parse_u8_param(request.frame.reg, request.frame.body);
  if (!parsed) return parameter_error(request, parsed.error().message);
  switch (parsed.value()) {
    case kStateStart:
      if (error_ != 0 || !motors_ready() || slow_stopping_ || state_ == kStateMoving) break;
      if (mode_ == kModePosition && !cache_.empty()) {
        state_ = kStateMoving;
        cache_.resume();
      } else {
        state_ = kStateSleeping;
      }
      break;
    case kStatePaused:
      if (state_ == kStateMoving || state_ == kStateSleeping) {
        state_ = kStatePaused;
        cache_.brake();
        servo_.drop();
      }
      break;
    case kStateStopped:
      stop_motion();
      state_ = kStateStopped;
      break;
    case kStateSlowStop:
      if (state_ == kStateMoving && mode_ == kModePosition) {
        slow_stopping_ = true;
        cache_.brake();
      } else {
        stop_motion();
        state_ = kStateStopped;
      }
      break;
    default:
      return parameter_error(request, "state " + std::to_string(parsed.value()) + " cannot be set (0, 3, 4 or 6)");
  }
  return Outcome{};
}

Controller::Outcome Controller::get_state(const Request& /*request*/) { return answer(encode_state(state_)); }

Controller::Outcome Controller::get_cmdnum(const Request& /*request*/) {
  return answer(encode_cmdnum(static_cast<std::uint16_t>(cache_.size())));
}

Controller::Outcome Controller::get_err_code(const Request& /*request*/) {
  return answer(encode_err_code(ErrorWarning{.error = error_, .warning = warning_}));
}

Controller::Outcome Controller::clean_err(const Request& /*request*/) {
  if (estop_held_) return Outcome{};  // the button is still pressed: error 1 stays
  error_ = 0;
  servo_status_.fill(ServoStatus{});
  reset_system();
  return Outcome{};
}

Controller::Outcome Controller::clean_war(const Request& /*request*/) {
  warning_ = 0;
  return Outcome{};
}

Controller::Outcome Controller::set_brake(const Request& request) {
  const auto parsed = parse_set_brake(request.frame.body);
  if (!parsed) return parameter_error(request, parsed.error().message);
  const JointSwitch change = parsed.value();
  if (auto valid = check_joint_selector(change.joint, model_.dof); !valid) {
    return parameter_error(request, valid.error().message);
  }
  for (std::size_t j = 0; j < model_.dof; ++j) {
    if (change.joint == kAllJoints || static_cast<std::size_t>(change.joint) == j + 1) brake_released_[j] = change.on;
  }
  reset_system();
  return Outcome{};
}

Controller::Outcome Controller::set_mode(const Request& request) {
  const auto parsed = parse_u8_param(request.frame.reg, request.frame.body);
  if (!parsed) return parameter_error(request, parsed.error().message);
  const int mode = parsed.value();
  if (mode != kModePosition && mode != kModeServo && mode != kModeJointTeach) {
    return parameter_error(request, "mode " + std::to_string(mode) + " (" + mode_text(mode) +
                                        ") is not emulated by robotd-xarm-sim (0, 1 and 2 are)");
  }
  mode_ = mode;
  reset_system();
  return Outcome{};
}

Controller::Outcome Controller::set_sensitivity(const Request& request) {
  const auto parsed = parse_u8_param(request.frame.reg, request.frame.body);
  if (!parsed) return parameter_error(request, parsed.error().message);
  const bool collision = request.frame.reg == static_cast<std::uint8_t>(Register::kSetCollisionSensitivity);
  const int lowest = collision ? 0 : 1;
  const int value = parsed.value();
  if (value < lowest || value > kMaxSensitivity) {
    return parameter_error(request, "sensitivity " + std::to_string(value) + " is outside " + std::to_string(lowest) +
                                        " … " + std::to_string(kMaxSensitivity));
  }
  (collision ? config_.collision_sensitivity : config_.teach_sensitivity) = value;
  reset_system();
  return Outcome{};
}

Controller::Outcome Controller::clean_conf(const Request& /*request*/) {
  config_ = MotionConfig{};
  saved_config_.reset();
  return Outcome{};
}

Controller::Outcome Controller::save_conf(const Request& /*request*/) {
  saved_config_ = config_;
  return Outcome{};
}

Controller::Outcome Controller::servo_get_dbmsg(const Request& /*request*/) {
  return answer(encode_servo_dbmsg(servo_status_));
}

Controller::Outcome Controller::feedback_check(const Request& /*request*/) { return Outcome{}; }

Controller::Outcome Controller::set_feedback_type(const Request& request) {
  const auto parsed = parse_u8_param(request.frame.reg, request.frame.body);
  if (!parsed) return parameter_error(request, parsed.error().message);
  if ((parsed.value() & ~kFeedbackTypes) != 0) {
    return parameter_error(request, "feedback type " + std::to_string(parsed.value()) +
                                        " has bits other than 1 (started), 2 (finished), 4 (triggered), 32 and 64"
                                        " (other task started, finished)");
  }
  feedback_masks_[request.client] = static_cast<std::uint8_t>(parsed.value());
  return Outcome{};
}

Controller::Outcome Controller::get_reduced_mode(const Request& /*request*/) {
  return answer(encode_reduced_mode(reduced_mode_));
}

Controller::Outcome Controller::set_reduced_mode(const Request& request) {
  const auto parsed = parse_u8_param(request.frame.reg, request.frame.body);
  if (!parsed) return parameter_error(request, parsed.error().message);
  if (parsed.value() > 1) {
    return parameter_error(request, "reduced mode " + std::to_string(parsed.value()) + " is not 0 (off) or 1 (on)");
  }
  reduced_mode_ = parsed.value() == 1;
  return Outcome{};
}

}  // namespace robotd::xarm::sim
