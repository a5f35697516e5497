// Forward kinematics, the geometric Jacobian and the damped-least-squares inverse of any arm
// model. Everything but inverse_kinematics is allocation-free: fixed-size Eigen with at most
// kMaxArmJoints columns.
#include <algorithm>
#include <cmath>
#include <cstddef>

#include <Eigen/SVD>

#include "robotd/kinematics/arm_model.hpp"

namespace robotd::kinematics {
namespace {

using Twist = Eigen::Matrix<double, 6, 1>;
constexpr auto kMaxColumns = static_cast<int>(kMaxArmJoints);
using JointStep = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxColumns, 1>;

Eigen::Isometry3d link_transform(DhConvention convention, const DhLink& link, double q_rad) {
  const double theta = q_rad + link.theta_offset_rad;
  const double ct = std::cos(theta);
  const double st = std::sin(theta);
  const double ca = std::cos(link.alpha_rad);
  const double sa = std::sin(link.alpha_rad);
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  if (convention == DhConvention::kStandard) {
    transform.linear() << ct, -st * ca, st * sa, st, ct * ca, -ct * sa, 0.0, sa, ca;
    transform.translation() << link.a_m * ct, link.a_m * st, link.d_m;
  } else {
    transform.linear() << ct, -st, 0.0, st * ca, ct * ca, -sa, st * sa, ct * sa, ca;
    transform.translation() << link.a_m, -sa * link.d_m, ca * link.d_m;
  }
  return transform;
}

/// Where joint i turns: its axis (unit) and a point on it, in the base frame, and the tool.
struct JointAxes {
  std::array<Eigen::Vector3d, kMaxArmJoints> axis;
  std::array<Eigen::Vector3d, kMaxArmJoints> origin;
  Eigen::Isometry3d tool;
};

JointAxes joint_axes(const ArmModel& model, const ArmJoints& q_rad) {
  JointAxes axes;
  Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();
  for (std::size_t i = 0; i < model.dof; ++i) {
    const Eigen::Isometry3d link = link_transform(model.convention, model.links[i], q_rad[i]);
    // Standard DH turns joint i about the z axis of the frame before its link, modified DH about
    // the frame after it (its Rz comes after the link's Rx·Tx, and Tz runs along the axis).
    const Eigen::Isometry3d& turning = model.convention == DhConvention::kStandard ? frame : frame * link;
    axes.axis[i] = turning.linear().col(2);
    axes.origin[i] = turning.translation();
    frame = frame * link;
  }
  axes.tool = frame * model.tool;
  return axes;
}

ArmJacobian jacobian_of(const JointAxes& axes, std::size_t dof) {
  ArmJacobian result(6, static_cast<Eigen::Index>(dof));
  const Eigen::Vector3d tip = axes.tool.translation();
  for (std::size_t i = 0; i < dof; ++i) {
    const auto column = static_cast<Eigen::Index>(i);
    result.block<3, 1>(0, column) = axes.axis[i].cross(tip - axes.origin[i]);
    result.block<3, 1>(3, column) = axes.axis[i];
  }
  return result;
}

ArmJoints clamped(const ArmJoints& q, const ArmJoints& min_rad, const ArmJoints& max_rad, std::size_t dof) {
  ArmJoints out = q;
  for (std::size_t i = 0; i < dof; ++i) out[i] = std::clamp(q[i], min_rad[i], std::max(min_rad[i], max_rad[i]));
  return out;
}

bool below(const Twist& error, double position_m, double orientation_rad) {
  return error.head<3>().norm() < position_m && error.tail<3>().norm() < orientation_rad;
}

}  // namespace

std::array<Eigen::Isometry3d, kMaxArmJoints> link_frames(const ArmModel& model, const ArmJoints& q_rad) noexcept {
  std::array<Eigen::Isometry3d, kMaxArmJoints> frames;
  Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();
  for (std::size_t i = 0; i < kMaxArmJoints; ++i) {
    if (i < model.dof) frame = frame * link_transform(model.convention, model.links[i], q_rad[i]);
    frames[i] = frame;
  }
  return frames;
}

Eigen::Isometry3d tool_pose(const ArmModel& model, const ArmJoints& q_rad) noexcept {
  Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();
  for (std::size_t i = 0; i < model.dof; ++i)
    frame = frame * link_transform(model.convention, model.links[i], q_rad[i]);
  return frame * model.tool;
}

ArmJacobian jacobian(const ArmModel& model, const ArmJoints& q_rad) noexcept {
  return jacobian_of(joint_axes(model, q_rad), model.dof);
}

double smallest_singular_value(const ArmModel& model, const ArmJoints& q_rad) noexcept {
  const Eigen::JacobiSVD<ArmJacobian> svd(jacobian(model, q_rad));
  return svd.singularValues().minCoeff();
}

Eigen::Matrix<double, 6, 1> pose_error(const Eigen::Isometry3d& goal, const Eigen::Isometry3d& current) noexcept {
  const Eigen::AngleAxisd rotation(goal.linear() * current.linear().transpose());
  Twist error;
  error.head<3>() = goal.translation() - current.translation();
  error.tail<3>() = rotation.angle() * rotation.axis();
  return error;
}

IkSolution inverse_kinematics(const ArmModel& model, const Eigen::Isometry3d& goal, const ArmJoints& seed,
                              const ArmJoints& min_rad, const ArmJoints& max_rad, const IkOptions& options) {
  constexpr double kInitialDamping = 1e-3;  // λ²
  constexpr double kMinDamping = 1e-9;
  constexpr double kMaxDamping = 1e6;
  const std::size_t dof = model.dof;

  IkSolution result;
  result.q_rad = clamped(seed, min_rad, max_rad, dof);
  JointAxes axes = joint_axes(model, result.q_rad);
  Twist error = pose_error(goal, axes.tool);
  double damping = kInitialDamping;
  int refusals = 0;
  for (; result.iterations < options.max_iterations && refusals < options.max_refusals &&
         !below(error, options.stop_position_m, options.stop_orientation_rad);
       ++result.iterations) {
    ArmJacobian jacobian = jacobian_of(axes, dof);
    JointStep step;
    // A joint at a limit that the step pushes further out is taken out of the step, which is then
    // solved again: clamping alone would leave the other joints a direction they cannot follow.
    for (std::size_t pass = 0; pass < dof; ++pass) {
      const Eigen::Matrix<double, 6, 6> normal =
          jacobian * jacobian.transpose() + damping * Eigen::Matrix<double, 6, 6>::Identity();
      step = jacobian.transpose() * normal.ldlt().solve(error);
      bool blocked = false;
      for (std::size_t i = 0; i < dof; ++i) {
        const auto joint = static_cast<Eigen::Index>(i);
        const double q = result.q_rad[i];
        if ((q <= min_rad[i] && step(joint) < 0) || (q >= max_rad[i] && step(joint) > 0)) {
          jacobian.col(joint).setZero();
          step(joint) = 0;
          blocked = true;
        }
      }
      if (!blocked) break;
    }
    ArmJoints candidate = result.q_rad;
    for (std::size_t i = 0; i < dof; ++i) candidate[i] += step(static_cast<Eigen::Index>(i));
    candidate = clamped(candidate, min_rad, max_rad, dof);
    const JointAxes candidate_axes = joint_axes(model, candidate);
    const Twist candidate_error = pose_error(goal, candidate_axes.tool);
    if (candidate_error.squaredNorm() < error.squaredNorm()) {
      result.q_rad = candidate;
      axes = candidate_axes;
      error = candidate_error;
      damping = std::max(damping * 0.3, kMinDamping);
      refusals = 0;
    } else {
      damping = std::min(damping * 10.0, kMaxDamping);
      ++refusals;
    }
  }
  result.position_error_m = error.head<3>().norm();
  result.orientation_error_rad = error.tail<3>().norm();
  result.converged = below(error, options.converged_position_m, options.converged_orientation_rad);
  return result;
}

}  // namespace robotd::kinematics
