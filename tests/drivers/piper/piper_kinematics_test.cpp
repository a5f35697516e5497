// PiPER kinematics against the SDK's FK vectors (piper_can.md §9), the pose ⇄ transform
// conversions, and the inverse kinematics the simulator plans MOVE P / MOVE L with.
#include "kinematics/piper_kinematics.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "thread_allocations.hpp"

namespace robotd::piper {
namespace {

using Joints = std::array<double, kArmJoints>;

constexpr double degrees(double rad) { return rad * 180.0 / std::numbers::pi; }
constexpr double radians(double deg) { return deg * std::numbers::pi / 180.0; }

// The SDK's joint limits (§8.1).
constexpr Joints kMin{-2.6179, 0.0, -2.967, -1.745, -1.22, -2.09439};
constexpr Joints kMax{2.6179, 3.14, 0.0, 1.745, 1.22, 2.09439};

struct FkVector {
  Joints q_rad;
  DhVariant variant;
  std::array<double, 3> position_mm;
  std::array<double, 3> roll_pitch_yaw_deg;
};

constexpr std::array<FkVector, 6> kSdkVectors{{
    {{0, 0, 0, 0, 0, 0}, DhVariant::kOffset, {56.128, 0, 213.266}, {0, 85, 0}},
    {{0, 0, 0, 0, 0, 0}, DhVariant::kPlain, {54.953, 0, 203.387}, {0, 85, 0}},
    {{0.2, 0.2, -0.2, 0.3, -0.2, 0.5}, DhVariant::kOffset, {65.854, 7.898, 285.650}, {68.511, 41.469, 83.347}},
    {{0.2, 0.2, -0.2, 0.3, -0.2, 0.5}, DhVariant::kPlain, {62.802, 7.279, 276.201}, {68.511, 41.469, 83.347}},
    {{0, 1.57, -1.57, 0, 0, 0}, DhVariant::kOffset, {376.893, 0, 457.119}, {0, 85, 0}},
    {{0, 1.57, -1.57, 0, 0, 0}, DhVariant::kPlain, {367.013, 0, 458.285}, {0, 85, 0}},
}};

/// Rotation angle between two transforms plus the distance between their origins.
struct Difference {
  double position_m;
  double rotation_rad;
};

Difference difference(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return {(a.translation() - b.translation()).norm(), Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle()};
}

class RandomPoses {
 public:
  /// roll, yaw in (−π, π), pitch in (−π/2, π/2).
  CartesianPose pose() {
    return {uniform(-0.5, 0.5),
            uniform(-0.5, 0.5),
            uniform(0, 0.6),
            uniform(-std::numbers::pi, std::numbers::pi),
            uniform(-std::numbers::pi / 2, std::numbers::pi / 2),
            uniform(-std::numbers::pi, std::numbers::pi)};
  }
  Joints joints_within_limits() {
    Joints q{};
    for (std::size_t i = 0; i < q.size(); ++i) q[i] = uniform(kMin[i], kMax[i]);
    return q;
  }
  double uniform(double low, double high) { return std::uniform_real_distribution<double>(low, high)(random_); }

 private:
  std::mt19937 random_{42};
};

TEST(PiperKinematics, ForwardKinematicsMatchesTheSdkVectors) {
  for (const FkVector& vector : kSdkVectors) {
    const CartesianPose pose = forward_kinematics(vector.q_rad, vector.variant);
    SCOPED_TRACE(::testing::Message() << "q = " << vector.q_rad[1] << ", variant " << static_cast<int>(vector.variant));
    EXPECT_NEAR(pose.x_m * 1000, vector.position_mm[0], 0.005);
    EXPECT_NEAR(pose.y_m * 1000, vector.position_mm[1], 0.005);
    EXPECT_NEAR(pose.z_m * 1000, vector.position_mm[2], 0.005);
    EXPECT_NEAR(degrees(pose.rx_rad), vector.roll_pitch_yaw_deg[0], 0.01);
    EXPECT_NEAR(degrees(pose.ry_rad), vector.roll_pitch_yaw_deg[1], 0.01);
    EXPECT_NEAR(degrees(pose.rz_rad), vector.roll_pitch_yaw_deg[2], 0.01);
  }
}

TEST(PiperKinematics, FlangeTransformIsTheTransformOfTheReportedPose) {
  RandomPoses random;
  for (int i = 0; i < 200; ++i) {
    const Joints q = random.joints_within_limits();
    const Eigen::Isometry3d flange = flange_transform(q, DhVariant::kOffset);
    if (std::abs(flange.linear()(2, 0)) > 0.999) continue;  // the SDK's pitch snapping, tested below
    const Difference error = difference(transform_of(forward_kinematics(q, DhVariant::kOffset)), flange);
    EXPECT_LT(error.position_m, 1e-12);
    EXPECT_LT(error.rotation_rad, 1e-9);
  }
}

TEST(PiperKinematics, PoseOfInvertsTransformOf) {
  RandomPoses random;
  for (int i = 0; i < 1000; ++i) {
    const CartesianPose pose = random.pose();
    if (std::abs(pose.ry_rad) > radians(89)) continue;
    const CartesianPose back = pose_of(transform_of(pose));
    EXPECT_NEAR(back.x_m, pose.x_m, 1e-12);
    EXPECT_NEAR(back.y_m, pose.y_m, 1e-12);
    EXPECT_NEAR(back.z_m, pose.z_m, 1e-12);
    EXPECT_NEAR(back.rx_rad, pose.rx_rad, 1e-9);
    EXPECT_NEAR(back.ry_rad, pose.ry_rad, 1e-9);
    EXPECT_NEAR(back.rz_rad, pose.rz_rad, 1e-9);
  }
}

TEST(PiperKinematics, TransformOfInvertsPoseOfForAnyRotation) {
  RandomPoses random;
  for (int i = 0; i < 1000; ++i) {
    Eigen::Quaterniond rotation(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1),
                                random.uniform(-1, 1));
    rotation.normalize();
    Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
    transform.linear() = rotation.toRotationMatrix();
    transform.translation() << random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1);
    const Difference error = difference(transform_of(pose_of(transform)), transform);
    EXPECT_LT(error.position_m, 1e-12);
    // Within 0.81° of pitch ±90° the SDK snaps pitch to ±90°, which costs up to that much.
    const bool snapped = std::abs(transform.linear()(2, 0)) > 1 - 1e-4;
    EXPECT_LT(error.rotation_rad, snapped ? 0.015 : 1e-9);
  }
}

TEST(PiperKinematics, PitchOfPlusMinusNinetyDegreesPutsAllTurnInRoll) {
  for (const double pitch : {std::numbers::pi / 2, -std::numbers::pi / 2}) {
    const CartesianPose pose{.x_m = 0.1, .rx_rad = 0.3, .ry_rad = pitch, .rz_rad = 0.5};
    const CartesianPose back = pose_of(transform_of(pose));
    EXPECT_DOUBLE_EQ(back.ry_rad, pitch);
    EXPECT_EQ(back.rz_rad, 0.0);
    EXPECT_NEAR(back.rx_rad, pitch > 0 ? 0.3 - 0.5 : 0.3 + 0.5, 1e-9);
    const Difference error = difference(transform_of(back), transform_of(pose));
    EXPECT_LT(error.rotation_rad, 1e-9);
  }
}

TEST(PiperKinematics, PitchWithinTheSdkBandSnapsToNinetyDegrees) {
  const CartesianPose near_singular{.rx_rad = 0.2, .ry_rad = radians(89.5), .rz_rad = 0.1};
  const CartesianPose back = pose_of(transform_of(near_singular));
  EXPECT_DOUBLE_EQ(back.ry_rad, std::numbers::pi / 2);
  EXPECT_EQ(back.rz_rad, 0.0);
  const CartesianPose outside{.ry_rad = radians(89.0)};
  EXPECT_NEAR(pose_of(transform_of(outside)).ry_rad, radians(89.0), 1e-9);
}

TEST(PiperKinematics, QuaternionMatchesEigen) {
  RandomPoses random;
  for (int i = 0; i < 200; ++i) {
    const CartesianPose pose = random.pose();
    const auto [x, y, z, w] = quaternion_xyzw(pose);
    const Eigen::Quaterniond expected(transform_of(pose).linear());
    EXPECT_NEAR(std::abs(expected.dot(Eigen::Quaterniond(w, x, y, z))), 1.0, 1e-12);
    EXPECT_NEAR(x * x + y * y + z * z + w * w, 1.0, 1e-12);
  }
  const auto yaw = quaternion_xyzw(CartesianPose{.rz_rad = std::numbers::pi / 2});
  EXPECT_NEAR(yaw[0], 0, 1e-15);
  EXPECT_NEAR(yaw[1], 0, 1e-15);
  EXPECT_NEAR(yaw[2], std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(yaw[3], std::sqrt(0.5), 1e-15);
}

TEST(PiperKinematics, ForwardKinematicsDoesNotAllocate) {
  const Joints q{0.2, 0.2, -0.2, 0.3, -0.2, 0.5};
  const std::size_t before = testing::allocations_on_this_thread();
  const CartesianPose pose = forward_kinematics(q, DhVariant::kOffset);
  const Eigen::Isometry3d back = transform_of(pose);
  const auto quaternion = quaternion_xyzw(pose);
  EXPECT_EQ(testing::allocations_on_this_thread(), before);
  EXPECT_GT(back.translation().norm() + quaternion[3], 0);
}

TEST(PiperKinematics, InverseKinematicsRecoversReachablePoses) {
  RandomPoses random;
  for (const DhVariant variant : {DhVariant::kOffset, DhVariant::kPlain}) {
    for (int i = 0; i < 300; ++i) {
      const Joints q = random.joints_within_limits();
      const CartesianPose target = forward_kinematics(q, variant);
      Joints seed = q;
      for (double& angle : seed) angle += random.uniform(-0.1, 0.1);
      const IkResult result = inverse_kinematics(target, seed, variant, kMin, kMax);
      SCOPED_TRACE(::testing::Message() << "sample " << i << ", variant " << static_cast<int>(variant));
      ASSERT_TRUE(result.converged) << "position error " << result.position_error_m << " m, orientation error "
                                    << result.orientation_error_rad << " rad after " << result.iterations;
      const Difference error = difference(flange_transform(result.q_rad, variant), transform_of(target));
      EXPECT_LT(error.position_m, 1e-4);
      EXPECT_LT(error.rotation_rad, 1e-3);
      EXPECT_NEAR(error.position_m, result.position_error_m, 1e-9);
      for (std::size_t j = 0; j < q.size(); ++j) {
        EXPECT_GE(result.q_rad[j], kMin[j]);
        EXPECT_LE(result.q_rad[j], kMax[j]);
      }
    }
  }
}

// Near the wrist singularity (J5 ≈ 0) the search from the seed alone landed 140° away for a
// 20 mm move (J4 from 0.8 to −1.65 rad); the solution nearest the current joints keeps J4 on its side.
TEST(PiperKinematics, InverseKinematicsNearTheWristSingularityTakesTheNearestSolution) {
  const Joints start{0.0, 0.5, -1.0, 0.8, 0.02, -0.8};
  CartesianPose target = forward_kinematics(start, DhVariant::kOffset);
  target.y_m -= 0.02;
  const IkResult result = inverse_kinematics(target, start, DhVariant::kOffset, kMin, kMax);
  ASSERT_TRUE(result.converged);
  double largest = 0;
  for (std::size_t j = 0; j < start.size(); ++j) largest = std::max(largest, std::abs(result.q_rad[j] - start[j]));
  EXPECT_LT(largest, radians(60)) << "J4 " << result.q_rad[3] << ", J6 " << result.q_rad[5];
  EXPECT_GT(result.q_rad[3], 0.0);
}

TEST(PiperKinematics, InverseKinematicsFromTheSolutionTakesNoStep) {
  const Joints q{0.2, 0.2, -0.2, 0.3, -0.2, 0.5};
  const IkResult result =
      inverse_kinematics(forward_kinematics(q, DhVariant::kOffset), q, DhVariant::kOffset, kMin, kMax);
  EXPECT_TRUE(result.converged);
  EXPECT_EQ(result.iterations, 0);
  EXPECT_EQ(result.q_rad, q);
}

TEST(PiperKinematics, InverseKinematicsReportsAnUnreachablePose) {
  const CartesianPose far{.x_m = 2.0, .z_m = 0.2};
  const IkResult result = inverse_kinematics(far, Joints{0, 1.0, -1.0, 0, 0.3, 0}, DhVariant::kOffset, kMin, kMax);
  EXPECT_FALSE(result.converged);
  EXPECT_GT(result.position_error_m, 1.0);
  EXPECT_LE(result.iterations, 200);
  for (std::size_t j = 0; j < kArmJoints; ++j) {
    EXPECT_GE(result.q_rad[j], kMin[j]);
    EXPECT_LE(result.q_rad[j], kMax[j]);
  }
}

TEST(PiperKinematics, InverseKinematicsKeepsToTheJointLimits) {
  const Joints q{0.8, 1.0, -1.0, 0.3, 0.5, 0.2};
  Joints narrow_max = kMax;
  narrow_max[0] = 0.5;  // the target needs J1 = 0.8
  const IkResult result =
      inverse_kinematics(forward_kinematics(q, DhVariant::kOffset), Joints{0.4, 1.0, -1.0, 0.3, 0.5, 0.2},
                         DhVariant::kOffset, kMin, narrow_max);
  EXPECT_FALSE(result.converged);
  EXPECT_LE(result.q_rad[0], 0.5);
}

}  // namespace
}  // namespace robotd::piper
