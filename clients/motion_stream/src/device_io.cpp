#include "robotd/motion/device_io.hpp"

#include <algorithm>
#include <string_view>

#include "driver_io.hpp"

namespace robotd::motion {
namespace {

bool ends_with(std::string_view text, std::string_view tail) {
  return text.size() >= tail.size() && text.substr(text.size() - tail.size()) == tail;
}

// The statement as a program writes it, for messages.
std::string gripper_text(const GripperCommand& command) {
  return "Gripper(" + std::to_string(command.position) + ", " + std::to_string(command.speed) + ", " +
         std::to_string(command.current_ma) + ")";
}

std::string range_problem(const char* what, int value, int max, const char* unit) {
  if (value >= 0 && value <= max) return "";
  return std::string(what) + " " + std::to_string(value) + " is out of range: expected 0.." + std::to_string(max) +
         unit;
}

}  // namespace

DeviceIo::DeviceIo(DeviceInfo device) : device_(std::move(device)) {}

Error DeviceIo::cannot(const std::string& statement, const std::string& why) const {
  return make_error(ErrorCode::kRefused, "device '" + device_.name + "' (driver " + device_.driver + ") cannot do " +
                                             statement + ": " + why);
}

Result<DeviceCall> DeviceIo::offered(DeviceCall call, const std::string& statement) const {
  const std::string prefix = call.op + ":";
  const auto line = std::find_if(device_.ops.begin(), device_.ops.end(),
                                 [&](const std::string& op) { return op.rfind(prefix, 0) == 0; });
  if (line == device_.ops.end()) {
    return cannot(statement,
                  "the device does not offer the op " + call.op + " (robotctl devices --json lists its ops)");
  }
  call.needs_free_motors = ends_with(*line, kNeedsFreeMotorsMark);
  return call;
}

Result<DeviceCall> DeviceIo::output(int number, bool high) const {
  const std::string statement = "Output(" + std::to_string(number) + ", " + (high ? "HIGH" : "LOW") + ")";
  const detail::DriverIo* io = detail::find_driver_io(device_.driver);
  if (io == nullptr) return cannot(statement, "Output works on the drivers " + detail::known_drivers());
  auto call = io->output(number, high);
  if (!call) return cannot(statement, call.error().message);
  return offered(std::move(call.value()), statement);
}

Result<DeviceCall> DeviceIo::gripper_calibrate() const {
  const std::string statement = "Gripper_cal()";
  const detail::DriverIo* io = detail::find_driver_io(device_.driver);
  if (io == nullptr) return cannot(statement, "Gripper_cal works on the drivers " + detail::known_drivers());
  auto call = io->gripper_calibrate();
  if (!call) return cannot(statement, call.error().message);
  return offered(std::move(call.value()), statement);
}

Result<DeviceCall> DeviceIo::gripper(const GripperCommand& command) const {
  const std::string statement = gripper_text(command);
  for (const std::string& problem :
       {range_problem("position", command.position, 255, " (0 open, 255 closed)"),
        range_problem("speed", command.speed, 255, ""), range_problem("current", command.current_ma, 1300, " mA")}) {
    if (problem.empty()) continue;
    std::string message = statement + ": ";
    message += problem;
    return make_error(ErrorCode::kInvalidArgument, std::move(message));
  }
  const detail::DriverIo* io = detail::find_driver_io(device_.driver);
  if (io == nullptr) return cannot(statement, "Gripper works on the drivers " + detail::known_drivers());
  auto call = io->gripper(command, device_);
  if (!call) return cannot(statement, call.error().message);
  return offered(std::move(call.value()), statement);
}

Result<std::string> DeviceIo::run(Client& client, const DeviceCall& call) const {
  return client.device_call(device_.name, call.op, call.args_json);
}

}  // namespace robotd::motion
