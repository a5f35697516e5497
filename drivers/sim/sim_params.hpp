// The sim driver's "params" object, parsed and validated. Every error names its key path
// relative to params ("joints[2].inertia_kg_m2: expected a number > 0, got -1").
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "robotd/driver/driver.hpp"
#include "robotd/result.hpp"

namespace robotd::sim {

struct SimJointParams {
  std::string name;
  driver::JointLimits limits{
      .position_min_rad = -3.0,
      .position_max_rad = 3.0,
      .velocity_max_rad_s = 3.0,
      .acceleration_max_rad_s2 = 10.0,
      .effort_max_nm = 50.0,
      .kp_max = 500.0,
      .kd_max = 50.0,
  };
  double default_kp = 100.0;
  double default_kd = 5.0;
  double inertia_kg_m2 = 0.05;
  double damping_nm_s_rad = 0.5;  // viscous friction
  double external_torque_nm = 0;  // a constant load such as gravity
  double initial_position_rad = 0;
};

struct SimParams {
  std::string model = "robotd sim";
  // The arm model clients plan with (DeviceDescription::kinematic_model): lets a sim arm stand in
  // for a vendor arm in client-side planning. "" = none.
  std::string kinematic_model;
  std::vector<SimJointParams> joints;
  bool imu = false;
};

/// Joints come from either "joint_count" (named joint1..jointN) or "joints" (a list of named
/// joints); "joint_defaults" applies to each. All errors are reported at once.
Result<SimParams> parse_sim_params(const nlohmann::json& params);

}  // namespace robotd::sim
