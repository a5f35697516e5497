// Per driver, the device_call op that does each RBTscript I/O statement, with its arguments in the
// driver's units. Facts from each driver's op help (drivers/*/driver/*ops*.cpp, docs/drivers/).
#pragma once

#include <string>
#include <string_view>

#include "robotd/messages.hpp"
#include "robotd/motion/device_io.hpp"

namespace robotd::motion::detail {

/// Each returns the call, or an error whose message says why the driver cannot do the statement.
struct DriverIo {
  std::string_view driver;
  Result<DeviceCall> (*output)(int number, bool high);
  Result<DeviceCall> (*gripper_calibrate)();
  Result<DeviceCall> (*gripper)(const GripperCommand& command, const DeviceInfo& device);
};

/// nullptr when robotd has no I/O mapping for `driver`.
const DriverIo* find_driver_io(std::string_view driver);
/// The drivers find_driver_io knows, for messages: "parol6, piper, xarm, realman".
std::string known_drivers();

}  // namespace robotd::motion::detail
