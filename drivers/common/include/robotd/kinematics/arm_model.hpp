// The arms robotd knows, as kinematic models: each one's DH table (standard or modified), tool,
// joint limits and the way its vendor writes a pose's three angles; and what is computed on them
// for any number of joints up to 7: the tool pose, the geometric Jacobian, a singularity measure
// and a damped-least-squares inverse with joint limits. The one home of the arms' geometry: the
// drivers, their simulators and the client-side motion layer all take it from here.
// Lengths in m, angles in rad. Each table names its public source in src/arm_models.cpp.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <string_view>

#include <Eigen/Geometry>

namespace robotd::kinematics {

inline constexpr std::size_t kMaxArmJoints = 7;
/// Joint positions (rad); an arm with fewer joints uses the first `dof`, the rest are ignored.
using ArmJoints = std::array<double, kMaxArmJoints>;

enum class DhConvention {
  kStandard,  // link i = Rz(q + θ offset)·Tz(d)·Tx(a)·Rx(α); joint i turns about z of frame i−1
  kModified,  // link i = Rx(α)·Tx(a)·Rz(q + θ offset)·Tz(d) (Craig); joint i turns about z of frame i
};

struct DhLink {
  double a_m = 0;
  double alpha_rad = 0;
  double d_m = 0;
  double theta_offset_rad = 0;
};

/// How a vendor writes the orientation of a pose as three angles (a, b, c), in the order it lists
/// them (for RBTscript's MovePose the Rx, Ry, Rz arguments).
enum class EulerConvention {
  /// R = Rz(c)·Ry(b)·Rx(a): roll, pitch, yaw about fixed axes x, y, z (xArm, RealMan, PiPER).
  /// Angles back: b in [−π/2, π/2]; within 1e-9 of b = ±π/2 a is 0 and c carries the turn.
  kFixedXyz,
  /// R = Rx(c)·Ry(b)·Rz(a): the PAROL6 commander's MovePose(x, y, z, Rx, Ry, Rz), spatialmath's
  /// SE3.RPY([Rx, Ry, Rz], order="xyz"). Despite the names the first angle turns about z (the
  /// tool axis) and the third about x. Angles back: b in [−π/2, π/2]; within 1e-8 of b = ±π/2
  /// a is 0 and c carries the turn (spatialmath's tr2rpy).
  kParol6Commander,
};

struct ArmModel {
  std::string_view name;  // "parol6", "piper", "xarm6", … (find_arm_model)
  std::size_t dof = 0;    // 5 … 7
  DhConvention convention = DhConvention::kStandard;
  std::array<DhLink, kMaxArmJoints> links{};  // the first dof are used
  /// From the last link's frame to the point the vendor reports (the flange or its TCP).
  Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();
  EulerConvention euler = EulerConvention::kFixedXyz;
  /// The model's own joint limits (a device's configured limits may be narrower).
  ArmJoints min_rad{};
  ArmJoints max_rad{};
};

/// Every model robotd knows, in a fixed order.
std::span<const ArmModel> arm_models();
/// The model of that name (exact, lower case: "parol6", "piper", "piper_plain_dh", "xarm5",
/// "xarm6", "xarm7", "lite6", "uf850", "rm65", "rm75", "rml63", "gen72"); nullptr when unknown.
const ArmModel* find_arm_model(std::string_view name);

/// Link i's frame (after link i, i < dof) in the base frame; entries from dof on are the last
/// link's. Allocation-free.
std::array<Eigen::Isometry3d, kMaxArmJoints> link_frames(const ArmModel& model, const ArmJoints& q_rad) noexcept;

/// The tool in the base frame. Allocation-free.
Eigen::Isometry3d tool_pose(const ArmModel& model, const ArmJoints& q_rad) noexcept;

/// 6 × dof: column i is the tool's linear (m/rad) and angular (rad/rad) velocity, in the base
/// frame, per unit speed of joint i. Allocation-free (at most 7 columns on the stack).
using ArmJacobian = Eigen::Matrix<double, 6, Eigen::Dynamic, Eigen::ColMajor, 6, static_cast<int>(kMaxArmJoints)>;
ArmJacobian jacobian(const ArmModel& model, const ArmJoints& q_rad) noexcept;

/// The Jacobian's smallest singular value (of min(6, dof)): how close `q_rad` is to a
/// singularity, 0 on one. Mixes m and rad, so compare it with a threshold for that arm.
double smallest_singular_value(const ArmModel& model, const ArmJoints& q_rad) noexcept;

/// The twist that takes `current` onto `goal` in the base frame: position (m), then rotation vector (rad).
Eigen::Matrix<double, 6, 1> pose_error(const Eigen::Isometry3d& goal, const Eigen::Isometry3d& current) noexcept;

struct IkOptions {
  int max_iterations = 200;
  /// Consecutive refused steps after which the search is stuck (the damping has grown 10^k-fold):
  /// at the solution's numerical floor, in a local minimum, or against the limits.
  int max_refusals = 12;
  /// The search stops once the error is below both; far below the convergence tolerance by
  /// default, so that points solved along a line lie on it to well under a micrometre.
  double stop_position_m = 1e-10;
  double stop_orientation_rad = 1e-10;
  /// Converged when the error ends below both.
  double converged_position_m = 1e-4;
  double converged_orientation_rad = 1e-3;
};

struct IkSolution {
  bool converged = false;
  ArmJoints q_rad{};  // the best found, within the limits (entries from dof on are the seed's)
  double position_error_m = 0;
  double orientation_error_rad = 0;
  int iterations = 0;
};

/// Joint positions within [min_rad, max_rad] that put the tool on `goal`, searched from `seed`:
/// Levenberg–Marquardt on the geometric Jacobian (the damping shrinks after a step that lowers
/// the error and grows after one that does not); a joint at a limit the step pushes past is taken
/// out of that step. A joint with min = max is held. Redundant arms (7 joints) take the
/// least-squares step. Not real-time.
IkSolution inverse_kinematics(const ArmModel& model, const Eigen::Isometry3d& goal, const ArmJoints& seed,
                              const ArmJoints& min_rad, const ArmJoints& max_rad, const IkOptions& options = {});

/// A position and three angles in a vendor's convention.
struct EulerPose {
  std::array<double, 3> position_m{};
  std::array<double, 3> angles_rad{};  // a, b, c of the convention
};

Eigen::Isometry3d transform_of(EulerConvention convention, const EulerPose& pose) noexcept;
EulerPose pose_of(EulerConvention convention, const Eigen::Isometry3d& transform) noexcept;

}  // namespace robotd::kinematics
