#include "robotd/kinematics/serial_chain.hpp"

#include <algorithm>

namespace robotd::kinematics {
namespace {

JointArray clamped(const JointArray& q, const JointArray& min_rad, const JointArray& max_rad) {
  JointArray out{};
  for (std::size_t i = 0; i < q.size(); ++i) out[i] = std::max(min_rad[i], std::min(q[i], max_rad[i]));
  return out;
}

bool below(const Twist& error, const DlsOptions& options) {
  return error.head<3>().norm() < options.stop_position_m && error.tail<3>().norm() < options.stop_orientation_rad;
}

}  // namespace

Jacobian geometric_jacobian(const ChainFrames& frames) noexcept {
  const Eigen::Vector3d tip = frames.back().translation();
  Jacobian jacobian;
  for (std::size_t i = 0; i < kChainJoints; ++i) {
    const Eigen::Vector3d axis = frames[i].linear().col(2);
    const auto column = static_cast<Eigen::Index>(i);
    jacobian.block<3, 1>(0, column) = axis.cross(tip - frames[i].translation());
    jacobian.block<3, 1>(3, column) = axis;
  }
  return jacobian;
}

Twist pose_error(const Eigen::Isometry3d& goal, const Eigen::Isometry3d& current) noexcept {
  const Eigen::AngleAxisd rotation(goal.linear() * current.linear().transpose());
  Twist error;
  error.head<3>() = goal.translation() - current.translation();
  error.tail<3>() = rotation.angle() * rotation.axis();
  return error;
}

DlsResult solve_dls(const Eigen::Isometry3d& goal, const JointArray& seed, const JointArray& min_rad,
                    const JointArray& max_rad, const std::function<ChainFrames(const JointArray&)>& frames_of,
                    const DlsOptions& options) {
  constexpr double kInitialDamping = 1e-3;  // λ²
  constexpr double kMinDamping = 1e-9;
  constexpr double kMaxDamping = 1e6;
  constexpr auto kJoints = static_cast<int>(kChainJoints);

  DlsResult result;
  result.q_rad = clamped(seed, min_rad, max_rad);
  ChainFrames frames = frames_of(result.q_rad);
  result.error = pose_error(goal, frames.back());
  double damping = kInitialDamping;
  int refusals = 0;
  for (; result.iterations < options.max_iterations && refusals < options.max_refusals && !below(result.error, options);
       ++result.iterations) {
    Jacobian jacobian = geometric_jacobian(frames);
    Eigen::Matrix<double, kJoints, 1> step;
    // A joint at a limit that the step pushes further out is taken out of the step, which is then
    // solved again: clamping alone would leave the other joints a direction they cannot follow.
    for (int pass = 0; pass < kJoints; ++pass) {
      const Eigen::Matrix<double, 6, 6> normal =
          jacobian * jacobian.transpose() + damping * Eigen::Matrix<double, 6, 6>::Identity();
      step = jacobian.transpose() * normal.ldlt().solve(result.error);
      bool blocked = false;
      for (std::size_t i = 0; i < kChainJoints; ++i) {
        const auto joint = static_cast<Eigen::Index>(i);
        const double q = result.q_rad[i];
        if ((q <= min_rad[i] && step(joint) < 0) || (q >= max_rad[i] && step(joint) > 0)) {
          jacobian.col(joint).setZero();
          blocked = true;
        }
      }
      if (!blocked) break;
    }
    JointArray candidate{};
    for (std::size_t i = 0; i < kChainJoints; ++i) candidate[i] = result.q_rad[i] + step(static_cast<Eigen::Index>(i));
    candidate = clamped(candidate, min_rad, max_rad);
    const ChainFrames candidate_frames = frames_of(candidate);
    const Twist candidate_error = pose_error(goal, candidate_frames.back());
    if (candidate_error.squaredNorm() < result.error.squaredNorm()) {
      result.q_rad = candidate;
      frames = candidate_frames;
      result.error = candidate_error;
      damping = std::max(damping * 0.3, kMinDamping);
      refusals = 0;
    } else {
      damping = std::min(damping * 10.0, kMaxDamping);
      ++refusals;
    }
  }
  return result;
}

}  // namespace robotd::kinematics
