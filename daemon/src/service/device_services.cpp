#include "service/device_services.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <string_view>
#include <thread>

#include <spdlog/spdlog.h>

#include "app/log_text.hpp"
#include "rt/monotonic_clock.hpp"
#include "service/call_arguments.hpp"

namespace robotd::service {
namespace {

constexpr double kZeroTolerance_rad = 0.1;  // PI Plus: zeroing succeeded when every motor reads within 0.1 rad
// How long /estop waits for each device's loop to confirm it wrote the e-stop frame: a few
// ticks, and the time an e-stop takes to pre-empt maintenance.
constexpr auto kEstopConfirmation = std::chrono::milliseconds(50);

DeviceCallResponse call_failed(std::string message) { return DeviceCallResponse{false, std::move(message), ""}; }

// Holds a device's maintenance reservation (SessionService::reserve_for_maintenance) for a scope.
class MaintenanceReservation {
 public:
  MaintenanceReservation(SessionService& sessions, std::size_t device) : sessions_(sessions), device_(device) {}
  MaintenanceReservation(const MaintenanceReservation&) = delete;
  MaintenanceReservation& operator=(const MaintenanceReservation&) = delete;
  ~MaintenanceReservation() { sessions_.end_maintenance(device_); }

 private:
  SessionService& sessions_;
  std::size_t device_;
};

}  // namespace

DeviceServices::DeviceServices(std::vector<device::Device*> devices, std::vector<device::BlackBox*> black_boxes,
                               std::vector<DeviceObserver*> observers, SessionService& sessions)
    : devices_(std::move(devices)),
      black_boxes_(std::move(black_boxes)),
      sessions_(sessions),
      observers_(std::move(observers)) {
  for (std::size_t i = 0; i < devices_.size(); ++i) call_mutexes_.push_back(std::make_unique<std::mutex>());
}

std::vector<std::string> DeviceServices::daemon_ops() {
  return {
      "recover: clear a latched fault (calls the driver's recover); joints then hold where they are. On a RUNNING "
      "device it is refused while a session holds a motor. Args: {}",
      "blackbox: the recent ticks (state, command, timing) kept by the loop. Args: {\"fresh\": bool} — "
      "false (default) returns the capture made at the last fault, true captures now",
      "loop_timing: wake latency, execution time and period over the statistics window (p50, p99, p99.9, max "
      "in µs), ticks, overruns, /joint_states published. Args: {\"samples\": bool (every sample in ns), "
      "\"reset\": bool (empty the window after reading)}"};
}

ListDevicesResponse DeviceServices::list_devices(const ListDevicesRequest& /*request*/) const {
  ListDevicesResponse response;
  for (const device::Device* device : devices_) {
    const control::DeviceModel& model = device->model();
    DeviceInfo info;
    info.name = model.name;
    info.driver = model.driver;
    info.driver_version = model.driver_version;
    info.model = model.model;
    info.kinematic_model = model.kinematic_model;
    info.rate_hz = model.rate_hz;
    info.native_rate_hz = model.native_rate_hz;
    info.joint_names = model.joint_names;
    for (const auto& limits : *device->limits()) {
      info.position_min.push_back(limits.position_min_rad);
      info.position_max.push_back(limits.position_max_rad);
      info.velocity_max.push_back(limits.velocity_max_rad_s);
      info.acceleration_max.push_back(limits.acceleration_max_rad_s2);
      info.effort_max.push_back(limits.effort_max_nm);
    }
    for (const ControlMode mode : model.control_modes()) info.control_modes.emplace_back(to_string(mode));
    for (const Behavior behavior : {Behavior::kKeep, Behavior::kDamping, Behavior::kZeroTorque}) {
      info.behavior_map.push_back(static_cast<std::int32_t>(control::applied_behavior(behavior, model.behaviors)));
    }
    for (const auto& op : model.ops) {
      info.ops.push_back(op.name + ": " + op.help + (op.needs_free_motors ? std::string(kNeedsFreeMotorsMark) : ""));
    }
    for (const auto& op : daemon_ops()) info.ops.push_back(op);
    info.state = device->channel().device_state.load(std::memory_order_acquire);
    response.devices.push_back(std::move(info));
  }
  return response;
}

EstopResponse DeviceServices::estop(const EstopRequest& request) {
  std::vector<std::size_t> targets;
  if (request.device.empty()) {
    for (std::size_t i = 0; i < devices_.size(); ++i) targets.push_back(i);
  } else {
    auto index = sessions_.resolve_device(request.device);
    if (!index) return EstopResponse{false, index.error().message};
    targets.push_back(index.value());
  }
  // Client text reaches the log and DeviceStatus.state_text bounded and escaped.
  const std::string who = request.node_name.empty() ? "(unnamed)" : app::log_text(request.node_name);
  const std::string reason = app::log_text(request.reason);
  if (!request.engage) {
    for (const std::size_t i : targets) {
      if (devices_[i]->channel().estop_input_pressed.load(std::memory_order_acquire)) {
        return EstopResponse{false, "cannot reset the e-stop of '" + devices_[i]->model().name +
                                        "': its own e-stop input is still pressed; release the button first"};
      }
    }
    std::string names;
    for (const std::size_t i : targets) {
      names += (names.empty() ? "'" : ", '") + devices_[i]->model().name + "'";
      devices_[i]->channel().estop.store(false, std::memory_order_release);
      devices_[i]->set_estop_note("");
    }
    const std::string message = "e-stop reset on " + names + " by '" + who + "'";
    spdlog::info("{}", message);
    return EstopResponse{true, message};
  }

  const std::int64_t engaged_ns = rt::monotonic_now_ns();
  std::vector<bool> already(targets.size());
  for (std::size_t t = 0; t < targets.size(); ++t) {
    device::Device& device = *devices_[targets[t]];
    device.set_estop_note("engaged by '" + who + "'" + (reason.empty() ? "" : ": " + reason));
    already[t] = device.channel().estop.exchange(true, std::memory_order_acq_rel);
  }
  // The e-stop is latched now; say whether each device has been reached (its loop wrote the
  // e-stop frame), waiting a few ticks for it, and why not where it has not.
  const auto deadline = std::chrono::steady_clock::now() + kEstopConfirmation;
  std::string reached;
  std::string unreached;
  for (std::size_t t = 0; t < targets.size(); ++t) {
    device::Device& device = *devices_[targets[t]];
    std::int64_t at_ns = 0;
    while ((at_ns = device.channel().estop_reached_ns.load(std::memory_order_acquire)) == 0 &&
           std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    const std::string& name = device.model().name;
    if (at_ns != 0) {
      std::ostringstream text;
      text.precision(2);
      text << std::fixed << "'" << name << "' ";
      if (already[t]) {
        text << "(already engaged)";
      } else {
        text << "in " << static_cast<double>(std::max<std::int64_t>(at_ns - engaged_ns, 0)) / 1e6 << " ms";
      }
      reached += reached.empty() ? "" : ", ";
      reached += text.str();
    } else {
      const device::LoopState state = observers_[targets[t]]->latest();
      const std::string why = state.state == DeviceState::kFault ? "FAULT: " + std::string(state.fault.text.data())
                                                                 : std::string(to_string(state.state));
      unreached.append(unreached.empty() ? "'" : "; '").append(name).append("' (").append(why).append(")");
    }
  }
  std::string message = "e-stop engaged by '" + who + "'";
  if (!reached.empty()) message += "; reached " + reached;
  if (!unreached.empty()) {
    message +=
        "; NOT confirmed on " + unreached + ": robotd cannot reach it now and keeps sending the e-stop every tick";
  }
  spdlog::warn("{}{}", message, reason.empty() ? "" : " (" + reason + ")");
  return EstopResponse{true, message};
}

bool DeviceServices::wait_for_state(std::size_t device, std::uint64_t after_tick, std::chrono::milliseconds timeout,
                                    device::LoopState& out) const {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    out = observers_[device]->latest();
    if (out.tick > after_tick && out.state == DeviceState::kRunning) return true;
    if (out.state == DeviceState::kStopped) return false;  // robotd is shutting down: it never will
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return false;
}

ResetZeroResponse DeviceServices::reset_zero(const ResetZeroRequest& request) {
  auto index = sessions_.resolve_device(request.device);
  if (!index) return ResetZeroResponse{false, index.error().message};
  device::Device& device = *devices_[index.value()];
  const control::DeviceModel& model = device.model();
  const std::int32_t requested_timeout_ms = request.timeout_ms == 0 ? 10'000 : request.timeout_ms;
  if (requested_timeout_ms < 100 || requested_timeout_ms > 60'000) {
    return ResetZeroResponse{false, "timeout_ms " + std::to_string(request.timeout_ms) + " is outside 100..60000"};
  }
  // Reserved from here on: no session can be granted between this check and the zeroing.
  if (auto reserved = sessions_.reserve_for_maintenance(index.value(), "reset_zero"); !reserved) {
    return ResetZeroResponse{false, reserved.error().message};
  }
  std::optional<MaintenanceReservation> reservation;
  reservation.emplace(sessions_, index.value());
  const DeviceState state = device.channel().device_state.load(std::memory_order_acquire);
  if (state != DeviceState::kRunning) {
    return ResetZeroResponse{
        false, "device '" + model.name + "' is " + std::string(to_string(state)) + "; reset_zero needs it RUNNING"};
  }
  const std::int32_t timeout_ms = requested_timeout_ms;
  std::vector<int> joints;
  for (const auto id : request.motor_ids) {
    if (id < 0 || static_cast<std::size_t>(id) >= model.joint_count()) {
      return ResetZeroResponse{false, "motor id " + std::to_string(id) + " does not exist on '" + model.name + "'"};
    }
    joints.push_back(id);
  }
  if (joints.empty()) {
    for (std::size_t j = 0; j < model.joint_count(); ++j) joints.push_back(static_cast<int>(j));
  }

  const auto timeout = std::chrono::milliseconds(timeout_ms);
  spdlog::info("device '{}': reset_zero of {} motor(s)", model.name, joints.size());
  auto zeroed =
      device.run_maintenance([&](driver::Driver& driver) { return driver.reset_zero(joints); }, false, timeout);
  reservation.reset();  // the loop has the driver again: sessions may be granted
  if (!zeroed) return ResetZeroResponse{false, "reset_zero on '" + model.name + "' failed: " + zeroed.error().message};

  device::LoopState after;
  if (!wait_for_state(index.value(), observers_[index.value()]->latest().tick, timeout, after)) {
    return ResetZeroResponse{false, "device '" + model.name + "' gave no feedback within " +
                                        std::to_string(timeout_ms) + " ms after zeroing"};
  }
  std::ostringstream off;
  for (const int joint : joints) {
    const auto j = static_cast<std::size_t>(joint);
    const double position = after.feedback.joints[j].position_rad;
    if (std::fabs(position - model.zero_position_rad[j]) > kZeroTolerance_rad)
      off << " " << model.joint_names[j] << "=" << position;
  }
  if (!off.str().empty()) {
    return ResetZeroResponse{false, "zeroing did not take: motors not within " + std::to_string(kZeroTolerance_rad) +
                                        " rad of zero:" + off.str()};
  }
  return ResetZeroResponse{true, "zeroed " + std::to_string(joints.size()) + " motor(s) of '" + model.name +
                                     "'; every one reads within 0.1 rad of zero"};
}

DeviceCallResponse DeviceServices::device_call(const DeviceCallRequest& request) {
  auto index = sessions_.resolve_device(request.device);
  if (!index) return call_failed(index.error().message);
  const auto parsed = parse_call_arguments(request.args_json);
  if (!parsed) return call_failed(parsed.error().message);
  const nlohmann::json& args = parsed.value();
  for (const auto& op : daemon_ops()) {
    if (op.substr(0, op.find(':')) == request.op) return daemon_op(index.value(), request.op, args);
  }
  device::Device& device = *devices_[index.value()];
  const auto& ops = device.model().ops;
  const auto described = std::find_if(ops.begin(), ops.end(), [&](const auto& op) { return op.name == request.op; });
  // An op that acts on the joints themselves waits for nobody to hold them, and keeps new
  // sessions off while it runs.
  std::optional<MaintenanceReservation> reservation;
  if (described != ops.end() && described->needs_free_motors) {
    if (auto reserved = sessions_.reserve_for_maintenance(index.value(), request.op); !reserved) {
      return call_failed("'" + device.model().name + "' " + request.op + ": " + reserved.error().message);
    }
    reservation.emplace(sessions_, index.value());
  }
  const std::lock_guard lock(*call_mutexes_[index.value()]);
  auto result = device.driver().call(request.op, args);
  if (!result) return call_failed("'" + device.model().name + "' " + request.op + ": " + result.error().message);
  device.narrow_to_described();  // an op may have narrowed the driver's limits (piper sdk_joint_limit)
  // A plugin's text that is not UTF-8 would make dump() throw and end robotd: replace it.
  return DeviceCallResponse{true, "ok", result.value().dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)};
}

DeviceCallResponse DeviceServices::daemon_op(std::size_t index, const std::string& op, const nlohmann::json& args) {
  device::Device& device = *devices_[index];
  const std::string& name = device.model().name;
  if (op == "recover") {
    if (!args.empty()) return call_failed("recover takes no arguments, got " + args.dump());
    if (device.channel().estop.load(std::memory_order_acquire)) {
      return call_failed("'" + name + "' is e-stopped: reset the e-stop first (an e-stop pre-empts maintenance)");
    }
    // On a RUNNING device, recover re-initialises the driver under live motors: refused while
    // a session holds any of them, and no session may start while it runs.
    std::optional<MaintenanceReservation> reservation;
    if (device.channel().device_state.load(std::memory_order_acquire) == DeviceState::kRunning) {
      if (auto reserved = sessions_.reserve_for_maintenance(index, "recover"); !reserved) {
        return call_failed("'" + name + "' is RUNNING; " + reserved.error().message);
      }
      reservation.emplace(sessions_, index);
    }
    spdlog::info("device '{}': recover requested", name);
    auto recovered =
        device.run_maintenance([](driver::Driver& driver) { return driver.recover(); }, true, std::chrono::seconds(10));
    reservation.reset();  // the loop has the driver again: sessions may be granted
    if (!recovered) return call_failed("recover of '" + name + "' failed: " + recovered.error().message);
    device::LoopState state;
    if (!wait_for_state(index, observers_[index]->latest().tick, std::chrono::seconds(2), state)) {
      return call_failed("'" + name + "' recovered but is not RUNNING: " + std::string(to_string(state.state)) + " " +
                         state.fault.text.data());
    }
    spdlog::info("device '{}': recovered; joints hold where they are", name);
    return DeviceCallResponse{true, "recovered; joints hold where they are", R"({"state":"RUNNING"})"};
  }
  if (op == "loop_timing") {
    for (const auto& [key, value] : args.items()) {
      if ((key != "samples" && key != "reset") || !value.is_boolean()) {
        return call_failed("loop_timing takes {\"samples\": true|false, \"reset\": true|false}, got " + args.dump());
      }
    }
    const nlohmann::json timing =
        observers_[index]->loop_timing(args.value("samples", false), args.value("reset", false));
    return DeviceCallResponse{true, "ok", timing.dump()};
  }
  // blackbox
  for (const auto& [key, value] : args.items()) {
    if (key != "fresh" || !value.is_boolean()) {
      return call_failed("blackbox takes {\"fresh\": true|false}, got " + args.dump());
    }
  }
  device::BlackBox& box = *black_boxes_[index];
  if (args.value("fresh", false)) {
    auto capture = box.capture_now(std::chrono::seconds(2));
    if (!capture) return call_failed(capture.error().message);
    return DeviceCallResponse{true, "captured now", capture.value().dump()};
  }
  const nlohmann::json latest = box.latest();
  if (latest.is_null())
    return call_failed("no black box captured on '" + name + "' yet (no fault); use {\"fresh\": true}");
  return DeviceCallResponse{true, "last capture", latest.dump()};
}

}  // namespace robotd::service
