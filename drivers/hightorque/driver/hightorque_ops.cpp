// The driver's device_call ops (docs/drivers/hightorque.md lists them with their arguments).
// They run on robotd's service threads: requests go to the RT thread through a ring, which
// sends them between two ticks, and the motors' answers come back through another.
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "driver/hightorque_driver.hpp"
#include "driver/version_text.hpp"
#include "robotd/driver/op_arguments.hpp"

namespace robotd::hightorque {
namespace {

using nlohmann::json;

constexpr const char* kMotorUsage = "{\"motor\": a joint name or motor index 0..n-1}";

int motor_of(const Reply& reply) {
  switch (reply.kind) {
    case Reply::Kind::kState:
      return reply.state.motor;
    case Reply::Kind::kFirmwareVersion:
    case Reply::Kind::kHardwareVersion:
      return reply.version.motor;
    case Reply::Kind::kModel:
      return reply.model.motor;
    case Reply::Kind::kResult:
      return reply.result.motor;
  }
  return 0;
}

}  // namespace

bool HighTorqueDriver::from_motor(const BusReply& reply, std::size_t motor) const {
  const MotorParams& params = params_.motors[motor];
  return reply.bus == params.bus && motor_of(reply.reply) == params.id;
}

Result<nlohmann::json> HighTorqueDriver::call(const std::string& op, const nlohmann::json& args) {
  if (op == "state") return op_state();
  const std::lock_guard lock(ops_mutex_);
  if (op == "motor_info") return op_motor_info(args);
  if (op == "set_motor_timeout") return op_set_motor_timeout(args);
  if (op == "reboot_motor") return op_reboot_motor(args);
  std::string known;
  for (const auto& described : describe().ops) known += (known.empty() ? "" : ", ") + described.name;
  return make_error(ErrorCode::kInvalidArgument, "unknown op '" + op + "'; this driver has: " + known);
}

Result<std::size_t> HighTorqueDriver::motor_argument(const json& args, const std::string& op, const char* usage) const {
  const json* motor = args.is_object() && args.contains("motor") ? &args.at("motor") : nullptr;
  std::string problem = "missing \"motor\"";
  if (motor != nullptr && motor->is_number_integer()) {
    const auto index = motor->get<long long>();
    if (index >= 0 && static_cast<std::size_t>(index) < params_.motors.size()) return static_cast<std::size_t>(index);
    problem = "motor index " + std::to_string(index) + " is out of range";
  } else if (motor != nullptr && motor->is_string()) {
    for (std::size_t m = 0; m < params_.motors.size(); ++m) {
      if (params_.motors[m].name == motor->get<std::string>()) return m;
    }
    problem = "no motor named \"" + motor->get<std::string>() + "\"";
  }
  return make_error(ErrorCode::kInvalidArgument, op + ": " + problem + " (expects " + usage + ")");
}

Result<nlohmann::json> HighTorqueDriver::op_state() const {
  const DriverSnapshot snapshot = snapshot_.load_non_rt();
  json motors = json::array();
  for (std::size_t m = 0; m < params_.motors.size(); ++m) {
    const MotorParams& params = params_.motors[m];
    const MotorStatus& status = snapshot.motors[m];
    json motor = {{"index", m},
                  {"name", params.name},
                  {"bus", params_.buses[params.bus].name},
                  {"id", params.id},
                  {"position_rad", status.position_rad},
                  {"velocity_rad_s", status.velocity_rad_s},
                  {"torque_nm", status.torque_nm},
                  {"mode", mode_text(status.mode)},
                  {"fault", status.fault},
                  {"fault_text", fault_text(status.fault)},
                  {"owned", status.owned},
                  {"replies", status.replies}};
    motor["temperature_c"] = status.has_temperature ? json(status.temperature_c) : json(nullptr);
    motors.push_back(std::move(motor));
  }
  json buses = json::array();
  for (std::size_t b = 0; b < params_.buses.size(); ++b) {
    const BusCounters& counters = snapshot.buses[b];
    buses.push_back({{"name", params_.buses[b].name},
                     {"link", buses_[b]->describe()},
                     {"frames_sent", counters.frames_sent},
                     {"frames_received", counters.frames_received},
                     {"frames_dropped", counters.frames_dropped},
                     {"bytes_skipped", counters.bytes_skipped},
                     {"sent_per_s", counters.sent_per_s},
                     {"received_per_s", counters.received_per_s}});
  }
  return json{{"link_up", snapshot.link_up}, {"ticks", snapshot.ticks}, {"motors", motors}, {"buses", buses}};
}

Result<void> HighTorqueDriver::queue_request(std::size_t motor, const SystemRequest& request) {
  if (!connected_.load(std::memory_order_acquire)) {
    return make_error(ErrorCode::kNotAvailable, "the motors are not connected");
  }
  if (!requests_.push(QueuedRequest{params_.motors[motor].bus, request})) {
    return make_error(ErrorCode::kRefused, "too many requests waiting for the control loop; try again");
  }
  return {};
}

std::vector<Reply> HighTorqueDriver::collect_replies(std::size_t motor, std::size_t count) {
  std::vector<Reply> collected;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(params_.reply_timeout_ms);
  while (collected.size() < count && std::chrono::steady_clock::now() < deadline) {
    while (const auto reply = replies_.pop()) {
      if (from_motor(*reply, motor)) collected.push_back(reply->reply);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return collected;
}

Result<nlohmann::json> HighTorqueDriver::op_motor_info(const nlohmann::json& args) {
  const auto chosen = motor_argument(args, "motor_info", kMotorUsage);
  if (!chosen) return chosen.error();
  const std::size_t motor = chosen.value();
  replies_.clear();
  const int id = params_.motors[motor].id;
  for (const InfoKind kind : {InfoKind::kFirmwareVersion, InfoKind::kHardwareVersion, InfoKind::kModel}) {
    auto queued = queue_request(motor, SystemRequest{.kind = SystemRequest::Kind::kInfo, .motor = id, .info = kind});
    if (!queued) return queued.error();
  }
  json info = {
      {"motor", params_.motors[motor].name}, {"bus", params_.buses[params_.motors[motor].bus].name}, {"id", id}};
  for (const Reply& reply : collect_replies(motor, 3)) {
    if (reply.kind == Reply::Kind::kFirmwareVersion) info["firmware_version"] = version_text(reply.version);
    if (reply.kind == Reply::Kind::kHardwareVersion) info["hardware_version"] = version_text(reply.version);
    if (reply.kind == Reply::Kind::kModel) info["model"] = std::string(reply.model.text.data());
  }
  if (info.size() == 3) {
    return make_error(ErrorCode::kTimeout, "motor_info: motor " + params_.motors[motor].name +
                                               " did not answer within " + std::to_string(params_.reply_timeout_ms) +
                                               " ms");
  }
  return info;
}

Result<nlohmann::json> HighTorqueDriver::op_set_motor_timeout(const nlohmann::json& args) {
  // Any client may call an op, so it can only set a safe watchdog; disarming it (0) is for the
  // config (params.motor_timeout_ms), which robotd's owner writes.
  const std::string range = std::to_string(kMinMotorTimeoutMs) + ".." + std::to_string(kMaxMotorTimeoutMs);
  driver::OpArguments arguments("set_motor_timeout", args,
                                "{\"timeout_ms\": " + range +
                                    "}; 0, which disarms the motors' own watchdog, only through "
                                    "params.motor_timeout_ms");
  arguments.reader().require("timeout_ms", "the motors' own command timeout in ms, " + range);
  const auto timeout_ms = arguments.reader().integer("timeout_ms", kMinMotorTimeoutMs, kMaxMotorTimeoutMs);
  if (auto problem = arguments.finish()) return *problem;
  for (std::size_t m = 0; m < params_.motors.size(); ++m) {
    const SystemRequest request{.kind = SystemRequest::Kind::kCommandTimeout,
                                .motor = params_.motors[m].id,
                                .value = static_cast<int>(*timeout_ms)};
    // The ring holds 64 requests and the loop sends 4 a tick: wait for room rather than fail.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(params_.reply_timeout_ms);
    auto queued = queue_request(m, request);
    while (!queued && queued.error().code == ErrorCode::kRefused && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      queued = queue_request(m, request);
    }
    if (!queued) return queued.error();
  }
  motor_timeout_ms_.store(static_cast<int>(*timeout_ms));
  return json{{"timeout_ms", *timeout_ms}, {"motors", params_.motors.size()}};
}

std::vector<std::size_t> HighTorqueDriver::rebooted_with(std::size_t motor) const {
  const std::size_t bus = params_.motors[motor].bus;
  if (params_.buses[bus].kind == BusParams::Kind::kBoard) return motors_on_bus_[bus];
  return {motor};
}

Result<nlohmann::json> HighTorqueDriver::op_reboot_motor(const nlohmann::json& args) {
  using Verdict = RebootOutcome::Verdict;
  const auto chosen = motor_argument(args, "reboot_motor", kMotorUsage);
  if (!chosen) return chosen.error();
  const std::size_t motor = chosen.value();
  const std::string& name = params_.motors[motor].name;
  if (!connected_.load(std::memory_order_acquire)) {
    return make_error(ErrorCode::kNotAvailable, "reboot_motor: the motors are not connected");
  }
  // The RT thread decides at the tick it would send the reboot, from that tick's commands: a
  // session or a fallback that takes the motor meanwhile is seen (a snapshot could be 10 ticks old).
  if (!reboot_.offer(RebootRequest{.motor = motor})) {
    return make_error(ErrorCode::kRefused, "reboot_motor: another reboot is being decided; try again");
  }
  const auto outcome = reboot_.await(std::chrono::milliseconds(params_.reply_timeout_ms));
  if (!outcome) {
    return make_error(ErrorCode::kNotAvailable,
                      "reboot_motor: the control loop did not take the request within " +
                          std::to_string(params_.reply_timeout_ms) +
                          " ms (robotd pauses it during recover and reset_zero); nothing was sent");
  }
  const std::string& blocking = params_.motors[outcome->blocking_motor].name;
  const std::string port_mate =
      outcome->blocking_motor == motor
          ? ""
          : " (" + blocking + " shares " + name + "'s board port, and the board reboots the whole port)";
  switch (outcome->verdict) {
    case Verdict::kEstop:
      return make_error(ErrorCode::kRefused,
                        "reboot_motor: robotd's e-stop brakes every motor, and a rebooting motor lets go; reset the "
                        "e-stop first");
    case Verdict::kOwned:
      return make_error(ErrorCode::kRefused,
                        "reboot_motor: " + blocking + " is held by a session; release it first" + port_mate);
    case Verdict::kHeld:
      return make_error(ErrorCode::kRefused,
                        "reboot_motor: robotd still holds " + blocking +
                            " (the KEEP or DAMPING a session left it in), and a rebooting motor lets go; take it "
                            "with a session whose default_behavior is ZERO_TORQUE and release it first" +
                            port_mate);
    case Verdict::kBusBusy:
      return make_error(ErrorCode::kRefused, "reboot_motor: bus '" + params_.buses[params_.motors[motor].bus].name +
                                                 "' was too busy to take the frame; nothing was sent, try again");
    case Verdict::kLinkClosed:
      return make_error(ErrorCode::kNotAvailable,
                        "reboot_motor: bus '" + params_.buses[params_.motors[motor].bus].name + "' is closed");
    case Verdict::kSent:
      break;
  }
  json rebooted = json::array();
  for (const std::size_t m : rebooted_with(motor)) rebooted.push_back(params_.motors[m].name);
  const int watchdog_ms = motor_timeout_ms_.load();
  json result{{"motor", name}, {"rebooted", rebooted}, {"watchdog_ms", watchdog_ms}};
  result["watchdog_rearmed"] = rearm_watchdog_after_reboot(motor, outcome->replies_at_send);
  if (!result["watchdog_rearmed"].get<bool>()) {
    result["note"] = name + " did not answer within " + std::to_string(params_.reply_timeout_ms) +
                     " ms of its reboot: its own watchdog stays disarmed until recover re-arms it";
  }
  return result;
}

bool HighTorqueDriver::rearm_watchdog_after_reboot(std::size_t motor, std::uint64_t replies_at_send) {
  // A reply to the command sent in the reboot's own tick may still come; one more is the motor
  // answering after its reboot.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(params_.reply_timeout_ms);
  while (snapshot_.load_non_rt().motors[motor].replies <= replies_at_send + 1) {
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  const SystemRequest rearm{.kind = SystemRequest::Kind::kCommandTimeout,
                            .motor = params_.motors[motor].id,
                            .value = motor_timeout_ms_.load()};
  return queue_request(motor, rearm).ok();
}

}  // namespace robotd::hightorque
