#include "device/device.hpp"

#include <algorithm>
#include <sstream>

#include <spdlog/spdlog.h>

#include "control/limit_narrowing.hpp"
#include "rt/monotonic_clock.hpp"

namespace robotd::device {

std::uint64_t state_every_ticks(const config::DeviceConfig& config) {
  if (config.joint_state_rate_hz <= 0) return 1;
  const int every = (config.rate_hz + config.joint_state_rate_hz / 2) / config.joint_state_rate_hz;  // the nearest
  return static_cast<std::uint64_t>(std::max(1, every));
}
namespace {

Error invalid(std::string message) { return make_error(ErrorCode::kInvalidArgument, std::move(message)); }

// Applies one override, refusing to widen what the driver declares.
Result<void> narrow(double& limit, const std::optional<double>& requested, bool upper, const std::string& path,
                    const char* key) {
  if (!requested) return {};
  const bool widens = upper ? *requested > limit : *requested < limit;
  if (widens) {
    std::ostringstream text;
    text << path << "." << key << ": " << *requested << " is beyond the driver's limit " << limit
         << " (overrides may only narrow a limit)";
    return invalid(text.str());
  }
  limit = *requested;
  return {};
}

}  // namespace

Device::Device(config::DeviceConfig config, std::unique_ptr<plugin::LoadedDriver> plugin)
    : config_(std::move(config)), plugin_(std::move(plugin)), channel_(std::make_unique<DeviceChannel>()) {}

Device::~Device() { stop(); }

Result<void> Device::configure() {
  driver::Driver& drv = plugin_->driver();
  if (auto configured = drv.configure(config_.params); !configured) {
    return invalid(config_.path + ".params: " + configured.error().message);
  }
  const driver::DeviceDescription description = drv.describe();
  if (description.joints.empty() || description.joints.size() > driver::kMaxJoints) {
    return invalid(config_.path + ": driver '" + config_.driver + "' describes " +
                   std::to_string(description.joints.size()) + " joints (expected 1.." +
                   std::to_string(driver::kMaxJoints) + ")");
  }
  model_.name = config_.name;
  model_.driver = config_.driver;
  model_.driver_version = plugin_->version();
  model_.model = description.model;
  model_.kinematic_model = description.kinematic_model;
  model_.rate_hz = config_.rate_hz;
  model_.native_rate_hz = description.native_rate_hz;
  model_.supports_torque = description.supports_torque;
  model_.behaviors = control::BehaviorSupport{description.supports_damping, description.supports_zero_torque};
  model_.has_imu = description.has_imu;
  model_.has_end_pose = description.has_end_pose;
  model_.limit_policy = config_.limit_policy;
  model_.ops = description.ops;
  model_.read_only_reason = description.read_only_reason;
  for (const auto& joint : description.joints) {
    model_.joint_names.push_back(joint.name);
    model_.limits.push_back(joint.limits);
    model_.default_kp.push_back(joint.default_kp);
    model_.default_kd.push_back(joint.default_kd);
    model_.zero_position_rad.push_back(joint.zero_position_rad);
  }
  for (const auto& override_limits : config_.joint_limits) {
    const auto it = std::find(model_.joint_names.begin(), model_.joint_names.end(), override_limits.joint);
    if (it == model_.joint_names.end()) {
      std::string known;
      for (const auto& name : model_.joint_names) known += (known.empty() ? "" : ", ") + name;
      return invalid(override_limits.path + ": device has no joint '" + override_limits.joint + "' (joints: " + known +
                     ")");
    }
    driver::JointLimits& limits = model_.limits[static_cast<std::size_t>(it - model_.joint_names.begin())];
    const auto& o = override_limits;
    for (auto result :
         {narrow(limits.position_min_rad, o.position_min_rad, false, o.path, "position_min_rad"),
          narrow(limits.position_max_rad, o.position_max_rad, true, o.path, "position_max_rad"),
          narrow(limits.velocity_max_rad_s, o.velocity_max_rad_s, true, o.path, "velocity_max_rad_s"),
          narrow(limits.acceleration_max_rad_s2, o.acceleration_max_rad_s2, true, o.path, "acceleration_max_rad_s2"),
          narrow(limits.effort_max_nm, o.effort_max_nm, true, o.path, "effort_max_nm"),
          narrow(limits.kp_max, o.kp_max, true, o.path, "kp_max"),
          narrow(limits.kd_max, o.kd_max, true, o.path, "kd_max")}) {
      if (!result) return result;
    }
    if (limits.position_min_rad >= limits.position_max_rad) {
      return invalid(o.path + ": position_min_rad must be below position_max_rad");
    }
  }
  const std::lock_guard lock(limits_mutex_);
  limits_ = std::make_shared<const std::vector<driver::JointLimits>>(model_.limits);
  return {};
}

Result<void> Device::start(LoopRunner runner) {
  if (auto connected = plugin_->driver().connect(); !connected) {
    // A device that is just not there yet (powered later, a simulator started after robotd)
    // starts as a lost link and is connected by the reconnector once it answers.
    const bool retry = connected.error().code == ErrorCode::kNotAvailable && config_.reconnect_interval_ms > 0;
    if (!retry) {
      return make_error(connected.error().code,
                        "device '" + config_.name + "' (" + config_.driver + "): " + connected.error().message);
    }
    spdlog::warn("device '{}' ({}): not reachable yet: {}; starting it as a lost link and retrying every {} ms",
                 config_.name, config_.driver, connected.error().message, config_.reconnect_interval_ms);
  }
  narrow_to_described();
  connected_ = true;  // from here on the driver is ours to disconnect, whether or not it is connected now

  LoopSettings settings;
  settings.rate_hz = config_.rate_hz;
  settings.feedback_timeout_ns = static_cast<std::int64_t>(config_.feedback_timeout_ms) * rt::kNsPerMs;
  settings.safe_behavior = control::applied_behavior(config_.safe_behavior, model_.behaviors);
  settings.shutdown_behavior = control::applied_behavior(config_.shutdown_behavior, model_.behaviors);
  settings.shutdown_duration_ns = static_cast<std::int64_t>(config_.shutdown_ms) * rt::kNsPerMs;
  settings.warmup_ticks = static_cast<std::uint64_t>(config_.rate_hz) / 2;
  settings.state_every_ticks = state_every_ticks(config_);

  const rt::ThreadSettings thread_settings{"rt-" + config_.name, config_.realtime, config_.rt_priority, config_.cpu};
  // The loop is built on this thread (it may allocate); the RT thread only runs it.
  loop_ = std::make_unique<ControlLoop>(plugin_->driver(), model_, *channel_, settings);
  runner_ = runner;
  if (runner == LoopRunner::kCaller) return {};
  ControlLoop* loop = loop_.get();
  auto started = rt::start_thread(thread_, thread_settings, [loop] { loop->run(); });
  if (!started) {
    plugin_->driver().disconnect();
    connected_ = false;
    return make_error(started.error().code, "device '" + config_.name + "': " + started.error().message);
  }
  thread_start_ = started.value();
  return {};
}

void Device::request_stop() { channel_->shutdown_requested.store(true, std::memory_order_release); }

void Device::stop() {
  if (thread_.joinable()) {
    request_stop();
    thread_.join();
  }
  if (connected_) {
    plugin_->driver().disconnect();
    connected_ = false;
  }
}

Result<void> Device::run_maintenance(const std::function<Result<void>(driver::Driver&)>& work, bool clears_fault,
                                     std::chrono::milliseconds timeout) {
  const std::lock_guard lock(maintenance_mutex_);
  channel_->maintenance_declined.store(false, std::memory_order_release);
  channel_->maintenance_requested.store(true, std::memory_order_release);
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!channel_->maintenance_active.load(std::memory_order_acquire)) {
    const bool declined = channel_->maintenance_declined.exchange(false, std::memory_order_acq_rel);
    if (declined || std::chrono::steady_clock::now() > deadline || !running()) {
      channel_->maintenance_requested.store(false, std::memory_order_release);
      if (declined) return make_error(ErrorCode::kRefused, preempted_by());
      return make_error(ErrorCode::kTimeout, "device '" + config_.name + "': the loop did not pause for maintenance");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  Result<void> result = work(plugin_->driver());
  if (result) narrow_to_described();  // a reconnect may have read narrower limits from the device
  // The loop asks the driver to abort maintenance while an e-stop or a shutdown waits.
  const bool preempted =
      channel_->estop.load(std::memory_order_acquire) || channel_->shutdown_requested.load(std::memory_order_acquire);
  if (!result && preempted) result = make_error(ErrorCode::kRefused, "aborted: " + preempted_by());
  channel_->maintenance_clears_fault.store(result.ok() && clears_fault, std::memory_order_release);
  channel_->maintenance_requested.store(false, std::memory_order_release);
  while (channel_->maintenance_active.load(std::memory_order_acquire) && running()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return result;
}

std::shared_ptr<const std::vector<driver::JointLimits>> Device::limits() const {
  const std::lock_guard lock(limits_mutex_);
  return limits_;
}

Result<void> Device::narrow_limits(std::span<const driver::JointLimits> reported, std::string_view source) {
  const std::lock_guard lock(limits_mutex_);
  std::vector<driver::JointLimits> next = *limits_;
  auto changes = control::narrow_limits(next, reported, model_.joint_names);
  if (!changes) {
    return make_error(changes.error().code, "device '" + config_.name + "': " + changes.error().message);
  }
  if (changes.value().empty()) return {};
  for (const control::LimitChange& change : changes.value()) {
    spdlog::warn("device '{}': joint '{}' {} narrowed from {} to {} by {}", model_.name,
                 model_.joint_names[change.joint], change.key, change.from, change.to, source);
  }
  limits_ = std::make_shared<const std::vector<driver::JointLimits>>(std::move(next));
  publish_limits_locked();
  return {};
}

void Device::narrow_to_described() {
  std::vector<driver::JointLimits> reported;
  for (const auto& joint : plugin_->driver().describe().joints) reported.push_back(joint.limits);
  if (auto narrowed = narrow_limits(reported, "the limits the device reports"); !narrowed) {
    spdlog::warn("{}", narrowed.error().message);
  }
}

void Device::publish_limits_locked() {
  LimitSet& out = channel_->limits.write_buffer();
  for (std::size_t j = 0; j < limits_->size(); ++j) out.joints[j] = motion_limits((*limits_)[j]);
  channel_->limits.publish();
}

std::string Device::preempted_by() const {
  return channel_->shutdown_requested.load(std::memory_order_acquire)
             ? "robotd is shutting down"
             : "the e-stop of '" + config_.name + "' is engaged; reset it first";
}

void Device::set_estop_note(std::string note) {
  const std::lock_guard lock(note_mutex_);
  estop_note_ = std::move(note);
}

std::string Device::estop_note() const {
  const std::lock_guard lock(note_mutex_);
  return estop_note_;
}

}  // namespace robotd::device
