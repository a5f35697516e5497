// Rigid single-joint dynamics behind a motor: pure math, no I/O, no allocation.
//
//   inertia · accel = τ_motor + τ_external − damping · velocity
//   τ_motor = clamp(kp·(position − q) + kd·(velocity − dq) + torque, ±effort_max)
//
// Every command kind reduces to this motor law: unpowered is all zeros, a PD servo has
// torque = 0, damping has kp = 0.
#pragma once

namespace robotd::sim {

struct JointPhysics {
  double inertia_kg_m2 = 0.05;
  double damping_nm_s_rad = 0.5;   // viscous friction
  double position_min_rad = -3.0;  // hard stops
  double position_max_rad = 3.0;
  double effort_max_nm = 50.0;
};

struct MotorLaw {
  double kp = 0;  // N·m/rad
  double kd = 0;  // N·m·s/rad
  double position_rad = 0;
  double velocity_rad_s = 0;
  double torque_nm = 0;  // feed-forward
};

struct JointState {
  double position_rad = 0;
  double velocity_rad_s = 0;
  double motor_torque_nm = 0;  // applied during the last substep
};

/// Longest integration substep; a step is split into equal substeps no longer than this.
inline constexpr double kMaxSubstepS = 0.25e-3;
/// Longest step: a caller that stalls makes the joint lag rather than leap.
inline constexpr double kMaxStepS = 20e-3;

/// Advances `state` by `dt_s` seconds, cut to [0, kMaxStepS]. Semi-implicit Euler with the
/// damping terms implicit, so a high kd over a small inertia stays stable.
void step_joint(const JointPhysics& physics, const MotorLaw& law, double external_torque_nm, double dt_s,
                JointState& state) noexcept;

}  // namespace robotd::sim
