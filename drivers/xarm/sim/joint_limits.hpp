// The model's joint limits as the simulator applies them: the codec's check, which forgives the
// wire's fp32 rounding (a target sent exactly at a limit arrives a hair beyond it), and such a
// target put on the limit, so the joints never leave their range.
#pragma once

#include "codec/xarm_codec.hpp"
#include "robotd/result.hpp"

namespace robotd::xarm::sim {

/// `joints` with values within 1e-6 rad beyond a limit put on it; kInvalidArgument naming the
/// joint when one is further out.
Result<JointValues> within_limits(const JointValues& joints, const ArmModel& model);

/// Home: every joint at 0 where the model's limits allow it, else at the nearest limit (where the
/// arm powers on, and where move_gohome goes).
JointValues home_joints(const ArmModel& model);

}  // namespace robotd::xarm::sim
