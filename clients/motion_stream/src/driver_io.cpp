#include "driver_io.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <nlohmann/json.hpp>

namespace robotd::motion::detail {
namespace {

constexpr double kCommandRange = 255;     // RBTscript's position and speed: 0..255
constexpr double kCurrentRangeMa = 1300;  // RBTscript's current: 0..1300 mA (the SSG-48's)

Error cannot(std::string why) { return make_error(ErrorCode::kRefused, std::move(why)); }

DeviceCall call(std::string op, const nlohmann::json& args, std::string note = "") {
  return DeviceCall{std::move(op), args.dump(), false, std::move(note)};
}

// 0 (open) .. 255 (closed) as an opening between `closed` and `open` in the gripper's units.
double opening(int position, double closed, double open) {
  return open - (open - closed) * static_cast<double>(position) / kCommandRange;
}

// --- PAROL6: OUT1/OUT2 and the SSG-48 gripper, whose units RBTscript uses ----------------------

Result<DeviceCall> parol6_output(int number, bool high) {
  if (number != 1 && number != 2) {
    return cannot("the PAROL6 has outputs 1 and 2 (OUT1, OUT2), not " + std::to_string(number));
  }
  return call("output", {{"out" + std::to_string(number), high}});
}
Result<DeviceCall> parol6_calibrate() { return call("gripper_calibrate", nlohmann::json::object()); }
Result<DeviceCall> parol6_gripper(const GripperCommand& command, const DeviceInfo& /*device*/) {
  return call("gripper", {{"position", command.position},
                          {"speed", command.speed},
                          {"current_a", static_cast<double>(command.current_ma) / 1000.0}});
}

// --- PiPER: the gripper is joint "gripper", a stroke in metres, and a gripping torque ----------

constexpr double kPiperMaxEffortNm = 5;  // the gripper op's effort_nm range: 0..5 N·m

Result<DeviceCall> piper_output(int /*number*/, bool /*high*/) {
  return cannot("the piper driver has no digital outputs");
}
Result<DeviceCall> piper_calibrate() {
  return cannot("the PiPER gripper has no calibration (its zero is set once with the op gripper {\"set_zero\": true})");
}
Result<DeviceCall> piper_gripper(const GripperCommand& command, const DeviceInfo& device) {
  const auto joint = std::find(device.joint_names.begin(), device.joint_names.end(), "gripper");
  const auto index = static_cast<std::size_t>(joint - device.joint_names.begin());
  if (joint == device.joint_names.end() || index >= device.position_max.size()) {
    return cannot("it has no joint \"gripper\" (configured with \"gripper\": false?)");
  }
  const double stroke = opening(command.position, device.position_min[index], device.position_max[index]);
  return call("gripper",
              {{"stroke_m", stroke},
               {"effort_nm", kPiperMaxEffortNm * static_cast<double>(command.current_ma) / kCurrentRangeMa}},
              "speed is not used: the PiPER gripper takes a stroke and a gripping torque");
}

// --- xArm: the UFACTORY gripper, 850 pulses open .. 0 closed, speed in r/min ----------------------

constexpr double kXarmOpenPulses = 850;
constexpr double kXarmMaxSpeedRpm = 5000;

Result<DeviceCall> xarm_output(int /*number*/, bool /*high*/) {
  return cannot("the xarm driver has no digital output op");
}
Result<DeviceCall> xarm_calibrate() {
  return call("gripper_enable", {{"enable", true}},
              "the xArm gripper needs no calibration: Gripper_cal() switches its motor on");
}
Result<DeviceCall> xarm_gripper(const GripperCommand& command, const DeviceInfo& /*device*/) {
  const double speed = std::max(1.0, std::round(kXarmMaxSpeedRpm * static_cast<double>(command.speed) / kCommandRange));
  return call("gripper_set_position",
              {{"position", std::lround(opening(command.position, 0, kXarmOpenPulses))},
               {"speed_rpm", static_cast<long>(speed)}},
              "current is not used: the xArm gripper's position command takes no force");
}

// --- RealMan: the gripper's opening 1..1000 ------------------------------------------------------

constexpr double kRealmanClosed = 1;
constexpr double kRealmanOpen = 1000;

Result<DeviceCall> realman_output(int /*number*/, bool /*high*/) {
  return cannot("the realman driver has no digital output op");
}
Result<DeviceCall> realman_calibrate() {
  return cannot("the RealMan gripper has no calibration op (its opening limits are set with set_gripper_route)");
}
Result<DeviceCall> realman_gripper(const GripperCommand& command, const DeviceInfo& /*device*/) {
  return call("set_gripper_position",
              {{"position", std::lround(opening(command.position, kRealmanClosed, kRealmanOpen))}},
              "speed and current are not used: set_gripper_position takes only the opening");
}

constexpr std::array kDrivers{
    DriverIo{"parol6", parol6_output, parol6_calibrate, parol6_gripper},
    DriverIo{"piper", piper_output, piper_calibrate, piper_gripper},
    DriverIo{"xarm", xarm_output, xarm_calibrate, xarm_gripper},
    DriverIo{"realman", realman_output, realman_calibrate, realman_gripper},
};

}  // namespace

const DriverIo* find_driver_io(std::string_view driver) {
  const auto* found =
      std::find_if(kDrivers.begin(), kDrivers.end(), [&](const DriverIo& io) { return io.driver == driver; });
  return found == kDrivers.end() ? nullptr : &*found;
}

std::string known_drivers() {
  std::string names;
  for (const DriverIo& io : kDrivers) names += (names.empty() ? "" : ", ") + std::string(io.driver);
  return names;
}

}  // namespace robotd::motion::detail
