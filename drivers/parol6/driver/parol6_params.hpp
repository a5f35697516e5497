// The PAROL6 driver's "params" object, parsed and validated (docs/drivers/parol6.md). Every
// error names its key path relative to params.
#pragma once

#include <array>
#include <string>

#include <nlohmann/json.hpp>

#include "codec/joint_units.hpp"
#include "robotd/driver/driver.hpp"
#include "robotd/result.hpp"
#include "robotd/transport/serial_port.hpp"

namespace robotd::parol6 {

struct Parol6Params {
  std::string model = "PAROL6";
  transport::SerialConfig serial;
  double exchange_rate_hz = 100;  // frames per second to the board (it answers each)
  // No reply this long while sending: the link is lost. Below robotd's feedback_timeout_ms
  // (100 ms), so that a silent board is a lost link the driver names and reconnects, not the loop's
  // generic "no feedback" fault racing it on the same tick.
  int reply_timeout_ms = 50;
  int connect_timeout_ms = 500;    // the board must answer this soon after opening the port
  bool home_on_connect = false;    // run the homing sequence when the link comes up
  int gripper_id = 0;              // the SSG-48's CAN node id, 0 … 15
  int gripper_speed = 100;         // default set points for the gripper op (0 … 255)
  double gripper_current_a = 0.5;  // 0 … 1.3 (gripper_current.hpp)
  std::array<driver::JointLimits, kJoints> limits{};
};

/// Defaults from the spec's tables (§10), overridden by "joints": {"joint2": {...}}.
Result<Parol6Params> parse_parol6_params(const nlohmann::json& params);

}  // namespace robotd::parol6
