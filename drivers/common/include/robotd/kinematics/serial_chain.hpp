// What the arms' kinematics share: a 6-joint serial chain given as its frames, its geometric
// Jacobian, the twist between two poses, and a damped-least-squares inverse with joint limits.
// Each driver supplies its own model (DH convention, offsets, tool) as the frames function.
#pragma once

#include <array>
#include <cstddef>
#include <functional>

#include <Eigen/Geometry>

namespace robotd::kinematics {

inline constexpr std::size_t kChainJoints = 6;
using JointArray = std::array<double, kChainJoints>;
/// frames[i], i < 6: joint i turns about the z axis of frames[i], through its origin;
/// frames[6]: the tip (flange or tool). All in the base frame.
using ChainFrames = std::array<Eigen::Isometry3d, kChainJoints + 1>;
using Twist = Eigen::Matrix<double, 6, 1>;  // position (m), then rotation vector (rad)
using Jacobian = Eigen::Matrix<double, 6, static_cast<int>(kChainJoints)>;

/// Column i: z_i × (tip − o_i) and z_i. No allocation.
Jacobian geometric_jacobian(const ChainFrames& frames) noexcept;

/// The twist that takes `current` onto `goal`, in the base frame.
Twist pose_error(const Eigen::Isometry3d& goal, const Eigen::Isometry3d& current) noexcept;

struct DlsOptions {
  int max_iterations = 200;
  /// Consecutive refused steps after which the search is stuck (the damping has grown 10^k-fold):
  /// at the solution's numerical floor, in a local minimum, or against the limits.
  int max_refusals = 200;
  double stop_position_m = 1e-4;  // stop once the error is below both
  double stop_orientation_rad = 1e-3;
};

struct DlsResult {
  JointArray q_rad{};  // within the limits
  Twist error = Twist::Zero();
  int iterations = 0;
};

/// Joint angles in [min_rad, max_rad] that bring frames_of(q)[6] onto `goal`, from `seed`:
/// Levenberg–Marquardt on the geometric Jacobian (λ shrinks after a step that lowers the error,
/// grows after one that does not). Not real-time.
DlsResult solve_dls(const Eigen::Isometry3d& goal, const JointArray& seed, const JointArray& min_rad,
                    const JointArray& max_rad, const std::function<ChainFrames(const JointArray&)>& frames_of,
                    const DlsOptions& options);

}  // namespace robotd::kinematics
