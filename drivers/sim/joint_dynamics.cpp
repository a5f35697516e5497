#include "joint_dynamics.hpp"

#include <algorithm>
#include <cmath>

namespace robotd::sim {
namespace {

void substep(const JointPhysics& physics, const MotorLaw& law, double external_torque_nm, double h_s,
             JointState& state) noexcept {
  const double inertia = physics.inertia_kg_m2;
  // The motor torque without its −kd·dq term, which is solved for implicitly below.
  const double spring_torque =
      law.kp * (law.position_rad - state.position_rad) + law.kd * law.velocity_rad_s + law.torque_nm;
  // inertia·(v' − v)/h = spring_torque − kd·v' + external − damping·v'
  double velocity = (inertia * state.velocity_rad_s + h_s * (spring_torque + external_torque_nm)) /
                    (inertia + h_s * (law.kd + physics.damping_nm_s_rad));
  double motor_torque = spring_torque - law.kd * velocity;
  if (std::abs(motor_torque) > physics.effort_max_nm) {
    motor_torque = std::clamp(motor_torque, -physics.effort_max_nm, physics.effort_max_nm);
    velocity = (inertia * state.velocity_rad_s + h_s * (motor_torque + external_torque_nm)) /
               (inertia + h_s * physics.damping_nm_s_rad);
  }
  double position = state.position_rad + h_s * velocity;
  if (position <= physics.position_min_rad) {
    position = physics.position_min_rad;
    velocity = std::max(velocity, 0.0);
  } else if (position >= physics.position_max_rad) {
    position = physics.position_max_rad;
    velocity = std::min(velocity, 0.0);
  }
  state = JointState{.position_rad = position, .velocity_rad_s = velocity, .motor_torque_nm = motor_torque};
}

}  // namespace

void step_joint(const JointPhysics& physics, const MotorLaw& law, double external_torque_nm, double dt_s,
                JointState& state) noexcept {
  if (!(dt_s > 0)) return;
  const double step_s = std::min(dt_s, kMaxStepS);
  const int substeps = static_cast<int>(std::ceil(step_s / kMaxSubstepS));
  const double h_s = step_s / substeps;
  for (int i = 0; i < substeps; ++i) substep(physics, law, external_torque_nm, h_s, state);
}

}  // namespace robotd::sim
