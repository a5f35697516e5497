// ArmModel's Cartesian moves: MOVE P, MOVE L and MOVE C through the kinematics' IK (spec §4.3,
// §4.5). No solution: arm status 0x02 and no motion.
#include <algorithm>
#include <cmath>

#include "arm_model.hpp"

namespace robotd::piper::sim {
namespace {

constexpr double kLinearIkPeriodS = 5e-3;  // MOVE L: a new IK waypoint this often

bool same_pose(const CartesianPose& a, const CartesianPose& b) {
  constexpr double kEpsilon = 1e-9;
  return std::abs(a.x_m - b.x_m) < kEpsilon && std::abs(a.y_m - b.y_m) < kEpsilon &&
         std::abs(a.z_m - b.z_m) < kEpsilon && std::abs(a.rx_rad - b.rx_rad) < kEpsilon &&
         std::abs(a.ry_rad - b.ry_rad) < kEpsilon && std::abs(a.rz_rad - b.rz_rad) < kEpsilon;
}

}  // namespace

void ArmModel::end_pose_target(const EndPoseTargetPart& frame) {
  if (!accepts_motion() || frame.part < 0 || frame.part > 2) return;
  if (move_mode_ != MoveMode::kP && move_mode_ != MoveMode::kL && move_mode_ != MoveMode::kC) return;
  const auto part = static_cast<std::size_t>(frame.part);
  pose_parts_[2 * part] = frame.first;
  pose_parts_[2 * part + 1] = frame.second;
  pose_parts_seen_ = static_cast<std::uint8_t>(pose_parts_seen_ | (1U << part));
  if (pose_parts_seen_ != 0x07) return;  // a pose counts once all three frames have arrived
  pose_parts_seen_ = 0;
  const CartesianPose pose{.x_m = pose_parts_[0],
                           .y_m = pose_parts_[1],
                           .z_m = pose_parts_[2],
                           .rx_rad = pose_parts_[3],
                           .ry_rad = pose_parts_[4],
                           .rz_rad = pose_parts_[5]};
  if (move_mode_ == MoveMode::kC) {
    received_pose_ = pose;  // 0x158 says which point of the arc it is
  } else {
    start_pose_move(pose);
  }
}

void ArmModel::move_c_point(const MoveCPoint& frame) {
  if (!accepts_motion() || move_mode_ != MoveMode::kC || !received_pose_) return;
  if (frame.index < 1 || frame.index > 3) return;
  move_c_points_.at(frame.index - 1U) = received_pose_;
  if (frame.index == 3) start_move_c();
}

void ArmModel::start_pose_move(const CartesianPose& pose) {
  // The SDK streams the same pose every 10 ms; only a new target starts a new move.
  if (last_pose_target_ && same_pose(pose, *last_pose_target_)) return;
  const auto solution = solve(pose, positions());
  if (!solution) return;  // arm status 0x02, the arm stays where it is
  last_pose_target_ = pose;
  waypoints_.clear();
  linear_move_.reset();
  if (move_mode_ == MoveMode::kP) {
    set_targets(*solution);  // joint-space move, like MOVE J
    return;
  }
  const double scale = speed_percent_ / 100.0;
  linear_move_.emplace(end_pose(), pose, settings_.end_limits.max_linear_velocity_m_s.value_or(0.5) * scale,
                       settings_.end_limits.max_angular_velocity_rad_s.value_or(2.0) * scale);
  linear_ik_due_s_ = 0;
}

void ArmModel::start_move_c() {
  // An approximation of the arc: the joints move to the middle point and then to the end point,
  // each in joint space (IK at both points), not along the circle through start, middle and end.
  const auto& middle_pose = move_c_points_[1];
  const auto& final_pose = move_c_points_[2];
  if (!middle_pose || !final_pose) return;
  const auto middle = solve(*middle_pose, positions());
  if (!middle) return;
  const auto end = solve(*final_pose, *middle);
  if (!end) return;
  move_c_points_ = {};
  linear_move_.reset();
  set_targets(*middle);
  waypoints_.assign(1, *end);
}

void ArmModel::step_planners(double dt_s) {
  if (estop_) return;
  if (linear_move_) {
    const CartesianPose pose = linear_move_->advance(dt_s);
    linear_ik_due_s_ -= dt_s;
    if (linear_ik_due_s_ <= 0 || linear_move_->done()) {
      linear_ik_due_s_ = kLinearIkPeriodS;
      std::array<double, kArmJoints> seed{};
      for (std::size_t i = 0; i < joints_.size(); ++i) seed[i] = joints_[i].target_rad;
      const auto solution = solve(pose, seed);
      if (!solution) {  // the line leaves the workspace: stop where the arm is, status 0x02
        cancel_motion();
        return;
      }
      set_targets(*solution);
      if (linear_move_->done()) linear_move_.reset();
    }
  }
  if (!waypoints_.empty() && joints_at_targets()) {
    set_targets(waypoints_.front());
    waypoints_.erase(waypoints_.begin());
  }
}

std::optional<std::array<double, kArmJoints>> ArmModel::solve(const CartesianPose& pose,
                                                              const std::array<double, kArmJoints>& seed) {
  std::array<double, kArmJoints> min_rad{};
  std::array<double, kArmJoints> max_rad{};
  for (std::size_t i = 0; i < settings_.joints.size(); ++i) {
    min_rad[i] = settings_.joints[i].min_rad;
    max_rad[i] = settings_.joints[i].max_rad;
  }
  const IkResult result = inverse_kinematics(pose, seed, dh_, min_rad, max_rad);
  ik_failed_ = !result.converged;  // arm status 0x02 "no IK solution"
  if (!result.converged) return std::nullopt;
  return result.q_rad;
}

void ArmModel::set_targets(const std::array<double, kArmJoints>& targets_rad) {
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    joints_[i].target_rad = std::clamp(targets_rad[i], settings_.joints[i].min_rad, settings_.joints[i].max_rad);
    joints_[i].target_beyond_limit = false;
  }
}

}  // namespace robotd::piper::sim
