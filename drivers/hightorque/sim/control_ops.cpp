// The control channel's ops (README.md in this folder): what tests ask the simulator to report
// or to do wrong. Motors are named {"bus": index of its --bus/--board option, "motor": id}.
#include <cmath>
#include <stdexcept>
#include <string>

#include <spdlog/spdlog.h>

#include "robotd/sim_control/control_request.hpp"
#include "simulator.hpp"

namespace robotd::hightorque::sim {
namespace {

using nlohmann::json;
using sim_control::boolean_field;
using sim_control::expect_fields;
using sim_control::integer_field;
using sim_control::number_field;
using sim_control::RequestError;

constexpr std::int64_t kMaxDurationMs = 3'600'000;
constexpr std::int64_t kMaxCount = 1'000'000;
constexpr double kMaxTemperatureC = 200;
constexpr const char* kOps =
    "state, set_position, set_fault, clear_fault, set_temperature, mute, drop_replies, silence, garbage, disconnect, "
    "push_external_torque, reset_counters";

double finite_field(const json& request, const std::string& op, const char* name) {
  const double value = number_field(request, op, name);
  if (!std::isfinite(value)) throw RequestError("op \"" + op + "\": " + name + " must be a finite number");
  return value;
}

json motor_json(const SimMotor& motor) {
  const auto mode = static_cast<std::uint8_t>(motor.mode());
  return {{"id", motor.id()},
          {"position_rad", motor.position_rad()},
          {"velocity_rad_s", motor.velocity_rad_s()},
          {"torque_nm", motor.torque_nm()},
          {"mode", mode_text(mode)},
          {"mode_code", mode},
          {"mode_commanded_ns", motor.mode_commanded_ns()},
          {"fault", motor.fault()},
          {"kp", motor.stored().kp},
          {"kd", motor.stored().kd},
          {"target_position_rad", motor.stored().position_rad},
          {"target_velocity_rad_s", motor.stored().velocity_rad_s},
          {"target_torque_nm", motor.stored().torque_nm},
          {"timeout_ms", motor.timeout_ms()},
          {"temperature_c", motor.temperature_c()},
          {"commands", motor.requests()},
          {"reboots", motor.reboots()},
          {"zero_offset_rad", motor.zero_offset_rad()},
          {"external_torque_nm", motor.external_torque_nm()},
          {"push_period_us", motor.push_period_us()},
          {"muted", motor.muted()}};
}

}  // namespace

Bus& Simulator::bus_of(const json& request, const std::string& op) {
  const auto index = integer_field(request, op, "bus", 0, static_cast<std::int64_t>(buses_.size()) - 1);
  return *buses_.at(static_cast<std::size_t>(index));
}

SimMotor& Simulator::motor_of(const json& request, const std::string& op) {
  Bus& bus = bus_of(request, op);
  const auto id = static_cast<int>(integer_field(request, op, "motor", kMinMotorId, kMaxMotorId));
  SimMotor* motor = bus.motor(id);
  if (motor == nullptr) {
    std::string ids;
    for (const SimMotor& each : bus.motors()) ids += (ids.empty() ? "" : ",") + std::to_string(each.id());
    throw RequestError("op \"" + op + "\": bus " + std::to_string(request.at("bus").get<int>()) + " (" +
                       bus.spec().path + ") has no motor " + std::to_string(id) + "; its motors are " + ids);
  }
  return *motor;
}

json Simulator::control(const json& request) {
  try {
    const std::string op = sim_control::op_of(request, kOps);
    const std::int64_t now = monotonic_ns();
    if (op == "state") {
      expect_fields(request, op, {});
      return state();
    }
    if (op == "set_position") {
      expect_fields(request, op, {"bus", "motor", "position_rad"});
      const double position = finite_field(request, op, "position_rad");
      motor_of(request, op).teleport(position);
    } else if (op == "set_fault") {
      expect_fields(request, op, {"bus", "motor", "code"});
      const auto code = static_cast<std::uint8_t>(integer_field(request, op, "code", 1, 255));
      motor_of(request, op).inject_fault(code);
    } else if (op == "clear_fault") {
      expect_fields(request, op, {"bus", "motor"});
      motor_of(request, op).clear_fault();
    } else if (op == "set_temperature") {
      expect_fields(request, op, {"bus", "motor", "celsius"});
      const double celsius = finite_field(request, op, "celsius");
      if (celsius < -40 || celsius > kMaxTemperatureC) {
        throw RequestError("op \"set_temperature\": celsius must be within -40 … 200");
      }
      motor_of(request, op).set_temperature(celsius);
    } else if (op == "mute") {
      expect_fields(request, op, {"bus", "motor", "on"});
      const bool on = boolean_field(request, op, "on");
      motor_of(request, op).set_muted(on);
    } else if (op == "drop_replies") {
      expect_fields(request, op, {"bus", "count"});
      const std::int64_t count = integer_field(request, op, "count", 0, kMaxCount);
      bus_of(request, op).drop_replies(count);
    } else if (op == "silence") {
      expect_fields(request, op, {"bus", "for_ms"});
      const std::int64_t for_ms = integer_field(request, op, "for_ms", 0, kMaxDurationMs);
      bus_of(request, op).silence(for_ms, now);
    } else if (op == "garbage") {
      expect_fields(request, op, {"bus", "count"});
      const std::int64_t count = integer_field(request, op, "count", 1, kMaxCount);
      bus_of(request, op).queue_garbage(count);
    } else if (op == "disconnect") {
      expect_fields(request, op, {"bus", "for_ms"});
      const std::int64_t for_ms = integer_field(request, op, "for_ms", 0, kMaxDurationMs);
      bus_of(request, op).disconnect(for_ms, now);
    } else if (op == "push_external_torque") {
      expect_fields(request, op, {"bus", "motor", "torque_nm"});
      const double torque = finite_field(request, op, "torque_nm");
      motor_of(request, op).set_external_torque(torque);
    } else if (op == "reset_counters") {
      expect_fields(request, op, {});
      for (const auto& bus : buses_) {
        bus->reset_counters();
      }
    } else {
      throw RequestError("unknown op \"" + op + "\": expected one of " + kOps);
    }
    if (!options_.quiet) spdlog::info("control: {}", request.dump());
    return {{"ok", true}};
  } catch (const RequestError& error) {
    return sim_control::error_reply(error.what());
  } catch (const std::exception& error) {
    return sim_control::error_reply(std::string("the simulator failed on this request: ") + error.what());
  }
}

json Simulator::state() const {
  json buses = json::array();
  for (const auto& bus : buses_) {
    json motors = json::array();
    for (const SimMotor& motor : bus->motors()) motors.push_back(motor_json(motor));
    buses.push_back({{"path", bus->spec().path},
                     {"kind", bus->kind_text()},
                     {"open", bus->is_open()},
                     {"host_connected", bus->host_connected()},
                     {"frames_received", bus->frames_received()},
                     {"frames_sent", bus->frames_sent()},
                     {"bad_frames", bus->bad_frames()},
                     {"replies_dropped", bus->replies_dropped()},
                     {"drop_pending", bus->drop_pending()},
                     {"garbage_pending", bus->garbage_pending()},
                     {"board_firmware",
                      std::to_string(bus->board_firmware().major) + "." + std::to_string(bus->board_firmware().minor)},
                     {"function_version", static_cast<int>(bus->function_version())},
                     {"fdcan_resets", bus->fdcan_resets()},
                     {"motors", motors}});
  }
  return {{"ok", true}, {"buses", buses}};
}

}  // namespace robotd::hightorque::sim
