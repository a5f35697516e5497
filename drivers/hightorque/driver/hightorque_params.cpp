#include "driver/hightorque_params.hpp"

#include <map>
#include <set>
#include <sstream>
#include <utility>

#include "robotd/driver/json_reader.hpp"

namespace robotd::hightorque {
namespace {

std::string format_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

void read_bus(JsonReader& reader, BusParams& bus) {
  reader.require("name", "the bus's name, used by motors[].bus and in messages");
  bus.name = reader.string_or("name", "");
  const bool has_can = reader.has("can");
  const bool has_board = reader.has("board");
  if (has_can == has_board) {
    reader.error("can",
                 "expected exactly one of \"can\" (CAN-FD on SocketCAN or the stand-in) and \"board\" "
                 "(the USB-CDC CAN board)");
  }
  if (auto can = reader.object("can")) {
    bus.kind = BusParams::Kind::kCanFd;
    bus.can = transport::read_can_link(*can);
    bus.can.fd = true;  // the motors speak CAN-FD only
  }
  if (auto board = reader.object("board")) {
    bus.kind = BusParams::Kind::kBoard;
    bus.serial = transport::read_serial_link(*board);
  }
  reader.finish();
}

MotorScaling read_scaling(JsonReader& reader) {
  MotorScaling scaling;
  scaling.torque_per_unit = reader.number_or("torque_per_unit", scaling.torque_per_unit, NumberRange{.min = 1e-9});
  scaling.torque_offset_nm = reader.number_or("torque_offset_nm", scaling.torque_offset_nm);
  scaling.gain_factor = reader.number_or("gain_factor", scaling.gain_factor, NumberRange{.min = 1e-9});
  reader.finish();
  return scaling;
}

/// The keys a motor shares with motor_defaults (everything but name, bus and id).
void read_motor_settings(JsonReader& reader, MotorParams& motor) {
  if (const auto direction = reader.integer("direction", -1, 1)) {
    if (*direction == 0) {
      reader.error("direction", "expected 1 or -1, got 0");
    } else {
      motor.direction = static_cast<int>(*direction);
    }
  }
  motor.zero_offset_rad = reader.number_or("zero_offset_rad", motor.zero_offset_rad, NumberRange{-10, 10});
  motor.model = reader.string_or("model", motor.model);
  driver::JointLimits& limits = motor.limits;
  limits.position_min_rad = reader.number_or("position_min_rad", limits.position_min_rad, NumberRange{-20, 20});
  limits.position_max_rad = reader.number_or("position_max_rad", limits.position_max_rad, NumberRange{-20, 20});
  limits.velocity_max_rad_s =
      reader.number_or("velocity_max_rad_s", limits.velocity_max_rad_s, NumberRange{.min = 1e-6, .max = 50});
  limits.acceleration_max_rad_s2 =
      reader.number_or("acceleration_max_rad_s2", limits.acceleration_max_rad_s2, NumberRange{.min = 1e-6});
  limits.effort_max_nm = reader.number_or("effort_max_nm", limits.effort_max_nm, NumberRange{.min = 1e-6, .max = 300});
  limits.kp_max = reader.number_or("kp_max", limits.kp_max, NumberRange{.min = 1e-6});
  limits.kd_max = reader.number_or("kd_max", limits.kd_max, NumberRange{.min = 1e-6});
  motor.default_kp = reader.number_or("default_kp", motor.default_kp, NumberRange{.min = 0});
  motor.default_kd = reader.number_or("default_kd", motor.default_kd, NumberRange{.min = 0});
}

void check_motor(JsonReader& reader, const MotorParams& motor) {
  if (!(motor.limits.position_min_rad < motor.limits.position_max_rad)) {
    reader.error("position_min_rad", "expected less than position_max_rad (" +
                                         format_number(motor.limits.position_max_rad) + "), got " +
                                         format_number(motor.limits.position_min_rad));
  }
  if (motor.default_kp > motor.limits.kp_max) {
    reader.error("default_kp", "expected at most kp_max (" + format_number(motor.limits.kp_max) + "), got " +
                                   format_number(motor.default_kp));
  }
  if (motor.default_kd > motor.limits.kd_max) {
    reader.error("default_kd", "expected at most kd_max (" + format_number(motor.limits.kd_max) + "), got " +
                                   format_number(motor.default_kd));
  }
}

/// The default gains robotd falls back on must hold the joint (`whose`: "joint \"l_knee\"" or
/// "every motor"): describe() claims DAMPING, which is kp = 0, kd = default_kd.
void check_holding_gains(JsonReader& reader, const MotorParams& motor, const std::string& whose) {
  if (reader.has("default_kd") && !(motor.default_kd > 0)) {
    reader.error("default_kd", "expected more than 0 for " + whose + ", got " + format_number(motor.default_kd) +
                                   ": DAMPING holds a joint with kp = 0 and kd = default_kd, so 0 would let it "
                                   "free-wheel while robotd reports DAMPING");
  }
  if (reader.has("default_kp") && !(motor.default_kp > 0)) {
    reader.error("default_kp", "expected more than 0 for " + whose + ", got " + format_number(motor.default_kp) +
                                   ": a POSITION command without gains, and KEEP of a joint that was not "
                                   "tracking, hold it with default_kp and default_kd, so 0 would not hold it");
  }
}

std::string names_of(const std::vector<BusParams>& buses) {
  std::string names;
  for (const auto& bus : buses) names += (names.empty() ? "" : ", ") + bus.name;
  return names;
}

void read_motors(JsonReader& reader, HighTorqueParams& out, const std::map<std::string, MotorScaling>& models) {
  MotorParams defaults;
  defaults.limits = driver::JointLimits{.position_min_rad = -3.14,
                                        .position_max_rad = 3.14,
                                        .velocity_max_rad_s = 10.0,
                                        .acceleration_max_rad_s2 = 100.0,
                                        .effort_max_nm = 20.0,
                                        .kp_max = 500.0,
                                        .kd_max = 50.0};
  if (auto reader_defaults = reader.object("motor_defaults")) {
    read_motor_settings(*reader_defaults, defaults);
    check_holding_gains(*reader_defaults, defaults, "every motor");
    reader_defaults->finish();
  }
  reader.require("motors", "the joint map: [{\"name\", \"bus\", \"id\", …}], one entry per motor");
  std::set<std::pair<std::size_t, int>> taken;
  std::set<std::string> names;
  for (JsonReader& motor_reader : reader.object_array("motors")) {
    MotorParams motor = defaults;
    motor_reader.require("name", "the joint's name");
    motor.name = motor_reader.string_or("name", "");
    if (!motor.name.empty() && !names.insert(motor.name).second) {
      motor_reader.error("name", "\"" + motor.name + "\" is used by another motor");
    }
    motor_reader.require("bus", "the name of the bus the motor is on: " + names_of(out.buses));
    const std::string bus = motor_reader.string_or("bus", "");
    bool found = false;
    for (std::size_t b = 0; b < out.buses.size(); ++b) {
      if (out.buses[b].name == bus) {
        motor.bus = b;
        found = true;
      }
    }
    if (!found && motor_reader.has("bus")) {
      motor_reader.error("bus", "no bus named \"" + bus + "\"; buses: " + names_of(out.buses));
    }
    motor_reader.require("id", "the motor's CAN id, 1..126");
    motor.id = static_cast<int>(motor_reader.integer_or("id", 1, kMinMotorId, kMaxMotorId));
    if (found && motor_reader.has("id") && !taken.insert({motor.bus, motor.id}).second) {
      motor_reader.error("id", "id " + std::to_string(motor.id) + " is used twice on bus \"" + bus + "\"");
    }
    read_motor_settings(motor_reader, motor);
    if (!motor.model.empty()) {
      const auto model = models.find(motor.model);
      if (model == models.end()) {
        motor_reader.error("model", "no motor model \"" + motor.model + "\" in motor_models");
      } else {
        motor.scaling = model->second;
      }
    }
    check_motor(motor_reader, motor);
    check_holding_gains(motor_reader, motor, "joint \"" + motor.name + "\"");
    motor_reader.finish();
    out.motors.push_back(std::move(motor));
  }
  if (out.motors.size() > driver::kMaxJoints) {
    reader.error("motors", "at most " + std::to_string(driver::kMaxJoints) + " motors per device, got " +
                               std::to_string(out.motors.size()));
  }
}

}  // namespace

std::vector<std::size_t> HighTorqueParams::motors_on(std::size_t bus) const {
  std::vector<std::size_t> indices;
  for (std::size_t m = 0; m < motors.size(); ++m) {
    if (motors[m].bus == bus) indices.push_back(m);
  }
  return indices;
}

Result<HighTorqueParams> parse_hightorque_params(const nlohmann::json& params) {
  std::vector<std::string> errors;
  JsonReader reader(params, "", errors);
  HighTorqueParams out;
  out.model = reader.string_or("model", out.model);
  const std::string width = reader.string_or("width", "int16", {"int16", "int32", "float"});
  out.width = width == "int32" ? Width::kInt32 : width == "float" ? Width::kFloat : Width::kInt16;
  out.motor_timeout_ms = static_cast<int>(reader.integer_or("motor_timeout_ms", out.motor_timeout_ms, 0, 65535));
  if (out.motor_timeout_ms != 0 &&
      (out.motor_timeout_ms < kMinMotorTimeoutMs || out.motor_timeout_ms > kMaxMotorTimeoutMs)) {
    reader.error("motor_timeout_ms",
                 "expected " + std::to_string(kMinMotorTimeoutMs) + ".." + std::to_string(kMaxMotorTimeoutMs) +
                     " (shorter brakes the motors under normal jitter, longer lets the robot fall before they brake), "
                     "or 0 to disarm every motor's own watchdog, got " +
                     std::to_string(out.motor_timeout_ms));
  }
  out.feedback_timeout_ms = static_cast<int>(reader.integer_or("feedback_timeout_ms", out.feedback_timeout_ms, 5, 90));
  out.connect_timeout_ms = static_cast<int>(reader.integer_or("connect_timeout_ms", out.connect_timeout_ms, 10, 10000));
  out.reply_timeout_ms = static_cast<int>(reader.integer_or("reply_timeout_ms", out.reply_timeout_ms, 10, 10000));
  out.zero_settle_ms = static_cast<int>(reader.integer_or("zero_settle_ms", out.zero_settle_ms, 0, 5000));
  out.zero_save_to_flash = reader.boolean_or("zero_save_to_flash", out.zero_save_to_flash);
  out.imu = reader.raw("imu");

  reader.require("buses", "the motor buses: [{\"name\": \"legs\", \"can\": {…}} or {\"name\", \"board\": {…}}]");
  std::set<std::string> bus_names;
  for (JsonReader& bus_reader : reader.object_array("buses")) {
    BusParams bus;
    read_bus(bus_reader, bus);
    if (!bus.name.empty() && !bus_names.insert(bus.name).second) {
      bus_reader.error("name", "\"" + bus.name + "\" names two buses");
    }
    out.buses.push_back(std::move(bus));
  }

  std::map<std::string, MotorScaling> models;
  for (auto& [name, model_reader] : reader.object_map("motor_models")) models[name] = read_scaling(model_reader);
  read_motors(reader, out, models);
  for (std::size_t b = 0; b < out.buses.size(); ++b) {
    if (out.motors_on(b).empty()) {
      reader.error("buses", "bus \"" + out.buses[b].name + "\" has no motor in motors[]");
    }
  }
  reader.finish();
  if (!errors.empty()) return make_error(ErrorCode::kInvalidArgument, join_errors(errors));
  return out;
}

}  // namespace robotd::hightorque
