// PiPER kinematics to the J6 flange (piper_can.md §9) on the shared arm models "piper" and
// "piper_plain_dh" (robotd/kinematics/arm_model.hpp: the SDK's modified-DH table), in the
// driver's types: the SDK's roll/pitch/yaw extraction, and the inverse kinematics's search
// around the wrist singularity. Lengths in m, angles in rad.
// Everything but inverse_kinematics is allocation-free (fixed-size Eigen) for real-time use.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include <Eigen/Geometry>

#include "codec/piper_frames.hpp"

namespace robotd::piper {

/// The J2/J3 zero offsets of the firmware (the SDK's dh_is_offset).
enum class DhVariant : std::uint8_t {
  kOffset,  // dh_is_offset = 1, firmware ≥ S-V1.6-3 (default): θ2 −172.22°, θ3 −102.78°
  kPlain,   // dh_is_offset = 0, older firmware: θ2 −174.22°, θ3 −100.78°
};

/// The shared arm model of the variant: "piper" (kOffset) or "piper_plain_dh" (kPlain).
std::string_view arm_model_name(DhVariant variant) noexcept;

/// The flange in the base frame.
Eigen::Isometry3d flange_transform(const std::array<double, kArmJoints>& q_rad, DhVariant variant) noexcept;

/// The pose of every link (joint i's frame for links 1 … 6; link 6 is the flange) in the base
/// frame, as the SDK's GetFK / CalFK reports them.
std::array<CartesianPose, kArmJoints> link_poses(const std::array<double, kArmJoints>& q_rad,
                                                 DhVariant variant) noexcept;

/// The flange pose as the arm reports it on 0x2A2–0x2A4.
CartesianPose forward_kinematics(const std::array<double, kArmJoints>& q_rad, DhVariant variant) noexcept;

/// Position and roll/pitch/yaw of a transform, extracted like the SDK: within 1e-4 of the
/// pitch = ±90° singularity (|r20| > 0.9999) pitch snaps to ±90° and yaw to 0.
CartesianPose pose_of(const Eigen::Isometry3d& flange) noexcept;

/// The transform of a pose: R = Rz(rz)·Ry(ry)·Rx(rx).
Eigen::Isometry3d transform_of(const CartesianPose& pose) noexcept;

/// The orientation of a pose as a unit quaternion (x, y, z, w).
std::array<double, 4> quaternion_xyzw(const CartesianPose& pose) noexcept;

struct IkResult {
  bool converged = false;                  // position error < 0.1 mm and orientation error < 1e-3 rad
  std::array<double, kArmJoints> q_rad{};  // the best joint angles found, within the limits
  double position_error_m = 0;
  double orientation_error_rad = 0;
  int iterations = 0;
};

/// Joint angles within [min_rad, max_rad] that put the flange at `target`, searched from `seed_rad`
/// by damped least squares (Levenberg–Marquardt) on the geometric Jacobian, at most 200 steps.
/// Not real-time: for planning MOVE P / MOVE L targets.
IkResult inverse_kinematics(const CartesianPose& target, const std::array<double, kArmJoints>& seed_rad,
                            DhVariant variant, const std::array<double, kArmJoints>& min_rad,
                            const std::array<double, kArmJoints>& max_rad);

}  // namespace robotd::piper
