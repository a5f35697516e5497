// The xArm gripper on the tool's RS-485 bus (Modbus id 8): its registers as the Modbus requests of
// register 124 and the direct accesses of registers 127–130 see them, and its finger moving toward
// the target at the set speed. An object placed between the fingers (from the control channel)
// stops a closing move at its width, and the status register then says "gripping" (2).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "codec/xarm_codec.hpp"

namespace robotd::xarm::sim {

class XarmGripper {
 public:
  /// Pulses per second per r/min of the set speed: the full 850-pulse stroke in about 1.1 s at
  /// 1500 r/min (a simulator's choice; the manual gives no travel time).
  static constexpr double kPulsesPerSecondPerRpm = 0.5;
  static constexpr int kDefaultSpeedRpm = 1500;
  /// The firmware get_gripper_version reports: 3.4.3, the first that has the status register.
  static constexpr std::array<std::uint16_t, 3> kVersion{3, 4, 3};

  /// Moves the finger by `dt_s`.
  void advance(double dt_s);

  /// One 16-bit register; nullopt for an address the gripper does not have.
  std::optional<std::uint16_t> read(std::uint16_t address) const;
  /// Writes one register; false for an address it does not have or a value out of range.
  bool write(std::uint16_t address, std::uint16_t value);
  /// A Modbus request (functions 3 and 16) and the reply data of register 124.
  Bytes modbus(const ToolModbusRequest& request);

  /// An object `width_pulses` wide between the fingers (0: none): a move closing past it stops
  /// there. Set from the control channel.
  void set_object(int width_pulses) { object_pulses_ = width_pulses; }

  /// The error code the gripper reports (0 none): set from the control channel.
  void set_error(int code);
  int error() const { return error_; }
  nlohmann::json state() const;

 private:
  bool enabled_ = false;
  int mode_ = 0;
  int speed_rpm_ = kDefaultSpeedRpm;
  double position_ = 0;  // pulses
  std::int32_t target_ = 0;
  std::uint16_t target_high_ = 0;  // the first word of a target written one register at a time
  int error_ = 0;
  int object_pulses_ = 0;

  /// Where the finger stops: the target, or the object's width when it closes onto the object.
  double stop_position() const;
};

}  // namespace robotd::xarm::sim
