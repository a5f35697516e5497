// SimDriver's non-RT side: describe(), diagnostics() and the call() ops.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <ctime>
#include <exception>
#include <initializer_list>
#include <limits>
#include <optional>
#include <span>
#include <string_view>
#include <thread>
#include <vector>

#include "robotd/driver/monotonic_clock.hpp"
#include "sim_driver.hpp"

namespace robotd::sim {
namespace {

using driver::JointCommandKind;

using namespace std::chrono_literals;

struct OpSpec {
  std::string_view name;
  std::string_view help;
  bool needs_free_motors = false;
};

/// How long a disable may wait for write() to decide it.
constexpr auto kDecisionTimeout = 500ms;

constexpr std::array<OpSpec, 11> kOps{{
    {"motors",
     R"({"enabled": bool}: enable or disable the simulated motors, as a vendor's enable/disable op does. Disabled )"
     R"(motors apply no torque, not even the e-stop's damping: the joints coast under their load. Disabling is )"
     R"(refused while robotd drives a joint (a session, or the KEEP or DAMPING one left) and under the e-stop; a )"
     R"(session taking a joint enables them again)",
     driver::kNeedsFreeMotors},
    {"stop_feedback", R"({"enabled": bool}: while enabled, read() reports no new data; the simulation keeps running)"},
    {"estop_input", R"({"pressed": bool}: press or release the simulated controller's own e-stop button)"},
    {"disconnect",
     R"({"for_ms": int >= 0}: simulate a lost link; read()/write() report it and the joints damp; recover() )"
     R"(fails until for_ms has passed (0: the link is back as soon as it is recovered))"},
    {"raise_fault",
     R"({"code": int != 0, "text": string}: simulate a controller fault; read()/write() report it and the joints )"
     R"(damp until recover())"},
    {"set_external_torque",
     R"({"joint": name or index, "torque_nm": number}: set the constant load on a joint in N·m (e.g. gravity))"},
    {"set_imu",
     R"({"orientation_xyzw": [x, y, z, w] or "rpy_deg": [roll, pitch, yaw], "angular_velocity_rad_s": [x, y, z], )"
     R"("linear_acceleration_m_s2": [x, y, z]}, each optional: what the simulated IMU reports from now on)"},
    {"stall", R"({"ms": 1..10000}: the next read() blocks this long, like a driver hung on its bus (fault injection))"},
    {"slow_maintenance",
     R"({"ms": 1..60000}: the next recover(), reset_zero() or motors op waits this long first, like a controller )"
     R"(slow to answer; abort_maintenance() (an e-stop, a shutdown) ends the wait of a recover() or reset_zero() )"
     R"(with an error)"},
    {"command_latency",
     R"({"reset": bool, "samples": bool}: time from a client's publish (ControlCommand.sent_steady_ns) to the )"
     R"(write() that carried it: count and p50/p99/p99.9/max in µs, every sample in ns with samples=true)"},
    {"state", R"({}: per joint position (rad), velocity (rad/s), applied torque (N·m), command kind, applied kp, kd; )"
              R"(motors enabled or not, e-stop, link, feedback, recover() calls and injected fault)"},
}};

std::string_view help_of(std::string_view op) {
  const auto* spec =
      std::find_if(kOps.begin(), kOps.end(), [&](const OpSpec& candidate) { return candidate.name == op; });
  return spec == kOps.end() ? std::string_view{} : spec->help;
}

Error invalid_arguments(std::string_view op, const std::vector<std::string>& errors) {
  return make_error(ErrorCode::kInvalidArgument,
                    std::string(op) + ": " + join_errors(errors) + " (expects " + std::string(help_of(op)) + ")");
}

/// For ops that take no arguments: an error naming what was given, or nullopt.
std::optional<Error> unexpected_arguments(std::string_view op, const nlohmann::json& args) {
  std::vector<std::string> errors;
  if (!args.is_object()) {
    errors.push_back(std::string("args: expected an object, got ") + args.type_name());
  } else if (!args.empty()) {
    errors.push_back("args." + args.begin().key() + ": unknown key (this op takes no arguments)");
  }
  return errors.empty() ? std::nullopt : std::optional(invalid_arguments(op, errors));
}

/// What a missing args value stands for: no arguments.
const nlohmann::json& no_arguments() {
  static const nlohmann::json kNoArguments = nlohmann::json::object();
  return kNoArguments;
}

const char* command_kind_name(JointCommandKind kind) {
  switch (kind) {
    case JointCommandKind::kNone:
      return "none";
    case JointCommandKind::kPosition:
      return "position";
    case JointCommandKind::kImpedance:
      return "impedance";
  }
  return "unknown";
}

/// "position:6" or "impedance:4,none:2": how many joints have each command kind.
std::string command_kind_counts(const SimSnapshot& snapshot) {
  std::string text;
  for (const JointCommandKind kind :
       {JointCommandKind::kPosition, JointCommandKind::kImpedance, JointCommandKind::kNone}) {
    const auto joints = std::span(snapshot.joints).first(snapshot.joint_count);
    const auto count = std::count_if(joints.begin(), joints.end(),
                                     [&](const SimJointSnapshot& joint) { return joint.command == kind; });
    if (count == 0) continue;
    text += (text.empty() ? "" : ",") + std::string(command_kind_name(kind)) + ":" + std::to_string(count);
  }
  return text;
}

std::string fault_text(const driver::FaultInfo& fault) {
  if (fault.code == 0) return "none";
  return "code " + std::to_string(fault.code) + ": " + fault.text.data();
}

}  // namespace

driver::DeviceDescription SimDriver::describe() const {
  driver::DeviceDescription description;
  description.model = params_.model;
  description.kinematic_model = params_.kinematic_model;
  description.native_rate_hz = kNativeRateHz;
  for (const SimJointParams& joint : params_.joints) {
    description.joints.push_back(driver::JointDescription{
        .name = joint.name, .limits = joint.limits, .default_kp = joint.default_kp, .default_kd = joint.default_kd});
  }
  description.supports_torque = true;
  description.supports_damping = true;
  description.supports_zero_torque = true;
  description.has_imu = params_.imu;
  for (const OpSpec& op : kOps) {
    description.ops.push_back({std::string(op.name), std::string(op.help), op.needs_free_motors});
  }
  return description;
}

driver::Diagnostics SimDriver::diagnostics() const {
  const SimSnapshot snapshot = snapshot_.load_non_rt();
  const InjectedFaults injected = injected_faults_.load_non_rt();
  const bool connected = connected_.load();
  return {
      {"link", connected && !injected.link_lost ? "connected" : "disconnected"},
      {"motors", std::string(connected && motors_enabled_.load() ? "enabled" : "disabled") +
                     (motors_op_waiting_.load() ? "; switching (a motors op waits as slow_maintenance asked)" : "")},
      {"estop", snapshot.estop ? "engaged" : "clear"},
      {"injected_fault", fault_text(injected.fault)},
      {"modes", command_kind_counts(snapshot)},
      {"feedback", injected.feedback_stopped ? "stopped" : "streaming"},
  };
}

Result<nlohmann::json> SimDriver::call(const std::string& op, const nlohmann::json& args) {
  if (!configured_) return make_error(ErrorCode::kRefused, op + ": the sim driver is not configured");
  try {
    const nlohmann::json& arguments = args.is_null() ? no_arguments() : args;
    if (op == "motors") return motors(arguments);
    if (op == "stop_feedback") return stop_feedback(arguments);
    if (op == "estop_input") return press_estop_input(arguments);
    if (op == "disconnect") return inject_disconnect(arguments);
    if (op == "raise_fault") return raise_fault(arguments);
    if (op == "set_external_torque") return set_external_torque(arguments);
    if (op == "stall") return stall(arguments);
    if (op == "slow_maintenance") return slow_maintenance(arguments);
    if (op == "set_imu") return set_imu(arguments);
    if (op == "command_latency") return command_latency(arguments);
    if (op == "state") return state(arguments);
  } catch (const std::exception& e) {
    return make_error(ErrorCode::kInvalidArgument, op + ": " + e.what());
  }
  std::string known;
  for (const OpSpec& spec : kOps) known += (known.empty() ? "" : ", ") + std::string(spec.name);
  return make_error(ErrorCode::kInvalidArgument, "unknown op \"" + op + "\" (the sim driver has: " + known + ")");
}

Result<nlohmann::json> SimDriver::press_estop_input(const nlohmann::json& args) {
  std::vector<std::string> errors;
  JsonReader reader(args, "args", errors);
  reader.require("pressed", "true or false");
  const bool pressed = reader.boolean_or("pressed", false);
  reader.finish();
  if (!errors.empty()) return invalid_arguments("estop_input", errors);
  estop_input_.store(pressed, std::memory_order_relaxed);
  return nlohmann::json{{"estop_input", pressed ? "pressed" : "released"}};
}

Result<nlohmann::json> SimDriver::stop_feedback(const nlohmann::json& args) {
  std::vector<std::string> errors;
  JsonReader reader(args, "args", errors);
  reader.require("enabled", "true or false");
  const bool enabled = reader.boolean_or("enabled", false);
  reader.finish();
  if (!errors.empty()) return invalid_arguments("stop_feedback", errors);
  change_injected_faults([&](InjectedFaults& faults) { faults.feedback_stopped = enabled; });
  return nlohmann::json{{"feedback", enabled ? "stopped" : "streaming"}};
}

Result<nlohmann::json> SimDriver::inject_disconnect(const nlohmann::json& args) {
  std::vector<std::string> errors;
  JsonReader reader(args, "args", errors);
  const auto for_ms = reader.integer_or("for_ms", 0, 0, 600'000);
  reader.finish();
  if (!errors.empty()) return invalid_arguments("disconnect", errors);
  link_down_until_ns_.store(driver::monotonic_now_ns() + for_ms * 1'000'000);
  change_injected_faults([](InjectedFaults& faults) { faults.link_lost = true; });
  return nlohmann::json{{"link", "disconnected"}, {"for_ms", for_ms}};
}

Result<nlohmann::json> SimDriver::raise_fault(const nlohmann::json& args) {
  std::vector<std::string> errors;
  JsonReader reader(args, "args", errors);
  reader.require("code", "an integer other than 0");
  reader.require("text", "a string");
  const auto code =
      reader.integer("code", std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::max());
  if (code == 0) reader.error("code", "expected an integer other than 0 (0 means no fault), got 0");
  const auto text = reader.string("text");
  constexpr std::size_t kMaxTextLength = driver::FaultInfo{}.text.size() - 1;
  if (text && (text->empty() || text->size() > kMaxTextLength)) {
    reader.error("text",
                 "expected 1.." + std::to_string(kMaxTextLength) + " characters, got " + std::to_string(text->size()));
  }
  reader.finish();
  if (!errors.empty()) return invalid_arguments("raise_fault", errors);
  change_injected_faults(
      [&](InjectedFaults& faults) { faults.fault.set(static_cast<std::int32_t>(*code), text->c_str()); });
  return nlohmann::json{{"fault", {{"code", *code}, {"text", *text}}}};
}

Result<nlohmann::json> SimDriver::set_external_torque(const nlohmann::json& args) {
  std::vector<std::string> errors;
  JsonReader reader(args, "args", errors);
  const std::optional<std::size_t> joint = joint_argument(reader, args);
  reader.require("torque_nm", "a number (N·m)");
  const std::optional<double> torque_nm = reader.number("torque_nm");
  reader.finish();
  if (!errors.empty() || !joint || !torque_nm) return invalid_arguments("set_external_torque", errors);
  external_torque_nm_[*joint].store(*torque_nm);
  return nlohmann::json{{"joint", params_.joints[*joint].name}, {"external_torque_nm", *torque_nm}};
}

Result<nlohmann::json> SimDriver::stall(const nlohmann::json& args) {
  std::vector<std::string> errors;
  JsonReader reader(args, "args", errors);
  reader.require("ms", "an integer 1..10000 (milliseconds)");
  const auto ms = reader.integer("ms", 1, 10'000);
  reader.finish();
  if (!errors.empty()) return invalid_arguments("stall", errors);
  stall_ns_.store(*ms * 1'000'000, std::memory_order_release);
  return nlohmann::json{{"stall_ms", *ms}};
}

Result<nlohmann::json> SimDriver::slow_maintenance(const nlohmann::json& args) {
  std::vector<std::string> errors;
  JsonReader reader(args, "args", errors);
  reader.require("ms", "an integer 1..60000 (milliseconds)");
  const auto ms = reader.integer("ms", 1, 60'000);
  reader.finish();
  if (!errors.empty()) return invalid_arguments("slow_maintenance", errors);
  maintenance_wait_ns_.store(*ms * 1'000'000, std::memory_order_release);
  return nlohmann::json{{"maintenance_wait_ms", *ms}};
}

Result<nlohmann::json> SimDriver::motors(const nlohmann::json& args) {
  using Verdict = MotorsOffOutcome::Verdict;
  std::vector<std::string> errors;
  JsonReader reader(args, "args", errors);
  reader.require("enabled", "true or false");
  const bool enabled = reader.boolean_or("enabled", true);
  reader.finish();
  if (!errors.empty()) return invalid_arguments("motors", errors);
  if (!connected_.load())
    return make_error(ErrorCode::kNotAvailable, "motors: the simulated controller is not connected");
  // A controller slow to answer (slow_maintenance). This is no maintenance: nothing ends the wait early.
  if (const std::int64_t wait_ns = maintenance_wait_ns_.exchange(0); wait_ns > 0) {
    motors_op_waiting_.store(true);
    std::this_thread::sleep_for(std::chrono::nanoseconds(wait_ns));
    motors_op_waiting_.store(false);
  }
  if (enabled) {
    motors_enabled_.store(true);
    return nlohmann::json{{"motors", "enabled"}};
  }
  const Result<MotorsOffOutcome> decided = disable_motors();
  if (!decided) return decided.error();
  const std::string joint = params_.joints[decided.value().joint].name;
  switch (decided.value().verdict) {
    case Verdict::kDisabled:
      break;
    case Verdict::kEstop:
      return make_error(
          ErrorCode::kRefused,
          "motors: robotd's e-stop damps every joint, and disabled motors let go; reset the e-stop first");
    case Verdict::kOwned:
      return make_error(ErrorCode::kRefused, "motors: joint '" + joint + "' is held by a session; release it first");
    case Verdict::kHeld:
      return make_error(ErrorCode::kRefused,
                        "motors: robotd still holds joint '" + joint +
                            "' (the KEEP or DAMPING a session left it in), and disabled motors let go; take it with a "
                            "session and release it with ZERO_TORQUE first");
  }
  return nlohmann::json{{"motors", "disabled"}};
}

Result<MotorsOffOutcome> SimDriver::disable_motors() {
  const auto deadline = std::chrono::steady_clock::now() + kDecisionTimeout;
  std::optional<MotorsOffOutcome> owned;  // the last "a session owns a joint", while retrying
  for (;;) {
    if (!motors_off_.offer(MotorsOffRequest{})) {
      return make_error(ErrorCode::kRefused, "motors: another disable is being decided; try again");
    }
    const auto outcome = motors_off_.await(std::max<std::chrono::nanoseconds>(
        deadline - std::chrono::steady_clock::now(), std::chrono::nanoseconds::zero()));
    if (!outcome && owned) return *owned;  // time ran out while the session still owned the joint
    if (!outcome) {
      return make_error(ErrorCode::kNotAvailable,
                        "motors: the control loop did not take the request within " +
                            std::to_string(kDecisionTimeout.count()) +
                            " ms (robotd pauses it during recover and reset_zero; a lost link or an injected fault "
                            "silences the controller); nothing was changed");
    }
    if (outcome->verdict != MotorsOffOutcome::Verdict::kOwned || std::chrono::steady_clock::now() >= deadline) {
      return *outcome;
    }
    owned = outcome;
    std::this_thread::sleep_for(1ms);
  }
}

Result<nlohmann::json> SimDriver::set_imu(const nlohmann::json& args) {
  if (!params_.imu) return make_error(ErrorCode::kRefused, "set_imu: this device has no IMU (params.imu is false)");
  std::vector<std::string> errors;
  JsonReader reader(args, "args", errors);
  const auto triple = [&](std::string_view key) -> std::optional<std::array<double, 3>> {
    const auto values = reader.number_array(key);
    if (!values) return std::nullopt;
    if (values->size() != 3) {
      reader.error(key, "expected 3 numbers, got " + std::to_string(values->size()));
      return std::nullopt;
    }
    return std::array<double, 3>{(*values)[0], (*values)[1], (*values)[2]};
  };
  const auto quaternion = reader.number_array("orientation_xyzw");
  const auto rpy_deg = triple("rpy_deg");
  const auto angular_velocity = triple("angular_velocity_rad_s");
  const auto linear_acceleration = triple("linear_acceleration_m_s2");
  if (quaternion && rpy_deg) reader.error("rpy_deg", "give orientation_xyzw or rpy_deg, not both");
  double norm = 0;
  if (quaternion) {
    for (const double value : *quaternion) norm += value * value;
    norm = std::sqrt(norm);
    if (quaternion->size() != 4 || norm < 1e-9) {
      reader.error("orientation_xyzw", "expected 4 numbers x, y, z, w of a non-zero quaternion");
    }
  }
  reader.finish();
  if (!errors.empty()) return invalid_arguments("set_imu", errors);

  const std::lock_guard lock(imu_writer_mutex_);
  driver::ImuSample sample = imu_.load_non_rt();
  if (quaternion) {
    for (std::size_t i = 0; i < 4; ++i) sample.orientation_xyzw[i] = (*quaternion)[i] / norm;
  }
  if (rpy_deg) {  // roll about x, then pitch about y, then yaw about z (q = yaw * pitch * roll)
    constexpr double kRadPerDeg = 3.14159265358979323846 / 180.0;
    const double cr = std::cos((*rpy_deg)[0] * kRadPerDeg / 2);
    const double sr = std::sin((*rpy_deg)[0] * kRadPerDeg / 2);
    const double cp = std::cos((*rpy_deg)[1] * kRadPerDeg / 2);
    const double sp = std::sin((*rpy_deg)[1] * kRadPerDeg / 2);
    const double cy = std::cos((*rpy_deg)[2] * kRadPerDeg / 2);
    const double sy = std::sin((*rpy_deg)[2] * kRadPerDeg / 2);
    sample.orientation_xyzw = {sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy,
                               cr * cp * cy + sr * sp * sy};
  }
  if (angular_velocity) sample.angular_velocity_rad_s = *angular_velocity;
  if (linear_acceleration) sample.linear_acceleration_m_s2 = *linear_acceleration;
  imu_.store(sample);
  return nlohmann::json{{"orientation_xyzw", sample.orientation_xyzw},
                        {"angular_velocity_rad_s", sample.angular_velocity_rad_s},
                        {"linear_acceleration_m_s2", sample.linear_acceleration_m_s2}};
}

Result<nlohmann::json> SimDriver::command_latency(const nlohmann::json& args) {
  std::vector<std::string> errors;
  JsonReader reader(args, "args", errors);
  const bool reset = reader.boolean_or("reset", false);
  const bool with_samples = reader.boolean_or("samples", false);
  reader.finish();
  if (!errors.empty()) return invalid_arguments("command_latency", errors);

  const std::uint64_t end = latency_count_.load(std::memory_order_acquire);
  const std::uint64_t begin = std::max(latency_reset_at_.load(), end > kLatencySamples ? end - kLatencySamples : 0);
  std::vector<std::int32_t> samples;
  samples.reserve(static_cast<std::size_t>(end - begin));
  for (std::uint64_t i = begin; i < end; ++i) samples.push_back(latency_ns_[i % kLatencySamples].load());
  if (reset) latency_reset_at_.store(end);

  nlohmann::json out{{"count", samples.size()}};
  if (with_samples) out["samples_ns"] = samples;
  std::sort(samples.begin(), samples.end());
  const auto rank_us = [&](double q) {
    if (samples.empty()) return 0.0;
    const auto index = static_cast<std::size_t>(std::ceil(q * static_cast<double>(samples.size()))) - 1;
    return samples[std::min(index, samples.size() - 1)] / 1000.0;
  };
  out["p50_us"] = rank_us(0.50);
  out["p99_us"] = rank_us(0.99);
  out["p999_us"] = rank_us(0.999);
  out["max_us"] = samples.empty() ? 0.0 : samples.back() / 1000.0;
  return out;
}

std::optional<std::size_t> SimDriver::joint_argument(JsonReader& reader, const nlohmann::json& args) const {
  reader.require("joint", "a joint name or index");
  if (!args.is_object() || !args.contains("joint")) return std::nullopt;
  const nlohmann::json& value = args.at("joint");
  const std::size_t joint_count = params_.joints.size();
  if (value.is_number_integer()) {
    const auto index = reader.integer("joint", 0, static_cast<std::int64_t>(joint_count) - 1);
    return index ? std::optional(static_cast<std::size_t>(*index)) : std::nullopt;
  }
  if (value.is_string()) {
    const std::string name = value.get<std::string>();
    const auto joint = std::find_if(params_.joints.begin(), params_.joints.end(),
                                    [&](const SimJointParams& candidate) { return candidate.name == name; });
    if (joint != params_.joints.end()) return static_cast<std::size_t>(joint - params_.joints.begin());
    reader.error("joint", "no joint is named \"" + name + "\"");
    return std::nullopt;
  }
  reader.error("joint",
               "expected a joint name or an index 0.." + std::to_string(joint_count - 1) + ", got " + value.dump());
  return std::nullopt;
}

Result<nlohmann::json> SimDriver::state(const nlohmann::json& args) const {
  if (auto error = unexpected_arguments("state", args)) return *error;

  const SimSnapshot snapshot = snapshot_.load_non_rt();
  const InjectedFaults injected = injected_faults_.load_non_rt();
  nlohmann::json joints = nlohmann::json::array();
  for (std::size_t i = 0; i < snapshot.joint_count; ++i) {
    const SimJointSnapshot& joint = snapshot.joints[i];
    joints.push_back({{"name", params_.joints[i].name},
                      {"position_rad", joint.position_rad},
                      {"velocity_rad_s", joint.velocity_rad_s},
                      {"torque_nm", joint.torque_nm},
                      {"command", command_kind_name(joint.command)},
                      {"kp", joint.kp},
                      {"kd", joint.kd},
                      {"external_torque_nm", external_torque_nm_[i].load()},
                      {"zero_offset_rad", zero_offset_rad_[i].load()}});
  }
  const bool connected = connected_.load();
  nlohmann::json fault = nullptr;
  if (injected.fault.code != 0) fault = {{"code", injected.fault.code}, {"text", injected.fault.text.data()}};
  return nlohmann::json{{"joints", std::move(joints)},
                        {"motors", motors_enabled_.load() ? "enabled" : "disabled"},
                        {"estop", snapshot.estop},
                        {"link", connected && !injected.link_lost ? "connected" : "disconnected"},
                        {"feedback", injected.feedback_stopped ? "stopped" : "streaming"},
                        {"recover_calls", recover_calls_.load()},
                        {"injected_fault", std::move(fault)}};
}

}  // namespace robotd::sim
