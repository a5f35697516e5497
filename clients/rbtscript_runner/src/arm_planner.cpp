#include "robotd/rbtscript/arm_planner.hpp"

#include <cmath>
#include <cstddef>
#include <numbers>
#include <utility>
#include <vector>

#include "robotd/motion/cartesian_move.hpp"

namespace robotd::rbtscript {
namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180.0;
constexpr double kMPerMm = 1e-3;

Error invalid(std::string message) { return Error{ErrorCode::kInvalidArgument, std::move(message)}; }

motion::MoveTiming timing_of(const JointMotion& motion) {
  motion::MoveTiming timing;
  timing.duration_s = motion.duration_s;
  timing.speed_percent = motion.speed_percent;
  timing.acceleration_percent = motion.acceleration_percent;
  if (motion.profile) {
    timing.shape = *motion.profile == Profile::kTrapezoid ? motion::Shape::kTrapezoid : motion::Shape::kPolynomial;
  }
  return timing;
}

motion::MoveTiming timing_of(const CartesianMotion& motion) {
  JointMotion joint;
  joint.duration_s = motion.duration_s;
  joint.profile = motion.profile;
  return timing_of(joint);
}

kinematics::EulerPose si_pose(const Pose& pose) {
  kinematics::EulerPose euler;
  euler.position_m = {pose.x_mm * kMPerMm, pose.y_mm * kMPerMm, pose.z_mm * kMPerMm};
  euler.angles_rad = {pose.rx_deg * kRadPerDeg, pose.ry_deg * kRadPerDeg, pose.rz_deg * kRadPerDeg};
  return euler;
}

Result<PlannedMove> planned(Result<motion::Trajectory> plan, Tracking tracking) {
  if (!plan) return plan.error();
  return PlannedMove{std::move(plan).value(), tracking};
}

}  // namespace

ArmPlanner::ArmPlanner(DeviceInfo device, const kinematics::ArmModel* model, motion::JointLimits limits)
    : device_(std::move(device)), model_(model), limits_(std::move(limits)) {}

Result<ArmPlanner> ArmPlanner::for_device(const DeviceInfo& device) {
  const std::size_t joints = device.joint_names.size();
  if (joints == 0) return invalid("device '" + device.name + "' lists no joints");
  if (device.position_min.size() != joints || device.position_max.size() != joints ||
      device.velocity_max.size() != joints || device.acceleration_max.size() != joints) {
    return invalid("device '" + device.name +
                   "' does not list position, velocity and acceleration limits for each of its " +
                   std::to_string(joints) + " joints: a script needs them to plan its moves");
  }
  const kinematics::ArmModel* model = nullptr;
  if (!device.kinematic_model.empty()) {
    model = kinematics::find_arm_model(device.kinematic_model);
    if (model == nullptr) {
      return invalid("device '" + device.name + "' names the arm model '" + device.kinematic_model +
                     "', which this client does not know (a newer robotd?)");
    }
    if (model->dof > joints) {
      return invalid("device '" + device.name + "' has " + std::to_string(joints) + " joints but its arm model '" +
                     device.kinematic_model + "' has " + std::to_string(model->dof));
    }
  }
  // The arm's joints come first; any after them (a PiPER's gripper) are not the arm's.
  const auto arm_joints = static_cast<std::ptrdiff_t>(model != nullptr ? model->dof : joints);
  const auto first = [arm_joints](const std::vector<double>& values) {
    return std::vector<double>(values.begin(), values.begin() + arm_joints);
  };
  motion::JointLimits limits{first(device.position_min), first(device.position_max), first(device.velocity_max),
                             first(device.acceleration_max)};
  return ArmPlanner(device, model, std::move(limits));
}

Result<const kinematics::ArmModel*> ArmPlanner::model_for(const std::string& statement) const {
  if (model_ != nullptr) return model_;
  return invalid(statement + " needs the arm's kinematics, and device '" + device_.name + "' (driver " +
                 device_.driver + ") names no arm model; use MoveJoint");
}

Result<motion::Trajectory> ArmPlanner::plan_joints(const motion::Joints& from, const motion::Joints& to_rad,
                                                   const motion::MoveTiming& timing) const {
  if (to_rad.size() != joint_count()) {
    return invalid("the target gives " + std::to_string(to_rad.size()) + " joint value(s); device '" + device_.name +
                   "' has " + std::to_string(joint_count()) + " joints");
  }
  return motion::plan_joint_move(from, to_rad, timing, limits_, kPlanningStepS);
}

Result<motion::Trajectory> ArmPlanner::plan_pose(const motion::Joints& from, const kinematics::EulerPose& goal,
                                                 const motion::MoveTiming& timing, bool straight_line) const {
  auto model = model_for(straight_line ? "a straight-line move" : "a move to a pose");
  if (!model) return model.error();
  const Eigen::Isometry3d transform = kinematics::transform_of(model.value()->euler, goal);
  if (straight_line) {
    return motion::plan_line_move(*model.value(), from, transform, timing, limits_, kPlanningStepS);
  }
  return motion::plan_pose_move(*model.value(), from, transform, timing, limits_, kPlanningStepS);
}

Result<PlannedMove> ArmPlanner::plan(const MoveJoint& statement, const motion::Joints& from) const {
  if (statement.joints_deg.size() != joint_count()) {
    return invalid("MoveJoint gives " + std::to_string(statement.joints_deg.size()) + " joint value(s); device '" +
                   device_.name + "' has " + std::to_string(joint_count()) + " joints");
  }
  motion::Joints to;
  for (const double degrees : statement.joints_deg) to.push_back(degrees * kRadPerDeg);
  return planned(plan_joints(from, to, timing_of(statement.motion)), statement.motion.tracking);
}

Result<PlannedMove> ArmPlanner::plan(const MovePose& statement, const motion::Joints& from) const {
  if (auto model = model_for("MovePose"); !model) return model.error();
  return planned(plan_pose(from, si_pose(statement.pose), timing_of(statement.motion), false),
                 statement.motion.tracking);
}

Result<PlannedMove> ArmPlanner::plan(const MoveCart& statement, const motion::Joints& from) const {
  if (auto model = model_for("MoveCart"); !model) return model.error();
  return planned(plan_pose(from, si_pose(statement.pose), timing_of(statement.motion), true),
                 statement.motion.tracking);
}

Result<PlannedMove> ArmPlanner::plan(const MoveCartRelTrf& statement, const motion::Joints& from) const {
  auto model = model_for("MoveCartRelTRF");
  if (!model) return model.error();
  const Eigen::Isometry3d delta = kinematics::transform_of(model.value()->euler, si_pose(statement.delta));
  return planned(motion::plan_tool_relative_move(*model.value(), from, delta, timing_of(statement.motion), limits_,
                                                 kPlanningStepS),
                 statement.motion.tracking);
}

}  // namespace robotd::rbtscript
