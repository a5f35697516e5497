// robotd's messages as robotctl prints them for people.
#pragma once

#include <string>
#include <vector>

#include "robotd/messages.hpp"

namespace robotctl {

/// One row per device: name, driver and version, model, kinematic model (the arm
/// model clients plan with, "-" when none), joints, rate, control modes, state.
std::string device_table(const std::vector<robotd::DeviceInfo>& devices);
/// A block: state, fault, e-stop, loop timing, command counters, driver values.
std::string device_status_text(const robotd::DeviceStatus& status);
/// One row per session (public id, node, device, motors, mode, timeout fallback, time left, commands
/// accepted), or "no active sessions".
std::string session_table(const robotd::SessionStatus& status);
/// A block: commands no device could count, each service's requests, refusals and oversized
/// requests, the DDS layer's messages.
std::string surface_text(const robotd::SurfaceCounters& surface);
std::string joint_state_text(const robotd::JointState& state);
std::string imu_text(const robotd::Imu& imu);
std::string end_pose_text(const robotd::PoseStamped& pose);
/// Sticks, triggers and d-pad, and the names of the buttons held.
std::string joy_text(const robotd::Joy& joy);
/// data_type, stamp, and the values (each to 6 significant digits).
std::string policy_data_text(const robotd::PolicyData& data);

/// The state name, followed by robotd's explanation when it says more ("ESTOP (e-stop engaged by ...)").
std::string state_text(const robotd::DeviceStatus& status);
/// "DAMPING", or "DAMPING → KEEP" when the device applies something other than what was asked.
std::string behavior_text(robotd::Behavior requested, robotd::Behavior applied);

}  // namespace robotctl
