// PAROL6 kinematics (spec §11.1) on the shared arm model "parol6" (robotd/kinematics/
// arm_model.hpp: the commander's standard-DH model to the tool, link 6 carrying the 62.8 / 45.25 mm
// tool offset, and its roll/pitch/yaw convention), in the driver's 6-joint types; a
// damped-least-squares inverse, and the commander's move timing (trapezoidal or quintic
// polynomial) for MovePose / MoveCart. Lengths in m, angles in rad.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

#include "codec/parol6_frames.hpp"

namespace robotd::parol6 {

/// The shared arm model (robotd::kinematics::find_arm_model).
inline constexpr std::string_view kArmModelName = "parol6";

using JointVector = std::array<double, kJoints>;

/// A tool pose: position in m and orientation in rad, in the convention the commander uses for
/// MovePose(x, y, z, Rx, Ry, Rz) and shows in its GUI: roll_rad, pitch_rad, yaw_rad are its Rx,
/// Ry, Rz, which it turns into a rotation with spatialmath's SE3.RPY([Rx, Ry, Rz], order="xyz"):
///   R = Rx(yaw_rad) · Ry(pitch_rad) · Rz(roll_rad).
/// Despite the argument names, roll (the first angle) turns about z, the tool axis, and yaw (the
/// third) about x; this is not the usual R = Rz(yaw)·Ry(pitch)·Rx(roll). pose_of gives pitch in
/// [−π/2, π/2]; at pitch ±π/2 it sets roll to 0 and puts the whole turn in yaw.
struct Pose {
  double x_m = 0, y_m = 0, z_m = 0;
  double roll_rad = 0, pitch_rad = 0, yaw_rad = 0;
};

Eigen::Isometry3d tool_transform(const JointVector& q_rad) noexcept;
Pose forward_kinematics(const JointVector& q_rad) noexcept;
Eigen::Isometry3d transform_of(const Pose& pose) noexcept;
Pose pose_of(const Eigen::Isometry3d& transform) noexcept;

struct IkResult {
  bool converged = false;  // position error < 0.1 mm and orientation error < 1e-3 rad
  JointVector q_rad{};     // within the limits
  double position_error_m = 0;
  double orientation_error_rad = 0;
};

/// Damped least squares from `seed`, joint limits respected. Not real-time.
IkResult inverse_kinematics(const Pose& target, const JointVector& seed, const JointVector& min_rad,
                            const JointVector& max_rad);

enum class Profile : std::uint8_t { kTrapezoid, kPolynomial };

/// How a move is timed, like the commander's MoveJoint / MovePose / MoveCart arguments:
/// a duration (trapezoid: 1/3 accelerate, 1/3 cruise, 1/3 decelerate), or speed and
/// acceleration as fractions 0 < f ≤ 1 of the leading joint's maximum. The leading joint is the
/// one whose limit binds: no joint goes past f × its own maximum. The fractions time joint moves
/// only; a Cartesian move takes a duration or a linear speed.
struct MoveTiming {
  Profile profile = Profile::kTrapezoid;
  std::optional<double> duration_s;
  double speed_fraction = 0.3;
  double acceleration_fraction = 0.3;
};

/// Joint positions every `dt_s` from `from` to `to` (both included; the duration rounded up to
/// whole samples), all joints arriving together; `max_speed` / `max_acceleration` per joint in
/// rad/s, rad/s². A duration too short for a joint's maximum is refused. Errors in `error`.
std::vector<JointVector> plan_joint_move(const JointVector& from, const JointVector& to, const MoveTiming& timing,
                                         const JointVector& max_speed, const JointVector& max_acceleration, double dt_s,
                                         std::string& error);

/// A straight line of the tool from the pose at `from` to `target` (position linear,
/// orientation by slerp) on the timing profile, solved by IK at every sample from the previous
/// one. Without a duration the tool cruises at `linear_speed_m_s` and turns at most 25°/s (the
/// commander's Cartesian maximum). Fails (empty, `error` says where) when a sample has no
/// solution or a joint would exceed its limits or its max speed (near a singularity).
std::vector<JointVector> plan_cartesian_move(const JointVector& from, const Pose& target, const MoveTiming& timing,
                                             const JointVector& min_rad, const JointVector& max_rad,
                                             const JointVector& max_speed, double linear_speed_m_s, double dt_s,
                                             std::string& error);

}  // namespace robotd::parol6
