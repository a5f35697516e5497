// The HighTorque driver's "params" object, parsed and validated (docs/drivers/hightorque.md):
// the buses, the motor models' scalings and the joint map (logical motor id → bus, CAN id,
// direction, zero offset, limits, default gains), like the PI Plus joints.yaml. Every error
// names its key path relative to params.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "codec/hightorque_codec.hpp"
#include "robotd/driver/driver.hpp"
#include "robotd/result.hpp"
#include "robotd/transport/can_transport.hpp"
#include "robotd/transport/serial_port.hpp"

namespace robotd::hightorque {

struct BusParams {
  enum class Kind : std::uint8_t {
    kCanFd,  // the CAN-FD protocol on SocketCAN or the stand-in
    kBoard,  // the livelybot USB-CDC CAN board: one tty is one CAN port
  };
  std::string name;
  Kind kind = Kind::kCanFd;
  transport::CanLinkConfig can;
  transport::SerialConfig serial;
};

/// What the set_motor_timeout op may set: a shorter watchdog brakes the motors under normal
/// jitter, a longer one lets a robot fall before they brake. 0 (disarmed) only through the config.
inline constexpr int kMinMotorTimeoutMs = 20;
inline constexpr int kMaxMotorTimeoutMs = 1000;

struct MotorParams {
  std::string name;     // the joint's name in /joint_states
  std::size_t bus = 0;  // index into HighTorqueParams::buses
  int id = 1;           // the motor's CAN id on its bus, 1…126
  int direction = 1;    // +1 or −1: joint = direction × motor + zero_offset_rad
  double zero_offset_rad = 0;
  std::string model;  // key of motor_models
  MotorScaling scaling;
  driver::JointLimits limits;
  // Both must be above 0: DAMPING holds a joint with kp = 0 and kd = default_kd, and KEEP holds a
  // joint that was not tracking (after a TORQUE session) with both. 40 and 1.0 are the shipped
  // PI Plus configs' values; 1.0 is also the kd of the vendor's own passive (damping) mode.
  double default_kp = 40;
  double default_kd = 1.0;
};

struct HighTorqueParams {
  std::string model = "HighTorque motors";
  std::vector<BusParams> buses;
  std::vector<MotorParams> motors;  // index = logical motor id (robotd's joint index)
  Width width = Width::kInt16;      // parameter width of single-motor frames (blocks are int16)
  /// Each motor's own command timeout (system command 0x05): no command this long and the motor
  /// brakes by itself, so the robot brakes when robotd dies. 0 disarms it (diagnostics say so).
  int motor_timeout_ms = 200;
  int feedback_timeout_ms = 50;  // no reply from a bus this long: its link is lost
  int connect_timeout_ms = 500;  // every motor must answer this soon after the link opens
  int reply_timeout_ms = 300;    // ops and zeroing wait this long for a motor's answer
  int zero_settle_ms = 300;      // reset_zero: motors at zero torque this long before zeroing
  bool zero_save_to_flash = true;
  std::optional<nlohmann::json> imu;  // an IMU source's params (robotd/imu/imu_source.hpp)

  /// Motors on bus `bus`, as indices into motors.
  std::vector<std::size_t> motors_on(std::size_t bus) const;
};

Result<HighTorqueParams> parse_hightorque_params(const nlohmann::json& params);

}  // namespace robotd::hightorque
