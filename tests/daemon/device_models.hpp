// Device models built by hand, as a driver's describe() plus the config would give them, so
// the session, validator and loop tests need no driver.
#pragma once

#include <string>

#include "control/device_model.hpp"

namespace robotd::test {

/// Every joint gets the same limits, so a test can state its bounds once.
struct JointSpec {
  double position_min_rad = -2.0;
  double position_max_rad = 2.0;
  double velocity_max_rad_s = 1.0;
  double acceleration_max_rad_s2 = 10.0;
  double effort_max_nm = 5.0;
  double kp_max = 100.0;
  double kd_max = 10.0;
  double default_kp = 50.0;
  double default_kd = 2.0;
};

inline control::DeviceModel make_device_model(const std::string& name, std::size_t joint_count, bool supports_torque,
                                              control::BehaviorSupport behaviors, const JointSpec& spec = {}) {
  control::DeviceModel model;
  model.name = name;
  model.driver = "test";
  model.supports_torque = supports_torque;
  model.behaviors = behaviors;
  for (std::size_t j = 0; j < joint_count; ++j) {
    model.joint_names.push_back("j" + std::to_string(j));
    driver::JointLimits limits;
    limits.position_min_rad = spec.position_min_rad;
    limits.position_max_rad = spec.position_max_rad;
    limits.velocity_max_rad_s = spec.velocity_max_rad_s;
    limits.acceleration_max_rad_s2 = spec.acceleration_max_rad_s2;
    limits.effort_max_nm = spec.effort_max_nm;
    limits.kp_max = spec.kp_max;
    limits.kd_max = spec.kd_max;
    model.limits.push_back(limits);
    model.default_kp.push_back(spec.default_kp);
    model.default_kd.push_back(spec.default_kd);
  }
  return model;
}

/// A position-only arm: no torque, cannot damp or let go (the PiPER / xArm kind).
inline control::DeviceModel position_only_arm(const std::string& name = "arm", std::size_t joints = 6) {
  control::BehaviorSupport none;
  return make_device_model(name, joints, false, none);
}

/// A torque-capable chain that can damp and let go (the HighTorque kind).
inline control::DeviceModel torque_chain(const std::string& name = "legs", std::size_t joints = 4) {
  control::BehaviorSupport all;
  all.damping = true;
  all.zero_torque = true;
  return make_device_model(name, joints, true, all);
}

}  // namespace robotd::test
