// What robotd knows about one device once its driver is configured: the driver's description
// narrowed by the config's limit overrides. Built before the loop starts and read-only after,
// so the RT thread may read it freely.
#pragma once

#include <string>
#include <vector>

#include "control/behavior_map.hpp"
#include "robotd/driver/driver.hpp"
#include "robotd/messages.hpp"

namespace robotd::control {

enum class LimitPolicy { kReject, kClamp };

struct DeviceModel {
  std::string name;
  std::string driver;
  std::string driver_version;
  std::string model;
  std::string kinematic_model;  // the arm model clients plan with, "" when none
  double rate_hz = 1000;
  double native_rate_hz = 1000;
  std::vector<std::string> joint_names;
  std::vector<driver::JointLimits> limits;
  std::vector<double> default_kp;
  std::vector<double> default_kd;
  std::vector<double> zero_position_rad;  // what reset_zero leaves each joint reading
  bool supports_torque = false;
  BehaviorSupport behaviors;
  bool has_imu = false;
  bool has_end_pose = false;
  LimitPolicy limit_policy = LimitPolicy::kReject;
  std::vector<driver::OpDescription> ops;
  std::string read_only_reason;  // non-empty: no control modes; control requests are refused

  std::size_t joint_count() const { return joint_names.size(); }
  std::vector<ControlMode> control_modes() const;
};

}  // namespace robotd::control
