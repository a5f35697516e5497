// The settings clean_conf restores and save_conf remembers (in memory only: a restart loses
// both): TCP offset, payload, motion limits, sensitivities.
#pragma once

#include <array>

#include "codec/xarm_codec.hpp"

namespace robotd::xarm::sim {

struct MotionConfig {
  Pose tcp_offset;  // from the flange
  double payload_kg = 0;
  std::array<double, 3> payload_centre_m{};
  // Defaults are the ends of the spec's ranges (§7): they cap nothing until set. The
  // accelerations cap the planned moves' own; the jerks are stored only (the profiles are
  // trapezoids).
  double tcp_jerk_m_s3 = 100;
  double tcp_max_acc_m_s2 = 50;
  double joint_jerk_rad_s3 = 500;
  double joint_max_acc_rad_s2 = 20;
  int collision_sensitivity = 3;
  int teach_sensitivity = 3;
};

}  // namespace robotd::xarm::sim
