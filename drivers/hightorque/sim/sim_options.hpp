// What the command line sets (main.cpp), checked: the buses with their motors, the motors'
// physics and identity, and the control channel.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "codec/hightorque_codec.hpp"
#include "robotd/result.hpp"

namespace robotd::hightorque::sim {

struct BusSpec {
  enum class Kind : std::uint8_t { kStandIn, kSocketCan, kBoard };
  Kind kind = Kind::kStandIn;
  std::string path;      // stand-in socket path, SocketCAN interface name, or the board's pty symlink
  std::vector<int> ids;  // ascending, each 1 … 126, no repeats
};

/// What the board's 0x0B answer reports for some of its motors: `ids` (empty: every board motor).
struct BoardMotorFirmware {
  std::vector<int> ids;
  FirmwareVersion version;
};

struct MotorPhysics {
  double inertia_kg_m2 = 0.02;
  double friction_nm_s_rad = 0.05;  // viscous
  double torque_max_nm = 40;
};

struct SimOptions {
  std::vector<BusSpec> buses;  // in command-line order: the control channel's "bus" index
  std::string control_path;    // --control; empty: no control channel
  MotorPhysics physics;
  std::string model = "5047_36";  // what 00 07 answers
  FirmwareVersion firmware{.motor = 0, .major = 0, .minor = 3, .patch = 3};
  double gain_factor = 1.0;          // MotorScaling::gain_factor, CAN-FD and board
  double board_torque_per_unit = 0;  // board τ LSB, N·m; 0: from the model (board_torque_per_unit())
  BoardFirmware board_firmware{.major = 4, .minor = 3};  // the board's own, its 0x05 answer
  /// The board motors' firmware (0x0B), applied in order over the default 4.4.6 (function v5).
  std::vector<BoardMotorFirmware> board_motor_firmware;
  bool quiet = false;
};

/// "1-6", "1,2,5", "1-4,7": ascending unique ids within 1 … 126.
Result<std::vector<int>> parse_motor_ids(std::string_view text);
/// "PATH:IDS" (split at the last colon) for `kind`; `option` names it in errors.
Result<BusSpec> parse_bus_spec(BusSpec::Kind kind, std::string_view text, std::string_view option);
/// "MAJOR.MINOR.PATCH", each 0 … 255; `option` names it in errors.
Result<FirmwareVersion> parse_firmware(std::string_view text, std::string_view option = "--firmware");
/// "MAJOR.MINOR", each 0 … 255 (--board-firmware).
Result<BoardFirmware> parse_board_firmware(std::string_view text);
/// "[IDS:]MAJOR.MINOR.PATCH" (--board-motor-firmware): without IDS, every board motor.
Result<BoardMotorFirmware> parse_board_motor_firmware(std::string_view text);
/// The livelybot board's torque LSB for a motor model (N·m per unit; 0.004938 for 5047_36),
/// or 0 for a model the SDK's table does not list.
double model_torque_per_unit(std::string_view model);

}  // namespace robotd::hightorque::sim
