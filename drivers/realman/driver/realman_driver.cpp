#include "driver/realman_driver.hpp"

#include <algorithm>

#include "driver/realman_ops.hpp"
#include "robotd/driver/position_targets.hpp"

namespace robotd::realman {
namespace {

constexpr auto kFeedbackPoll = std::chrono::milliseconds(2);
constexpr auto kMinimumFirstFeedbackWait = std::chrono::milliseconds(500);
constexpr auto kClearedWait = std::chrono::milliseconds(500);

std::string joint_name(std::size_t index) { return "joint" + std::to_string(index + 1); }

}  // namespace

Result<void> RealmanDriver::configure(const nlohmann::json& params) {
  auto parsed = parse_realman_params(params);
  if (!parsed) return parsed.error();
  params_ = std::move(parsed).value();
  configured_ = true;
  not_connected_fault_.set(kNotConnectedFault,
                           ("not connected to the RealMan controller at " + params_.controller.to_string()).c_str());
  return {};
}

driver::DeviceDescription RealmanDriver::describe() const {
  driver::DeviceDescription description;
  description.model = "RealMan " + std::string(params_.model.name);
  // The configured model's standard flange: a force ("-6F") version's longer one is known only
  // once the controller names itself.
  description.kinematic_model = params_.model.kinematic_model;
  description.native_rate_hz = params_.command_rate_hz;
  for (std::size_t j = 0; j < params_.model.dof; ++j) {
    description.joints.push_back(driver::JointDescription{.name = joint_name(j), .limits = params_.limits[j]});
  }
  description.has_end_pose = true;
  description.ops = op_descriptions();
  return description;
}

Result<void> RealmanDriver::connect() {
  if (!configured_) return make_error(ErrorCode::kInvalidArgument, "the realman driver was not configured");
  abort_.clear();
  const std::lock_guard lock(link_mutex_);
  return connect_locked();
}

Result<void> RealmanDriver::connect_locked() {
  connected_.store(false, std::memory_order_release);
  link_.close();
  const LinkSettings settings{
      .controller = params_.controller,
      .connect_timeout = std::chrono::milliseconds(params_.connect_timeout_ms),
      .dof = params_.model.dof,
      .push = params_.push.enabled,
      .push_local = transport::Endpoint{params_.push.ip, params_.push.port},
      .push_cycle = params_.push.cycle,
      .push_joint_speed = params_.push.joint_speed,
      .speed_unit = params_.push.speed_unit,
      .poll_period = std::chrono::milliseconds(params_.poll_period_ms),
      .feedback_timeout = std::chrono::milliseconds(params_.feedback_timeout_ms),
      .command_period = std::chrono::nanoseconds(static_cast<std::int64_t>(1e9 / params_.command_rate_hz)),
      .pass_through = params_.pass_through,
      .io_priority = params_.io_priority,
  };
  auto opened = link_.open(settings, &abort_);
  Result<void> ready = opened ? check_software() : opened;
  if (ready && params_.push.enabled) ready = start_push();
  if (ready) ready = await_feedback();
  if (!ready) {
    link_.close();
    return ready;
  }
  last_sequence_ = 0;
  rt_health_ = LinkHealth{};
  connected_.store(true, std::memory_order_release);
  return {};
}

Result<void> RealmanDriver::check_software() {
  auto reply = request(plain_request("get_arm_software_info"));
  if (!reply && reply.error().code == ErrorCode::kTimeout) {
    reply = request(plain_request("get_arm_software_version"));  // 2nd-generation controllers
  }
  if (!reply) return reply.error();
  const std::string key = reply.value().body.contains("command") ? "arm_software_info" : "arm_software_version";
  auto info = parse_software_info(Message{MessageKind::kReply, key, reply.value().body});
  if (!info) return info.error();
  product_version_ = info.value().product_version;
  controller_version_ = info.value().controller_version;
  const auto model = find_model(product_version_);
  if (!model) {
    return make_error(ErrorCode::kRefused, "the controller at " + params_.controller.to_string() + " reports \"" +
                                               product_version_ + "\", which is not a model this driver knows");
  }
  if (model->name != params_.model.name) {
    return make_error(ErrorCode::kRefused, "the controller at " + params_.controller.to_string() + " reports a " +
                                               product_version_ + " (" + std::to_string(model->dof) +
                                               " joints) but params.model is \"" + std::string(params_.model.name) +
                                               "\"; set \"model\": \"" + std::string(model->name) + "\"");
  }
  return {};
}

Result<void> RealmanDriver::start_push() {
  const transport::Endpoint& local = link_.push_endpoint();
  RealtimePushConfig push{.cycle = params_.push.cycle,
                          .enable = true,
                          .port = local.port,
                          .ip = local.host,
                          .joint_speed = params_.push.joint_speed,
                          .arm_current_status = true,
                          .hand = false};
  auto reply = request(set_realtime_push_request(push));
  if (!reply) return reply.error();
  return {};
}

Result<void> RealmanDriver::await_feedback() {
  const auto wait = std::max(kMinimumFirstFeedbackWait, std::chrono::milliseconds(params_.connect_timeout_ms));
  const auto deadline = Clock::now() + wait;
  while (Clock::now() < deadline) {
    const LinkHealth health = link_.health();
    if (health.lost) return make_error(ErrorCode::kNotAvailable, health.reason.text.data());
    if (link_.feedback().sequence > 0) return {};
    if (!abort_.sleep_for(kFeedbackPoll)) return driver::aborted_error("waiting for the first feedback");
  }
  const std::string waited = std::to_string(wait.count()) + " ms";
  if (params_.push.enabled) {
    return make_error(
        ErrorCode::kNotAvailable,
        "the controller at " + params_.controller.to_string() +
            " accepted the connection but sent no "
            "real-time push to " +
            link_.push_endpoint().to_string() + " within " + waited +
            " (does a firewall drop UDP, or is push.ip not this PC's address on the controller's network?)");
  }
  return make_error(ErrorCode::kNotAvailable, "the controller at " + params_.controller.to_string() +
                                                  " did not answer get_current_arm_state within " + waited);
}

void RealmanDriver::disconnect() noexcept {
  const std::lock_guard lock(link_mutex_);
  connected_.store(false, std::memory_order_release);
  link_.close();
}

Result<void> RealmanDriver::recover() {
  abort_.clear();
  const std::lock_guard lock(link_mutex_);
  if (!connected_.load(std::memory_order_acquire) || link_.health().lost) {
    return abort_.verdict(connect_locked(), "recover");
  }
  auto cleared = clear_errors();
  link_.restart_stream();
  return abort_.verdict(cleared, "recover");
}

Result<void> RealmanDriver::clear_errors() {
  const ArmFeedback before = link_.feedback();
  if (auto cleared = request(plain_request("clear_system_err")); !cleared) return cleared.error();
  for (std::size_t j = 0; j < params_.model.dof; ++j) {
    if (before.joint_errors[j] == 0) continue;
    if (auto cleared = request(set_joint_clear_err_request(static_cast<int>(j + 1))); !cleared) return cleared.error();
  }
  const auto deadline = Clock::now() + kClearedWait;
  ArmFeedback now = link_.feedback();
  while (Clock::now() < deadline) {
    now = link_.feedback();
    if (now.sequence > before.sequence && now.fault.code == 0) return {};
    if (!abort_.sleep_for(kFeedbackPoll)) return driver::aborted_error("waiting for the errors to clear");
  }
  return make_error(ErrorCode::kRefused, std::string("errors cleared, but ") + now.fault.text.data());
}

Result<void> RealmanDriver::reset_zero(std::span<const int> /*joints*/) {
  return make_error(
      ErrorCode::kRefused,
      "RealMan joints have absolute encoders; their zero is set with RealMan's tools, not through robotd");
}

bool RealmanDriver::link_up(driver::FaultInfo& fault) noexcept {
  if (!connected_.load(std::memory_order_acquire)) {
    fault = not_connected_fault_;
    return false;
  }
  (void)link_.try_health(rt_health_);  // the link thread mid-store: the previous health, one tick longer
  if (rt_health_.lost) fault = rt_health_.reason;
  return !rt_health_.lost;
}

driver::IoResult RealmanDriver::read(driver::Feedback& out, driver::FaultInfo& fault) noexcept {
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
                                          .effort_nm = 0};  // the controller reports currents, not torques
  }
  out.has_end_pose = rt_feedback_.has_pose;
  out.end_pose = rt_feedback_.pose;
  return driver::IoResult::kOk;
}

driver::IoResult RealmanDriver::write(const driver::CommandFrame& command, driver::FaultInfo& fault) noexcept {
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

Result<nlohmann::json> RealmanDriver::call(const std::string& op, const nlohmann::json& args) {
  const std::lock_guard lock(ops_mutex_);
  return RealmanOps(*this).call(op, args);
}

Result<ControllerLink::Reply> RealmanDriver::request(const nlohmann::json& message) {
  RequestOptions options = default_options();
  options.abort = &abort_;
  return link_.request(message, options);
}

Result<ControllerLink::Reply> RealmanDriver::request(const nlohmann::json& message, const RequestOptions& options) {
  return link_.request(message, options);
}

RequestOptions RealmanDriver::default_options() const {
  RequestOptions options;
  options.reply_timeout = std::chrono::milliseconds(params_.request_timeout_ms);
  return options;
}

}  // namespace robotd::realman
