// The RBTscript statements that act on a device's I/O rather than its joints — Output(n, HIGH|LOW),
// Gripper_cal() and Gripper(position, speed, current) — as the device_call op of the device's
// driver that does each: PAROL6 output / gripper_calibrate / gripper, the PiPER's gripper, the
// xArm's gripper_enable / gripper_set_position, RealMan's set_gripper_position. A statement the
// device cannot do is an error naming the device, its driver and why, so a dry run finds it.
#pragma once

#include <string>

#include "robotd/client.hpp"

namespace robotd::motion {

/// One device_call: what DeviceIo maps a statement to.
struct DeviceCall {
  std::string op;
  std::string args_json;
  /// robotd refuses the op while a session holds a motor of the device (its line in
  /// DeviceInfo.ops ends with " [needs free motors]"): release the session before calling it.
  bool needs_free_motors = false;
  /// What the device does differently from the PAROL6 the statements were made for, e.g. that it
  /// has no speed setting; "" when nothing.
  std::string note;
};

/// RBTscript's gripper command: the PAROL6 SSG-48's units.
struct GripperCommand {
  int position = 0;    // 0 (open) .. 255 (closed)
  int speed = 0;       // 0 .. 255
  int current_ma = 0;  // 0 .. 1300, the gripping current (force)
};

class DeviceIo {
 public:
  /// For `device` as /list_devices describes it: its name, driver and ops.
  explicit DeviceIo(DeviceInfo device);

  Result<DeviceCall> output(int number, bool high) const;
  Result<DeviceCall> gripper_calibrate() const;
  /// The gripper's own units: the position's 0..255 spread over its stroke, the speed's and
  /// current's over its ranges (DeviceCall::note says what the gripper does not take).
  Result<DeviceCall> gripper(const GripperCommand& command) const;

  /// Runs `call` on the device: robotd's JSON result, or its refusal.
  Result<std::string> run(Client& client, const DeviceCall& call) const;

  const DeviceInfo& device() const { return device_; }

 private:
  // `call` when the device offers its op (needs_free_motors read from DeviceInfo.ops), else an
  // error that `statement` cannot be done.
  Result<DeviceCall> offered(DeviceCall call, const std::string& statement) const;
  Error cannot(const std::string& statement, const std::string& why) const;

  DeviceInfo device_;
};

}  // namespace robotd::motion
