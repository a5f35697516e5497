// What a move becomes on one arm: a planned trajectory (robotd/motion) from given joint
// positions, on the device's joint limits and the arm model its driver names
// (DeviceInfo.kinematic_model). The one place that reads limits and model from a DeviceInfo: an
// RBTscript statement (in the script's units, degrees and mm), and the library's moves in SI
// units (robotd/motion/session_moves.hpp), both plan through here, so what a dry run accepts is
// what a run does.
#pragma once

#include <string>

#include "robotd/kinematics/arm_model.hpp"
#include "robotd/messages.hpp"
#include "robotd/motion/joint_move.hpp"
#include "robotd/motion/trajectory.hpp"
#include "robotd/rbtscript/program.hpp"
#include "robotd/result.hpp"

namespace robotd::rbtscript {

/// The planning step: the commander's loop interval (INTERVAL_S, 10 ms). The streamer
/// interpolates the samples to the device's own period.
inline constexpr double kPlanningStepS = 0.01;

/// A planned move and how to follow it.
struct PlannedMove {
  motion::Trajectory trajectory;
  Tracking tracking = Tracking::kPosition;
};

class ArmPlanner {
 public:
  /// For `device` as /list_devices describes it. Fails (kInvalidArgument) when the device has no
  /// joint limits to plan with or names an arm model robotd does not know or that has more joints
  /// than the device.
  static Result<ArmPlanner> for_device(const DeviceInfo& device);

  const DeviceInfo& device() const { return device_; }
  /// The joints a program moves: the device's first joints, as many as its arm model has (all of
  /// them without a model). Joints after those (a PiPER's gripper) are not planned or streamed:
  /// the Gripper statement drives them.
  std::size_t joint_count() const { return limits_.min_rad.size(); }
  /// nullptr when the device names no arm model: joint moves only.
  const kinematics::ArmModel* model() const { return model_; }

  /// A joint move to `to_rad`, one value per joint.
  Result<motion::Trajectory> plan_joints(const motion::Joints& from, const motion::Joints& to_rad,
                                         const motion::MoveTiming& timing) const;
  /// A move of the tool to `goal` (in the model's Euler convention): a joint move to the goal's
  /// IK solution, or the straight line (`timing`'s v and a do not apply to a line).
  Result<motion::Trajectory> plan_pose(const motion::Joints& from, const kinematics::EulerPose& goal,
                                       const motion::MoveTiming& timing, bool straight_line) const;

  Result<PlannedMove> plan(const MoveJoint& statement, const motion::Joints& from) const;
  Result<PlannedMove> plan(const MovePose& statement, const motion::Joints& from) const;
  Result<PlannedMove> plan(const MoveCart& statement, const motion::Joints& from) const;
  Result<PlannedMove> plan(const MoveCartRelTrf& statement, const motion::Joints& from) const;

 private:
  ArmPlanner(DeviceInfo device, const kinematics::ArmModel* model, motion::JointLimits limits);
  // The model, or why `statement` needs one.
  Result<const kinematics::ArmModel*> model_for(const std::string& statement) const;

  DeviceInfo device_;
  const kinematics::ArmModel* model_ = nullptr;
  motion::JointLimits limits_;
};

}  // namespace robotd::rbtscript
