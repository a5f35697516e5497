// PiperDriver::diagnostics(): what DeviceStatus shows of the arm (robotctl status).
#include <algorithm>
#include <cstdio>

#include "driver/piper_driver.hpp"

namespace robotd::piper {

driver::Diagnostics PiperDriver::diagnostics() const {
  const ArmSnapshot snapshot = snapshot_.load_non_rt();
  const ArmState& arm = snapshot.arm;
  int enabled = 0;
  std::string driver_faults;
  for (std::size_t j = 0; j < kArmJoints; ++j) {
    if (arm.joints[j].enabled()) ++enabled;
    const std::string faults = driver_status_text(arm.joints[j].driver_status);
    if (!faults.empty()) driver_faults += (driver_faults.empty() ? "" : "; ") + params_.joints[j].name + ": " + faults;
  }
  std::array<char, 64> rates{};
  std::snprintf(rates.data(), rates.size(), "rx %.0f/s, tx %.0f/s", snapshot.rx_fps, snapshot.tx_fps);
  if (params_.leader()) {
    // A leader reports no status: what it commands is what there is to show.
    return {{"link", std::string(link_name_.data()) + (snapshot.link_up ? " (up)" : " (down)")},
            {"frames", rates.data()},
            {"role", "leader: robotd reads its commands and sends it nothing"},
            {"leader_mode", std::string(control_mode_text(arm.master_mode.ctrl_mode)) + ", " +
                                move_mode_text(arm.master_mode.move_mode) + (arm.master_mode.mit ? ", 0xAD" : "")}};
  }
  driver::Diagnostics values{
      {"link", std::string(link_name_.data()) + (snapshot.link_up ? " (up)" : " (down)")},
      {"frames", rates.data()},
      {"ctrl_mode", control_mode_text(arm.status.ctrl_mode)},
      {"arm_status", arm_status_text(arm.status.arm_status)},
      {"move_mode", move_mode_text(arm.status.mode_feed)},
      {"motion", arm.status.motion_status == 0 ? "target reached" : "moving"},
      {"enabled", std::to_string(enabled) + "/6 joints"},
      {"firmware",
       firmware_note_.empty() ? software_version(firmware_text_).value_or(params_.firmware) : firmware_note_},
  };
  if (!arm_limits_note_.empty()) values.emplace_back("arm_limits", arm_limits_note_);
  if (arm.status.angle_limit_bits != 0 || arm.status.comm_error_bits != 0) {
    std::array<char, 64> bits{};
    std::snprintf(bits.data(), bits.size(), "angle limit 0x%02X, communication 0x%02X", arm.status.angle_limit_bits,
                  arm.status.comm_error_bits);
    values.emplace_back("joint_errors", bits.data());
  }
  if (!driver_faults.empty()) values.emplace_back("driver_faults", driver_faults);
  if (arm.implausible_frames != 0) {
    values.emplace_back("implausible_frames", std::to_string(arm.implausible_frames) + " dropped (impossible values)");
  }
  if (arm.joints[0].low_speed_seen) {
    // The hottest motor and driver and the lowest bus voltage: enough to spot trouble at a glance;
    // the state op has every joint's values.
    int motor_c = arm.joints[0].motor_temperature_c;
    int driver_c = arm.joints[0].driver_temperature_c;
    double volts = arm.joints[0].voltage_v;
    for (const JointReport& joint : arm.joints) {
      motor_c = std::max(motor_c, joint.motor_temperature_c);
      driver_c = std::max(driver_c, joint.driver_temperature_c);
      volts = std::min(volts, joint.voltage_v);
    }
    std::array<char, 96> health{};
    std::snprintf(health.data(), health.size(), "motors up to %d °C, drivers up to %d °C, bus %.1f V", motor_c,
                  driver_c, volts);
    values.emplace_back("temperatures", health.data());
  }
  if (params_.gripper) {
    std::array<char, 96> gripper{};
    std::snprintf(gripper.data(), gripper.size(), "%s, %.1f mm, %.2f N·m%s%s",
                  (arm.gripper.status_bits & 0x40U) != 0 ? "enabled" : "disabled", arm.gripper.stroke_m * 1e3,
                  arm.gripper.effort_nm, (arm.gripper.status_bits & 0x3FU) != 0 ? ", " : "",
                  gripper_status_text(arm.gripper.status_bits).c_str());
    values.emplace_back("gripper", gripper.data());
  }
  if (hold_for_ops_.load()) values.emplace_back("streaming", "held: a device_call move drives the arm");
  return values;
}

}  // namespace robotd::piper
