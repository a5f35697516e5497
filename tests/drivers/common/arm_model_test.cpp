// The arm models (robotd/kinematics/arm_model.hpp): every model's forward kinematics against its
// vendor's figures, inverse kinematics round trips from random reachable postures, the Jacobian
// against finite differences, the singularity measure, joint limits, and both Euler conventions.
#include "robotd/kinematics/arm_model.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <random>
#include <set>
#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include "thread_allocations.hpp"

namespace robotd::kinematics {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

const ArmModel& model(std::string_view name) {
  const ArmModel* found = find_arm_model(name);
  if (found == nullptr) throw std::invalid_argument("no arm model " + std::string(name));
  return *found;
}

ArmJoints degrees(const std::array<double, kMaxArmJoints>& deg) {
  ArmJoints q{};
  for (std::size_t i = 0; i < q.size(); ++i) q[i] = deg[i] * kDeg;
  return q;
}

double rotation_between(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle();
}

class Random {
 public:
  double uniform(double low, double high) { return std::uniform_real_distribution<double>(low, high)(random_); }
  /// Within the model's limits, at most ±150° (a joint with ±360° has the same postures there).
  ArmJoints joints_within(const ArmModel& arm, double margin_rad) {
    ArmJoints q{};
    for (std::size_t i = 0; i < arm.dof; ++i) {
      q[i] = uniform(std::max(arm.min_rad[i], -150 * kDeg) + margin_rad,
                     std::min(arm.max_rad[i], 150 * kDeg) - margin_rad);
    }
    return q;
  }

 private:
  std::mt19937 random_{7};
};

// --- the table -----------------------------------------------------------------------------------

TEST(ArmModel, EveryModelIsFoundByItsNameAndIsWellFormed) {
  std::set<std::string_view> names;
  for (const ArmModel& arm : arm_models()) {
    SCOPED_TRACE(arm.name);
    EXPECT_TRUE(names.insert(arm.name).second) << "names are unique";
    EXPECT_EQ(find_arm_model(arm.name), &arm);
    EXPECT_GE(arm.dof, 5U);
    EXPECT_LE(arm.dof, kMaxArmJoints);
    for (std::size_t i = 0; i < arm.dof; ++i) EXPECT_LT(arm.min_rad[i], arm.max_rad[i]) << "joint " << i + 1;
  }
  for (const std::string_view name :
       {"parol6", "piper", "piper_plain_dh", "xarm5", "xarm6", "xarm7", "lite6", "rm65", "rm75"}) {
    EXPECT_NE(find_arm_model(name), nullptr) << name;
  }
}

TEST(ArmModel, AnUnknownNameHasNoModel) {
  EXPECT_EQ(find_arm_model("xarm8"), nullptr);
  EXPECT_EQ(find_arm_model(""), nullptr);
  EXPECT_EQ(find_arm_model("PAROL6"), nullptr) << "names are lower case, matched exactly";
}

// --- forward kinematics against the vendors' figures --------------------------------------------

struct VendorFigure {
  std::string_view model;
  std::array<double, kMaxArmJoints> q_deg;
  std::array<double, 3> position_mm;
  double tolerance_mm;
};

// PAROL6: the spec's FK check values (parol6_serial.md §11.1, given to 2 or 3 decimals).
// PiPER: piper_sdk's GetFK for both DH variants (q in rad there; converted here).
// xArm, Lite 6: UFACTORY's zero postures, TCP at (207, 0, 112) mm on the xArm 5 and 6,
// (206, 0, 120.5) mm on the xArm 7, (87, 0, 154.2) mm on the Lite 6.
// RM65: the RealMan simulator tests' well-conditioned posture, flange at x −410 mm, z 337 mm.
constexpr double kRadInDeg = 180.0 / std::numbers::pi;
constexpr std::array<VendorFigure, 16> kVendorFigures{{
    {"parol6", {0, -90, 180, 0, 0, 180}, {262.57, 0.00, 288.75}, 0.01},
    {"parol6", {90, -90, 180, 0, 0, 180}, {0.00, 262.57, 288.75}, 0.01},
    {"parol6", {10, -60, 200, 20, -30, 100}, {325.356, 86.622, 219.474}, 0.01},
    {"parol6", {0, 0, 0, 0, 0, 0}, {114.67, 0.00, 349.65}, 0.01},
    {"piper", {0, 0, 0, 0, 0, 0}, {56.128, 0, 213.266}, 0.005},
    {"piper_plain_dh", {0, 0, 0, 0, 0, 0}, {54.953, 0, 203.387}, 0.005},
    {"piper",
     {0.2 * kRadInDeg, 0.2 * kRadInDeg, -0.2 * kRadInDeg, 0.3 * kRadInDeg, -0.2 * kRadInDeg, 0.5 * kRadInDeg},
     {65.854, 7.898, 285.650},
     0.005},
    {"piper_plain_dh",
     {0.2 * kRadInDeg, 0.2 * kRadInDeg, -0.2 * kRadInDeg, 0.3 * kRadInDeg, -0.2 * kRadInDeg, 0.5 * kRadInDeg},
     {62.802, 7.279, 276.201},
     0.005},
    {"piper", {0, 1.57 * kRadInDeg, -1.57 * kRadInDeg, 0, 0, 0}, {376.893, 0, 457.119}, 0.005},
    {"piper_plain_dh", {0, 1.57 * kRadInDeg, -1.57 * kRadInDeg, 0, 0, 0}, {367.013, 0, 458.285}, 0.005},
    {"xarm5", {0, 0, 0, 0, 0}, {207, 0, 112}, 0.01},
    {"xarm6", {0, 0, 0, 0, 0, 0}, {207, 0, 112}, 0.01},
    {"xarm7", {0, 0, 0, 0, 0, 0, 0}, {206, 0, 120.5}, 0.01},
    {"lite6", {0, 0, 0, 0, 0, 0}, {87, 0, 154.2}, 0.01},
    {"rm65", {0, 30, 60, 0, 60, 0}, {-410, 0, 337}, 1.0},
    {"rm65", {0, 0, 0, 0, 0, 0}, {0, 0, 850.5}, 1e-3},
}};

TEST(ArmModel, ForwardKinematicsMatchesTheVendorsFigures) {
  for (const VendorFigure& figure : kVendorFigures) {
    const Eigen::Vector3d position = tool_pose(model(figure.model), degrees(figure.q_deg)).translation() * 1000;
    SCOPED_TRACE(::testing::Message() << figure.model << " at q1 " << figure.q_deg[0] << ", q2 " << figure.q_deg[1]);
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_NEAR(position(axis), figure.position_mm[static_cast<std::size_t>(axis)], figure.tolerance_mm) << axis;
    }
  }
}

TEST(ArmModel, PiperOrientationMatchesTheSdkVectors) {
  // piper_sdk's GetFK roll, pitch, yaw (fixed axes) at its two test postures.
  const EulerPose zero = pose_of(EulerConvention::kFixedXyz, tool_pose(model("piper"), {}));
  EXPECT_NEAR(zero.angles_rad[0], 0, 0.01 * kDeg);
  EXPECT_NEAR(zero.angles_rad[1], 85 * kDeg, 0.01 * kDeg);
  EXPECT_NEAR(zero.angles_rad[2], 0, 0.01 * kDeg);
  const EulerPose turned =
      pose_of(EulerConvention::kFixedXyz, tool_pose(model("piper"), {0.2, 0.2, -0.2, 0.3, -0.2, 0.5}));
  EXPECT_NEAR(turned.angles_rad[0], 68.511 * kDeg, 0.01 * kDeg);
  EXPECT_NEAR(turned.angles_rad[1], 41.469 * kDeg, 0.01 * kDeg);
  EXPECT_NEAR(turned.angles_rad[2], 83.347 * kDeg, 0.01 * kDeg);
}

TEST(ArmModel, AtZeroTheUfactoryArmsPointDown) {
  for (const std::string_view name : {"xarm5", "xarm6", "xarm7", "lite6"}) {
    const Eigen::Isometry3d tool = tool_pose(model(name), {});
    EXPECT_NEAR(tool.linear().col(2).z(), -1.0, 1e-9) << name << ": roll 180°";
  }
}

TEST(ArmModel, AtStandbyThePAROL6ToolPointsAlongBaseX) {
  const Eigen::Isometry3d tool = tool_pose(model("parol6"), degrees({0, -90, 180, 0, 0, 180}));
  EXPECT_NEAR(tool.linear().col(2).x(), 1.0, 1e-12);
}

TEST(ArmModel, TheForceFlangeIsLongerAlongTheFlangeAxis) {
  const ArmJoints q = degrees({10, 20, 30, 40, 50, 60});
  const Eigen::Isometry3d flange = tool_pose(model("rm65"), q);
  const Eigen::Isometry3d force = tool_pose(model("rm65_6f"), q);
  EXPECT_NEAR((force.translation() - flange.translation() - 0.0285 * flange.linear().col(2)).norm(), 0, 1e-12);
}

TEST(ArmModel, JointOneTurnsEveryArmAboutBaseZ) {
  Random random;
  for (const ArmModel& arm : arm_models()) {
    ArmJoints q = random.joints_within(arm, 0.1);
    const Eigen::Isometry3d before = tool_pose(arm, q);
    q[0] += 0.3;
    const Eigen::Isometry3d expected = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) * before;
    const Eigen::Isometry3d after = tool_pose(arm, q);
    EXPECT_LT((after.translation() - expected.translation()).norm(), 1e-12) << arm.name;
    EXPECT_LT(rotation_between(after, expected), 1e-12) << arm.name;
  }
}

TEST(ArmModel, LinkFramesEndAtTheToollessFlange) {
  const ArmModel& arm = model("rm65_6f");
  const ArmJoints q = degrees({10, 20, 30, 40, 50, 60});
  const auto frames = link_frames(arm, q);
  EXPECT_TRUE((frames[arm.dof - 1] * arm.tool).isApprox(tool_pose(arm, q), 1e-15));
  EXPECT_TRUE(frames.back().isApprox(frames[arm.dof - 1])) << "entries from dof on repeat the last link";
}

TEST(ArmModel, ForwardKinematicsAndTheJacobianDoNotAllocate) {
  const ArmModel& arm = model("xarm7");
  const ArmJoints q = degrees({10, -20, 30, 40, -50, 60, 70});
  const std::size_t before = testing::allocations_on_this_thread();
  const Eigen::Isometry3d tool = tool_pose(arm, q);
  const ArmJacobian j = jacobian(arm, q);
  const double sigma = smallest_singular_value(arm, q);
  const EulerPose pose = pose_of(arm.euler, tool);
  const Eigen::Isometry3d back = transform_of(arm.euler, pose);
  EXPECT_EQ(testing::allocations_on_this_thread(), before);
  EXPECT_EQ(j.cols(), 7);
  EXPECT_GT(sigma, 0);
  EXPECT_TRUE(back.isApprox(tool, 1e-12));
}

// --- the Jacobian --------------------------------------------------------------------------------

TEST(ArmModel, TheJacobianMatchesFiniteDifferencesOnEveryModel) {
  constexpr double kStep = 1e-6;
  Random random;
  for (const ArmModel& arm : arm_models()) {
    for (int trial = 0; trial < 5; ++trial) {
      const ArmJoints q = random.joints_within(arm, 0.0);
      const ArmJacobian j = jacobian(arm, q);
      ASSERT_EQ(j.cols(), static_cast<Eigen::Index>(arm.dof));
      for (std::size_t i = 0; i < arm.dof; ++i) {
        ArmJoints plus = q;
        ArmJoints minus = q;
        plus[i] += kStep;
        minus[i] -= kStep;
        const Eigen::Isometry3d a = tool_pose(arm, plus);
        const Eigen::Isometry3d b = tool_pose(arm, minus);
        const Eigen::Vector3d linear = (a.translation() - b.translation()) / (2 * kStep);
        const Eigen::AngleAxisd turn(a.linear() * b.linear().transpose());
        const Eigen::Vector3d angular = turn.angle() * turn.axis() / (2 * kStep);
        const auto column = static_cast<Eigen::Index>(i);
        EXPECT_LT((j.block<3, 1>(0, column) - linear).norm(), 1e-7) << arm.name << " joint " << i + 1;
        EXPECT_LT((j.block<3, 1>(3, column) - angular).norm(), 1e-7) << arm.name << " joint " << i + 1;
      }
    }
  }
}

TEST(ArmModel, TheSmallestSingularValueVanishesAtAWristSingularity) {
  // With joint 5 at 0 the wrist axes 4 and 6 of the PAROL6 and the PiPER line up.
  const double regular = smallest_singular_value(model("parol6"), degrees({10, -60, 200, 20, -30, 100}));
  const double wrist = smallest_singular_value(model("parol6"), degrees({10, -60, 200, 20, 0, 100}));
  EXPECT_GT(regular, 1e-2);
  EXPECT_LT(wrist, 1e-12);
  EXPECT_LT(smallest_singular_value(model("piper"), {0.2, 1.2, -1.0, 0.3, 0, 0.5}), 1e-12);
  EXPECT_GT(smallest_singular_value(model("piper"), {0.2, 1.2, -1.0, 0.3, -0.4, 0.5}), 1e-2);
}

// --- inverse kinematics --------------------------------------------------------------------------

TEST(ArmModel, InverseKinematicsRecoversRandomReachablePosturesOfEveryModel) {
  Random random;
  for (const ArmModel& arm : arm_models()) {
    int converged = 0;
    constexpr int kTrials = 20;
    for (int trial = 0; trial < kTrials; ++trial) {
      const ArmJoints q = random.joints_within(arm, 0.1);
      ArmJoints seed = q;
      for (std::size_t i = 0; i < arm.dof; ++i) seed[i] += random.uniform(-0.1, 0.1);
      const Eigen::Isometry3d goal = tool_pose(arm, q);
      const IkSolution solved = inverse_kinematics(arm, goal, seed, arm.min_rad, arm.max_rad);
      if (!solved.converged) continue;
      ++converged;
      const Eigen::Isometry3d reached = tool_pose(arm, solved.q_rad);
      EXPECT_LT((reached.translation() - goal.translation()).norm(), 1e-6) << arm.name;
      EXPECT_LT(rotation_between(reached, goal), 1e-6) << arm.name;
      EXPECT_NEAR(solved.position_error_m, (reached.translation() - goal.translation()).norm(), 1e-12);
      for (std::size_t i = 0; i < arm.dof; ++i) {
        EXPECT_GE(solved.q_rad[i], arm.min_rad[i]);
        EXPECT_LE(solved.q_rad[i], arm.max_rad[i]);
      }
    }
    EXPECT_EQ(converged, kTrials) << arm.name << ": every posture from a seed 0.1 rad away";
  }
}

TEST(ArmModel, InverseKinematicsFromTheSolutionTakesNoStep) {
  const ArmModel& arm = model("piper");
  const ArmJoints q{0.2, 1.2, -1.0, 0.3, -0.4, 0.5};
  const IkSolution solved = inverse_kinematics(arm, tool_pose(arm, q), q, arm.min_rad, arm.max_rad);
  EXPECT_TRUE(solved.converged);
  EXPECT_EQ(solved.iterations, 0);
  EXPECT_EQ(solved.q_rad, q);
}

TEST(ArmModel, InverseKinematicsReportsAnUnreachablePose) {
  const ArmModel& arm = model("parol6");
  Eigen::Isometry3d far = Eigen::Isometry3d::Identity();
  far.translation() << 2.0, 0, 0.3;  // the arm reaches about half a metre
  const ArmJoints standby = degrees({0, -90, 180, 0, 0, 180});
  const IkSolution solved = inverse_kinematics(arm, far, standby, arm.min_rad, arm.max_rad);
  EXPECT_FALSE(solved.converged);
  EXPECT_GT(solved.position_error_m, 1.0);
}

TEST(ArmModel, InverseKinematicsKeepsToTheLimitsAndHoldsAJointWhoseRangeIsAPoint) {
  const ArmModel& arm = model("xarm7");
  Random random;
  const ArmJoints q = random.joints_within(arm, 0.2);
  ArmJoints seed = q;
  for (std::size_t i = 0; i < arm.dof; ++i) seed[i] += 0.1;
  seed[2] = q[2];
  ArmJoints min_rad = arm.min_rad;
  ArmJoints max_rad = arm.max_rad;
  min_rad[2] = q[2];
  max_rad[2] = q[2];
  const IkSolution solved = inverse_kinematics(arm, tool_pose(arm, q), seed, min_rad, max_rad);
  EXPECT_TRUE(solved.converged);
  EXPECT_EQ(solved.q_rad[2], q[2]) << "joint 3 held";

  // A goal only reachable past joint 1's limit: the search stays inside it.
  const ArmModel& piper = model("piper");
  const ArmJoints outside{2.9, 1.0, -1.0, 0, 0.5, 0};
  ArmJoints start = outside;
  start[0] = 2.5;
  const IkSolution limited = inverse_kinematics(piper, tool_pose(piper, outside), start, piper.min_rad, piper.max_rad);
  EXPECT_FALSE(limited.converged);
  EXPECT_LE(limited.q_rad[0], piper.max_rad[0]);
}

// --- Euler conventions ---------------------------------------------------------------------------

TEST(EulerConvention, FixedXyzIsRzRyRx) {
  const EulerPose pose{.position_m = {0.1, 0.2, 0.3}, .angles_rad = {0.4, -0.5, 0.6}};
  const Eigen::Isometry3d transform = transform_of(EulerConvention::kFixedXyz, pose);
  const Eigen::Matrix3d expected =
      (Eigen::AngleAxisd(0.6, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(-0.5, Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  EXPECT_TRUE(transform.linear().isApprox(expected, 1e-15));
  EXPECT_TRUE(transform.translation().isApprox(Eigen::Vector3d(0.1, 0.2, 0.3)));
}

TEST(EulerConvention, Parol6CommanderIsRxOfTheThirdRyRzOfTheFirst) {
  const EulerPose pose{.angles_rad = {0.4, -0.5, 0.6}};
  const Eigen::Matrix3d expected =
      (Eigen::AngleAxisd(0.6, Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(-0.5, Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()))
          .toRotationMatrix();
  EXPECT_TRUE(transform_of(EulerConvention::kParol6Commander, pose).linear().isApprox(expected, 1e-15));
}

TEST(EulerConvention, AnglesBackGiveTheSameRotationInBothConventions) {
  Random random;
  for (const EulerConvention convention : {EulerConvention::kFixedXyz, EulerConvention::kParol6Commander}) {
    for (int trial = 0; trial < 200; ++trial) {
      const EulerPose pose{
          .position_m = {random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1)},
          .angles_rad = {random.uniform(-kPi, kPi), random.uniform(-kPi / 2, kPi / 2), random.uniform(-kPi, kPi)}};
      const EulerPose back = pose_of(convention, transform_of(convention, pose));
      for (std::size_t k = 0; k < 3; ++k) {
        EXPECT_NEAR(back.angles_rad[k], pose.angles_rad[k], 1e-9);
        EXPECT_EQ(back.position_m[k], pose.position_m[k]);
      }
    }
  }
}

TEST(EulerConvention, AtPitchNinetyDegreesTheThirdAngleCarriesTheTurn) {
  for (const EulerConvention convention : {EulerConvention::kFixedXyz, EulerConvention::kParol6Commander}) {
    for (const double pitch : {kPi / 2, -kPi / 2}) {
      const Eigen::Isometry3d transform = transform_of(convention, EulerPose{.angles_rad = {0.3, pitch, 0.5}});
      const EulerPose back = pose_of(convention, transform);
      EXPECT_EQ(back.angles_rad[0], 0.0);
      EXPECT_NEAR(back.angles_rad[1], pitch, 1e-12);
      EXPECT_TRUE(transform_of(convention, back).linear().isApprox(transform.linear(), 1e-12));
    }
  }
}

}  // namespace
}  // namespace robotd::kinematics
