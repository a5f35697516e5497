#include "driver/xarm_driver.hpp"

#include <algorithm>

#include "driver/xarm_fault.hpp"
#include "driver/xarm_ops.hpp"
#include "robotd/driver/position_targets.hpp"

namespace robotd::xarm {
namespace {

constexpr auto kFeedbackPoll = std::chrono::milliseconds(2);
constexpr auto kMinimumFirstReportWait = std::chrono::milliseconds(500);
constexpr auto kClearedWait = std::chrono::milliseconds(1000);

std::string joint_name(std::size_t index) { return "joint" + std::to_string(index + 1); }

}  // namespace

Result<void> XarmDriver::configure(const nlohmann::json& params) {
  auto parsed = parse_xarm_params(params);
  if (!parsed) return parsed.error();
  params_ = std::move(parsed).value();
  configured_ = true;
  not_connected_fault_.set(kNotConnectedFault,
                           ("not connected to the xArm control box at " + params_.controller.to_string()).c_str());
  return {};
}

driver::DeviceDescription XarmDriver::describe() const {
  driver::DeviceDescription description;
  description.model = "UFACTORY " + std::string(params_.model.display);
  description.kinematic_model = params_.model.kinematic_model;
  description.native_rate_hz = params_.servo_rate_hz;
  for (std::size_t j = 0; j < params_.model.dof; ++j) {
    description.joints.push_back(driver::JointDescription{.name = joint_name(j), .limits = params_.limits[j]});
  }
  description.has_end_pose = true;
  description.ops = op_descriptions();
  return description;
}

Result<void> XarmDriver::connect() {
  if (!configured_) return make_error(ErrorCode::kInvalidArgument, "the xarm driver was not configured");
  abort_.clear();
  const std::lock_guard lock(link_mutex_);
  return connect_locked();
}

Result<void> XarmDriver::connect_locked() {
  connected_.store(false, std::memory_order_release);
  link_.close();
  const LinkSettings settings{
      .controller = params_.controller,
      .report = transport::Endpoint{params_.controller.host, params_.report_port},
      .report_kind = params_.report_kind,
      .connect_timeout = std::chrono::milliseconds(params_.connect_timeout_ms),
      .report_timeout = std::chrono::milliseconds(params_.report_timeout_ms),
      .error_poll_period = std::chrono::milliseconds(params_.error_poll_ms),
      .servo_period = std::chrono::nanoseconds(static_cast<std::int64_t>(1e9 / params_.servo_rate_hz)),
      .dof = params_.model.dof,
      .enable_for_servo = params_.enable != EnablePolicy::kManual,
      .io_priority = params_.io_priority,
  };
  Result<void> ready = link_.open(settings, &abort_);
  if (ready) ready = await_report();
  if (ready) ready = check_version();
  if (ready && params_.enable == EnablePolicy::kOnConnect) {
    ready =
        run_steps({motion_enable_request(8, true), set_mode_request(kModePosition), set_state_request(kStateStart)});
  } else if (ready && link_.feedback().mode != kModePosition) {
    // Left in servo (or another) mode, e.g. by a robotd that died mid-session: planned moves
    // need position mode.
    ready = run_steps({set_mode_request(kModePosition), set_state_request(kStateStart)});
  }
  if (!ready) {
    link_.close();
    return ready;
  }
  last_sequence_ = 0;
  rt_health_ = LinkHealth{};
  connected_.store(true, std::memory_order_release);
  return {};
}

Result<void> XarmDriver::check_version() {
  auto reply = request(plain_request(Register::kGetVersion), &abort_);
  if (!reply) return reply.error();
  auto version = parse_version(reply.value().data);
  if (!version) return version.error();
  version_ = version.value();
  const auto model = model_for_type(version_.axes, version_.type);
  const std::string reported = std::to_string(version_.axes) + " axes, device type " + std::to_string(version_.type);
  if (!model) {
    return make_error(ErrorCode::kRefused, "the control box at " + params_.controller.to_string() + " reports " +
                                               reported + ", which is not an arm this driver knows");
  }
  if (model->name != params_.model.name) {
    return make_error(ErrorCode::kRefused, "the control box at " + params_.controller.to_string() + " reports " +
                                               reported + " (" + std::string(model->display) +
                                               ") but params.model is \"" + std::string(params_.model.name) +
                                               "\"; set \"model\": \"" + std::string(model->name) + "\"");
  }
  return {};
}

Result<void> XarmDriver::await_report() {
  const auto wait = std::max(kMinimumFirstReportWait, std::chrono::milliseconds(params_.connect_timeout_ms));
  const auto deadline = Clock::now() + wait;
  while (Clock::now() < deadline) {
    const LinkHealth health = link_.health();
    if (health.lost) return make_error(ErrorCode::kNotAvailable, health.reason.text.data());
    if (link_.feedback().sequence > 0) return {};
    if (!abort_.sleep_for(kFeedbackPoll)) return driver::aborted_error("waiting for the first report");
  }
  return make_error(ErrorCode::kNotAvailable, "the control box at " + params_.controller.to_string() + " sent no " +
                                                  std::string(report_kind_name(params_.report_kind)) +
                                                  " report on port " + std::to_string(params_.report_port) +
                                                  " within " + std::to_string(wait.count()) +
                                                  " ms (is report.port the port of report.kind?)");
}

Result<void> XarmDriver::run_steps(std::initializer_list<Request> requests) {
  for (const Request& step : requests) {
    auto reply = request(step, &abort_);
    if (!reply) return reply.error();
    if (reply.value().status.invalid) {
      return make_error(ErrorCode::kRefused, "the control box refused " + register_name(step.reg) + " as invalid");
    }
  }
  return {};
}

void XarmDriver::disconnect() noexcept {
  const std::lock_guard lock(link_mutex_);
  connected_.store(false, std::memory_order_release);
  link_.close();
}

Result<void> XarmDriver::recover() {
  abort_.clear();
  const std::lock_guard lock(link_mutex_);
  if (!connected_.load(std::memory_order_acquire) || link_.health().lost) {
    return abort_.verdict(connect_locked(), "recover");
  }
  return abort_.verdict(clear_errors_locked(), "recover");
}

Result<void> XarmDriver::clear_errors_locked() {
  const ArmFeedback before = link_.feedback();
  Result<void> cleared = run_steps({plain_request(Register::kCleanErr), plain_request(Register::kCleanWar)});
  if (cleared && params_.enable == EnablePolicy::kOnConnect) cleared = run_steps({motion_enable_request(8, true)});
  if (cleared) cleared = run_steps({set_mode_request(kModePosition), set_state_request(kStateStart)});
  link_.restart();  // reads the codes again; a streaming session re-enters servo mode
  if (!cleared) return cleared;
  const auto deadline = Clock::now() + kClearedWait;
  ArmFeedback now = link_.feedback();
  while (Clock::now() < deadline) {
    now = link_.feedback();
    if (now.sequence > before.sequence + 1 && now.fault.code == 0 && now.error_code == 0) return {};
    if (!abort_.sleep_for(kFeedbackPoll)) return driver::aborted_error("waiting for the errors to clear");
  }
  if (is_estop_error(now.error_code)) {
    return make_error(ErrorCode::kRefused, "errors cleared, but " + controller_error_text(now.error_code) +
                                               " is still active: release the e-stop first");
  }
  return make_error(ErrorCode::kRefused,
                    std::string("errors cleared, but ") +
                        (now.fault.code != 0 ? now.fault.text.data() : controller_error_text(now.error_code).c_str()));
}

Result<void> XarmDriver::reset_zero(std::span<const int> /*joints*/) {
  return make_error(ErrorCode::kRefused,
                    "xArm joints have absolute encoders; their zero is set with UFACTORY's tools, not through robotd");
}

bool XarmDriver::link_up(driver::FaultInfo& fault) noexcept {
  if (!connected_.load(std::memory_order_acquire)) {
    fault = not_connected_fault_;
    return false;
  }
  (void)link_.try_health(rt_health_);  // the link thread mid-store: the previous health, one tick longer
  if (rt_health_.lost) fault = rt_health_.reason;
  return !rt_health_.lost;
}

driver::IoResult XarmDriver::read(driver::Feedback& out, driver::FaultInfo& fault) noexcept {
  if (!link_up(fault)) return driver::IoResult::kDisconnected;
  // The link thread mid-store (the RT thread may have preempted it): no new data this tick, and
  // write() keeps the previous feedback.
  if (!link_.try_feedback(rt_feedback_)) return driver::IoResult::kNoNewData;
  if (rt_feedback_.sequence == last_sequence_) return driver::IoResult::kNoNewData;
  last_sequence_ = rt_feedback_.sequence;
  const std::size_t dof = params_.model.dof;
  out.joint_count = dof;
  for (std::size_t j = 0; j < dof; ++j) {
    out.joints[j] = driver::JointFeedback{.position_rad = rt_feedback_.position_rad[j],
                                          .velocity_rad_s = rt_feedback_.velocity_rad_s[j],
                                          .effort_nm = rt_feedback_.effort[j]};
  }
  out.has_end_pose = true;
  out.end_pose = rt_feedback_.pose;
  out.estop_input = is_estop_error(rt_feedback_.error_code);
  return driver::IoResult::kOk;
}

driver::IoResult XarmDriver::write(const driver::CommandFrame& command, driver::FaultInfo& fault) noexcept {
  if (!link_up(fault)) return driver::IoResult::kDisconnected;
  StreamTarget target;
  target.estop = command.estop;
  target.active = driver::position_targets(command, params_.model.dof, rt_feedback_.position_rad, target.joints_rad);
  link_.publish_target(target);
  session_streaming_.store(target.active, std::memory_order_relaxed);
  if (rt_feedback_.fault.code != 0) {
    fault = rt_feedback_.fault;
    return driver::IoResult::kFault;
  }
  return driver::IoResult::kOk;
}

Result<nlohmann::json> XarmDriver::call(const std::string& op, const nlohmann::json& args) {
  const std::lock_guard lock(ops_mutex_);
  return XarmOps(*this).call(op, args);
}

Result<Reply> XarmDriver::request(const Request& request, const driver::AbortFlag* abort) {
  return link_.request(request, std::chrono::milliseconds(params_.request_timeout_ms), abort);
}

}  // namespace robotd::xarm
