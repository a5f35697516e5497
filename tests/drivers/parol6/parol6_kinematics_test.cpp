// PAROL6 kinematics against the spec's FK check values (parol6_serial.md §11.1), the commander's
// roll/pitch/yaw convention, the inverse kinematics, and MoveCart's straight line on the PAROL6
// (planned by robotd/motion, whose joint-move rules tests/motion checks on any arm).
#include "kinematics/parol6_kinematics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "codec/joint_units.hpp"
#include "robotd/motion/cartesian_move.hpp"
#include "thread_allocations.hpp"

namespace robotd::parol6 {
namespace {

constexpr double radians(double deg) { return deg * std::numbers::pi / 180.0; }
constexpr double kDt = 0.01;  // the hosts' 100 Hz

constexpr JointVector degrees_to_q(const std::array<double, kJoints>& deg) {
  JointVector q{};
  for (std::size_t j = 0; j < q.size(); ++j) q[j] = radians(deg[j]);
  return q;
}

constexpr JointVector kStandby = degrees_to_q({0, -90, 180, 0, 0, 180});  // the commander's DH standby

struct Limits {
  JointVector min_rad{};
  JointVector max_rad{};
  JointVector max_speed{};         // rad/s
  JointVector max_acceleration{};  // rad/s²
};

Limits joint_limits() {
  Limits limits;
  for (int j = 0; j < kJoints; ++j) {
    const auto i = static_cast<std::size_t>(j);
    const JointUnits& units = joint_units()[i];
    limits.min_rad[i] = units.min_rad;
    limits.max_rad[i] = units.max_rad;
    limits.max_speed[i] = steps_per_s_to_rad_per_s(j, units.max_speed_steps_s);
    limits.max_acceleration[i] = steps_per_s_to_rad_per_s(j, units.max_acceleration_steps_s2);
  }
  return limits;
}

/// Rotation angle between two transforms plus the distance between their origins.
struct Difference {
  double position_m;
  double rotation_rad;
};

Difference difference(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return {(a.translation() - b.translation()).norm(), Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle()};
}

Eigen::Matrix3d rot_x(double a) {
  Eigen::Matrix3d r;
  r << 1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a);
  return r;
}
Eigen::Matrix3d rot_y(double a) {
  Eigen::Matrix3d r;
  r << std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a);
  return r;
}
Eigen::Matrix3d rot_z(double a) {
  Eigen::Matrix3d r;
  r << std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1;
  return r;
}

class Random {
 public:
  double uniform(double low, double high) { return std::uniform_real_distribution<double>(low, high)(random_); }
  JointVector joints_within(const Limits& limits, double margin = 0.0) {
    JointVector q{};
    for (std::size_t j = 0; j < q.size(); ++j) q[j] = uniform(limits.min_rad[j] + margin, limits.max_rad[j] - margin);
    return q;
  }
  Pose pose() {
    return {uniform(-0.5, 0.5),
            uniform(-0.5, 0.5),
            uniform(0, 0.6),
            uniform(-std::numbers::pi, std::numbers::pi),
            uniform(-std::numbers::pi / 2, std::numbers::pi / 2),
            uniform(-std::numbers::pi, std::numbers::pi)};
  }

 private:
  std::mt19937 random_{42};
};

// --- forward kinematics (§11.1) ------------------------------------------------------------------

struct FkCheck {
  std::array<double, kJoints> q_deg;
  std::array<double, 3> position_mm;
};

constexpr std::array<FkCheck, 4> kFkChecks{{
    {{0, -90, 180, 0, 0, 180}, {262.57, 0.00, 288.75}},
    {{90, -90, 180, 0, 0, 180}, {0.00, 262.57, 288.75}},
    {{10, -60, 200, 20, -30, 100}, {325.356, 86.622, 219.474}},
    {{0, 0, 0, 0, 0, 0}, {114.67, 0.00, 349.65}},
}};

TEST(Parol6Kinematics, ForwardKinematicsMatchesTheSpecCheckValues) {
  for (const FkCheck& check : kFkChecks) {
    const Pose pose = forward_kinematics(degrees_to_q(check.q_deg));
    SCOPED_TRACE(::testing::Message() << "q1 " << check.q_deg[0] << ", q2 " << check.q_deg[1]);
    // The spec gives 2 or 3 decimals; its 2-decimal values are rounded to 0.005 mm.
    EXPECT_NEAR(pose.x_m * 1000, check.position_mm[0], 0.01);
    EXPECT_NEAR(pose.y_m * 1000, check.position_mm[1], 0.01);
    EXPECT_NEAR(pose.z_m * 1000, check.position_mm[2], 0.01);
  }
}

TEST(Parol6Kinematics, AtStandbyTheToolPointsAlongBaseX) {
  const Eigen::Isometry3d tool = tool_transform(kStandby);
  EXPECT_NEAR(tool.linear().col(2).x(), 1.0, 1e-12);
  EXPECT_NEAR(tool.linear().col(2).y(), 0.0, 1e-12);
  EXPECT_NEAR(tool.linear().col(2).z(), 0.0, 1e-12);
}

TEST(Parol6Kinematics, JointOneTurnsTheArmAboutBaseZ) {
  Random random;
  const Limits limits = joint_limits();
  for (int i = 0; i < 100; ++i) {
    JointVector q = random.joints_within(limits);
    const double turn = random.uniform(-1, 1);
    const Eigen::Isometry3d before = tool_transform(q);
    q[0] += turn;
    const Eigen::Isometry3d expected = Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ()) * before;
    const Difference error = difference(tool_transform(q), expected);
    EXPECT_LT(error.position_m, 1e-12);
    EXPECT_LT(error.rotation_rad, 1e-12);
  }
}

TEST(Parol6Kinematics, ForwardKinematicsDoesNotAllocate) {
  const JointVector q = degrees_to_q({10, -60, 200, 20, -30, 100});
  const std::size_t before = testing::allocations_on_this_thread();
  const Pose pose = forward_kinematics(q);
  const Eigen::Isometry3d back = transform_of(pose);
  const Pose again = pose_of(back);
  EXPECT_EQ(testing::allocations_on_this_thread(), before);
  EXPECT_NEAR(again.x_m, pose.x_m, 1e-12);
}

// --- the commander's roll/pitch/yaw ---------------------------------------------------------------

TEST(Parol6Pose, EachAngleTurnsAboutItsCommanderAxis) {
  const double angle = 0.7;
  const auto rotation = [](const Pose& pose) -> Eigen::Matrix3d { return transform_of(pose).linear(); };
  EXPECT_TRUE(rotation(Pose{.roll_rad = angle}).isApprox(rot_z(angle), 1e-12));  // Rx of MovePose: about z
  EXPECT_TRUE(rotation(Pose{.pitch_rad = angle}).isApprox(rot_y(angle), 1e-12));
  EXPECT_TRUE(rotation(Pose{.yaw_rad = angle}).isApprox(rot_x(angle), 1e-12));  // Rz of MovePose: about x
}

TEST(Parol6Pose, RotationIsSpatialmathRpyInXyzOrder) {
  // SE3.RPY([a, b, c], order="xyz") = rotx(c) · roty(b) · rotz(a).
  const Pose pose{.x_m = 0.1, .y_m = -0.2, .z_m = 0.3, .roll_rad = 0.3, .pitch_rad = -0.5, .yaw_rad = 1.2};
  const Eigen::Isometry3d transform = transform_of(pose);
  EXPECT_TRUE(transform.linear().isApprox(rot_x(1.2) * rot_y(-0.5) * rot_z(0.3), 1e-12));
  EXPECT_TRUE(transform.translation().isApprox(Eigen::Vector3d(0.1, -0.2, 0.3)));
}

TEST(Parol6Pose, PoseAtStandby) {
  // Tool z along base x: pitch +90°, so roll is 0 and the turn is in yaw.
  const Pose pose = forward_kinematics(kStandby);
  EXPECT_NEAR(pose.pitch_rad, std::numbers::pi / 2, 1e-12);
  EXPECT_EQ(pose.roll_rad, 0.0);
  EXPECT_LT(difference(transform_of(pose), tool_transform(kStandby)).rotation_rad, 1e-7);
}

TEST(Parol6Pose, PoseOfInvertsTransformOf) {
  Random random;
  for (int i = 0; i < 1000; ++i) {
    const Pose pose = random.pose();
    if (std::abs(pose.pitch_rad) > radians(89.9)) continue;
    const Pose back = pose_of(transform_of(pose));
    EXPECT_NEAR(back.x_m, pose.x_m, 1e-15);
    EXPECT_NEAR(back.y_m, pose.y_m, 1e-15);
    EXPECT_NEAR(back.z_m, pose.z_m, 1e-15);
    EXPECT_NEAR(back.roll_rad, pose.roll_rad, 1e-9);
    EXPECT_NEAR(back.pitch_rad, pose.pitch_rad, 1e-9);
    EXPECT_NEAR(back.yaw_rad, pose.yaw_rad, 1e-9);
  }
}

TEST(Parol6Pose, TransformOfInvertsPoseOfForAnyRotation) {
  Random random;
  for (int i = 0; i < 2000; ++i) {
    Eigen::Quaterniond rotation(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1),
                                random.uniform(-1, 1));
    rotation.normalize();
    Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
    transform.linear() = rotation.toRotationMatrix();
    transform.translation() << random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1);
    const Pose pose = pose_of(transform);
    EXPECT_LE(std::abs(pose.pitch_rad), std::numbers::pi / 2);
    const Difference error = difference(transform_of(pose), transform);
    EXPECT_LT(error.position_m, 1e-15);
    EXPECT_LT(error.rotation_rad, 1e-9);
  }
}

TEST(Parol6Pose, AtPitchNinetyDegreesYawCarriesTheTurn) {
  for (const double pitch : {std::numbers::pi / 2, -std::numbers::pi / 2}) {
    const Pose pose{.roll_rad = 0.3, .pitch_rad = pitch, .yaw_rad = 0.5};
    const Pose back = pose_of(transform_of(pose));
    EXPECT_DOUBLE_EQ(back.pitch_rad, pitch);
    EXPECT_EQ(back.roll_rad, 0.0);
    EXPECT_NEAR(back.yaw_rad, pitch > 0 ? 0.5 + 0.3 : 0.5 - 0.3, 1e-9);
    EXPECT_LT(difference(transform_of(back), transform_of(pose)).rotation_rad, 1e-9);
  }
}

// --- inverse kinematics ----------------------------------------------------------------------------

TEST(Parol6InverseKinematics, RecoversRandomReachableConfigurations) {
  Random random;
  const Limits limits = joint_limits();
  for (int i = 0; i < 500; ++i) {
    const JointVector q = random.joints_within(limits);
    const Pose target = forward_kinematics(q);
    JointVector seed = q;
    for (double& angle : seed) angle += random.uniform(-0.1, 0.1);
    const IkResult result = inverse_kinematics(target, seed, limits.min_rad, limits.max_rad);
    SCOPED_TRACE(::testing::Message() << "sample " << i);
    ASSERT_TRUE(result.converged) << "position error " << result.position_error_m << " m, orientation error "
                                  << result.orientation_error_rad << " rad";
    const Difference error = difference(tool_transform(result.q_rad), transform_of(target));
    EXPECT_LT(error.position_m, 1e-6);
    EXPECT_LT(error.rotation_rad, 1e-6);
    EXPECT_NEAR(error.position_m, result.position_error_m, 1e-9);
    for (std::size_t j = 0; j < q.size(); ++j) {
      EXPECT_GE(result.q_rad[j], limits.min_rad[j]);
      EXPECT_LE(result.q_rad[j], limits.max_rad[j]);
    }
  }
}

TEST(Parol6InverseKinematics, FromTheSolutionStaysThere) {
  const Limits limits = joint_limits();
  const JointVector q = degrees_to_q({10, -60, 200, 20, -30, 100});
  const IkResult result = inverse_kinematics(forward_kinematics(q), q, limits.min_rad, limits.max_rad);
  EXPECT_TRUE(result.converged);
  for (std::size_t j = 0; j < q.size(); ++j) EXPECT_NEAR(result.q_rad[j], q[j], 1e-9);
}

TEST(Parol6InverseKinematics, ReportsAnUnreachablePose) {
  const Limits limits = joint_limits();
  const Pose far{.x_m = 1.0, .z_m = 0.3};
  const IkResult result = inverse_kinematics(far, kStandby, limits.min_rad, limits.max_rad);
  EXPECT_FALSE(result.converged);
  EXPECT_GT(result.position_error_m, 0.4);
  for (std::size_t j = 0; j < kJoints; ++j) {
    EXPECT_GE(result.q_rad[j], limits.min_rad[j]);
    EXPECT_LE(result.q_rad[j], limits.max_rad[j]);
  }
}

TEST(Parol6InverseKinematics, KeepsToTheJointLimits) {
  Limits limits = joint_limits();
  const JointVector q = degrees_to_q({40, -80, 170, 10, 20, 150});
  limits.max_rad[0] = radians(30);  // the target needs J1 = 40°
  const IkResult result = inverse_kinematics(forward_kinematics(q), degrees_to_q({25, -80, 170, 10, 20, 150}),
                                             limits.min_rad, limits.max_rad);
  EXPECT_FALSE(result.converged);
  EXPECT_LE(result.q_rad[0], radians(30));
}

// --- Cartesian moves -------------------------------------------------------------------------------

constexpr JointVector kWorking = degrees_to_q({10, -60, 150, 10, 45, 170});  // well clear of singularities

/// Distance of `point` from the segment a–b.
double off_line(const Eigen::Vector3d& point, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double t = std::clamp((point - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + t * ab - point).norm();
}

Pose shifted(const JointVector& q, double dx_m, double dy_m, double dz_m) {
  Pose pose = forward_kinematics(q);
  pose.x_m += dx_m;
  pose.y_m += dy_m;
  pose.z_m += dz_m;
  return pose;
}

/// The line from `from` to `target` as the PAROL6 driver's move_cart plans it; empty, with
/// `error`, when refused.
std::vector<JointVector> plan_line(const JointVector& from, const Pose& target, const motion::MoveTiming& timing,
                                   double linear_speed_m_s, std::string& error) {
  const Limits limits = joint_limits();
  motion::JointLimits motion_limits;
  motion_limits.min_rad.assign(limits.min_rad.begin(), limits.min_rad.end());
  motion_limits.max_rad.assign(limits.max_rad.begin(), limits.max_rad.end());
  motion_limits.max_speed_rad_s.assign(limits.max_speed.begin(), limits.max_speed.end());
  motion_limits.max_acceleration_rad_s2.assign(limits.max_acceleration.begin(), limits.max_acceleration.end());
  motion::LineOptions line;
  line.linear_speed_m_s = linear_speed_m_s;
  const auto plan = motion::plan_line_move(parol6_model(), {from.begin(), from.end()}, transform_of(target), timing,
                                           motion_limits, kDt, line);
  if (!plan) {
    error = plan.error().message;
    return {};
  }
  std::vector<JointVector> samples(plan.value().positions.size());
  for (std::size_t k = 0; k < samples.size(); ++k) {
    std::copy_n(plan.value().positions[k].begin(), kJoints, samples[k].begin());
  }
  return samples;
}

/// Finite-difference speed of joint j between samples k − 1 and k.
double speed_at(const std::vector<JointVector>& samples, std::size_t k, std::size_t j) {
  return (samples[k][j] - samples[k - 1][j]) / kDt;
}

constexpr double kLineSpeed = 0.05;  // m/s: what a line with t does not use

TEST(Parol6CartesianMove, TheToolStaysOnTheLine) {
  Pose target = shifted(kWorking, 0.05, -0.04, 0.03);
  target.roll_rad += 0.2;
  target.yaw_rad -= 0.1;
  const Limits limits = joint_limits();
  for (const motion::Shape shape : {motion::Shape::kTrapezoid, motion::Shape::kPolynomial}) {
    std::string error;
    const auto samples =
        plan_line(kWorking, target, motion::MoveTiming{.duration_s = 2.0, .shape = shape}, kLineSpeed, error);
    ASSERT_EQ(samples.size(), 201U) << error;
    EXPECT_EQ(samples.front(), kWorking);
    const Eigen::Isometry3d start = tool_transform(kWorking);
    const Eigen::Isometry3d goal = transform_of(target);
    const Eigen::Quaterniond start_rotation(start.linear());
    const Eigen::Quaterniond goal_rotation(goal.linear());
    const double turn = start_rotation.angularDistance(goal_rotation);
    for (std::size_t k = 0; k < samples.size(); ++k) {
      const Eigen::Isometry3d tool = tool_transform(samples[k]);
      EXPECT_LT(off_line(tool.translation(), start.translation(), goal.translation()), 1e-4) << "sample " << k;
      // Orientation and position advance together: the same fraction of the turn as of the line.
      const double s =
          (tool.translation() - start.translation()).norm() / (goal.translation() - start.translation()).norm();
      EXPECT_NEAR(Eigen::Quaterniond(tool.linear()).angularDistance(start_rotation), s * turn, 1e-6);
      for (std::size_t j = 0; j < kJoints; ++j) {
        EXPECT_GE(samples[k][j], limits.min_rad[j]);
        EXPECT_LE(samples[k][j], limits.max_rad[j]);
        if (k > 0) {
          EXPECT_LE(std::abs(speed_at(samples, k, j)), limits.max_speed[j]);
        }
      }
    }
    const Difference end = difference(tool_transform(samples.back()), goal);
    EXPECT_LT(end.position_m, 1e-6);
    EXPECT_LT(end.rotation_rad, 1e-6);
  }
}

TEST(Parol6CartesianMove, WithoutADurationTheToolCruisesAtTheLinearSpeed) {
  const Pose target = shifted(kWorking, 0.0, 0.06, 0.0);
  std::string error;
  const auto samples = plan_line(kWorking, target, motion::MoveTiming{}, 0.02, error);
  ASSERT_FALSE(samples.empty()) << error;
  EXPECT_EQ(samples.size(), 451U);  // 60 mm at 20 mm/s, trapezoid thirds: 1.5 × 3 s
  double peak = 0;
  for (std::size_t k = 1; k < samples.size(); ++k) {
    const double step =
        (tool_transform(samples[k]).translation() - tool_transform(samples[k - 1]).translation()).norm();
    peak = std::max(peak, step / kDt);
  }
  EXPECT_NEAR(peak, 0.02, 1e-5);
}

TEST(Parol6CartesianMove, APureTurnIsTimedByTheAngularLimit) {
  Pose target = forward_kinematics(kWorking);
  target.roll_rad += radians(20);  // 20° at 25°/s, polynomial: 1.875 × 0.8 s
  std::string error;
  const auto samples =
      plan_line(kWorking, target, motion::MoveTiming{.shape = motion::Shape::kPolynomial}, 0.02, error);
  ASSERT_FALSE(samples.empty()) << error;
  EXPECT_EQ(samples.size(), 151U);
}

/// The percentage an error message gives first: "… 42.0 % along the line …".
std::optional<double> percent_in(const std::string& error) {
  const std::size_t end = error.find(" % along the line");
  if (end == std::string::npos) return std::nullopt;
  const std::size_t start = error.rfind(' ', end - 1);
  if (start == std::string::npos) return std::nullopt;
  return std::stod(error.substr(start + 1, end - start - 1));
}

TEST(Parol6CartesianMove, FailsNearAWristSingularityNamingWhere) {
  // J5 goes from +20° to −20° while J4 turns 5°: the line passes next to J5 = 0, where J4 and J6
  // line up and J4 would have to spin.
  const JointVector from = degrees_to_q({0, -60, 150, 0, 20, 180});
  const Pose target = forward_kinematics(degrees_to_q({0, -60, 150, 5, -20, 180}));
  std::string error;
  EXPECT_TRUE(plan_line(from, target, motion::MoveTiming{.duration_s = 2.0}, kLineSpeed, error).empty());
  EXPECT_NE(error.find("J4 would turn at"), std::string::npos) << error;
  EXPECT_NE(error.find("singularity"), std::string::npos) << error;
  const std::optional<double> percent = percent_in(error);
  ASSERT_TRUE(percent) << error;
  EXPECT_GT(*percent, 30);
  EXPECT_LT(*percent, 70);
}

TEST(Parol6CartesianMove, StopsAtTheWristSingularityEvenWhenNoJointMustSpin) {
  // The same line without the J4 turn only needs J5 to pass zero; like the commander's MoveCart
  // it stops close to the singularity, about half way.
  const JointVector from = degrees_to_q({0, -60, 150, 0, 20, 180});
  const JointVector to = degrees_to_q({0, -60, 150, 0, -20, 180});
  std::string error;
  EXPECT_TRUE(
      plan_line(from, forward_kinematics(to), motion::MoveTiming{.duration_s = 2.0}, kLineSpeed, error).empty());
  EXPECT_NE(error.find("stops before a singularity"), std::string::npos) << error;
  const std::optional<double> percent = percent_in(error);
  ASSERT_TRUE(percent) << error;
  EXPECT_GT(*percent, 40);
  EXPECT_LT(*percent, 50);
}

TEST(Parol6CartesianMove, LeavesTheWristSingularityItStartsAt) {
  // The commander's examples start their lines from MoveJoint(90, -90, 180, 0, 0, 180), J5 = 0.
  const JointVector from = degrees_to_q({90, -90, 180, 0, 0, 180});
  const Pose target = shifted(from, 0.0, 0.0, -0.03);
  std::string error;
  const auto samples = plan_line(from, target, motion::MoveTiming{.duration_s = 1.0}, kLineSpeed, error);
  ASSERT_EQ(samples.size(), 101U) << error;
  EXPECT_LT(difference(tool_transform(samples.back()), transform_of(target)).position_m, 1e-6);
}

TEST(Parol6CartesianMove, FailsAtAJointLimitNamingWhere) {
  // Around the base from J1 = 100° to where J1 would be 150°, past its 123° limit.
  const JointVector from = degrees_to_q({100, -60, 150, 0, 45, 180});
  const Pose target = forward_kinematics(degrees_to_q({150, -60, 150, 0, 45, 180}));
  std::string error;
  EXPECT_TRUE(plan_line(from, target, motion::MoveTiming{.duration_s = 5.0}, kLineSpeed, error).empty());
  EXPECT_NE(error.find("no joint solution"), std::string::npos) << error;
  EXPECT_NE(error.find("J1 would need"), std::string::npos) << error;
  EXPECT_NE(error.find("outside its limits"), std::string::npos) << error;
  const std::optional<double> percent = percent_in(error);
  ASSERT_TRUE(percent) << error;
  EXPECT_GT(*percent, 35);  // the chord reaches 123° a little before halfway
  EXPECT_LT(*percent, 50);
}

TEST(Parol6CartesianMove, OutOfReachFailsNamingWhere) {
  // Stretching out to the edge of the workspace is a singularity too: the elbow would have to
  // straighten ever faster, so either message may come first.
  const Pose target = shifted(kWorking, 0.6, 0.0, 0.0);
  std::string error;
  const auto samples = plan_line(kWorking, target, motion::MoveTiming{.duration_s = 30.0}, kLineSpeed, error);
  EXPECT_TRUE(samples.empty());
  const std::optional<double> percent = percent_in(error);
  ASSERT_TRUE(percent) << error;
  EXPECT_LT(*percent, 60) << error;  // the arm is about 0.3 m short of the target
  EXPECT_TRUE(error.find("out of reach") != std::string::npos || error.find("singularity") != std::string::npos)
      << error;
}

TEST(Parol6CartesianMove, ANullMoveIsOneSample) {
  std::string error;
  const auto samples = plan_line(kWorking, forward_kinematics(kWorking), motion::MoveTiming{}, 0.02, error);
  EXPECT_EQ(samples, std::vector<JointVector>{kWorking}) << error;
}

TEST(Parol6CartesianMove, RefusesBadArguments) {
  std::string error;
  EXPECT_TRUE(plan_line(kWorking, shifted(kWorking, 0.01, 0, 0), motion::MoveTiming{}, 0.0, error).empty());
  EXPECT_FALSE(error.empty());
  Pose bad = forward_kinematics(kWorking);
  bad.pitch_rad = std::nan("");
  EXPECT_TRUE(plan_line(kWorking, bad, motion::MoveTiming{}, 0.02, error).empty());
  EXPECT_FALSE(error.empty());
  EXPECT_TRUE(
      plan_line(kWorking, shifted(kWorking, 0.01, 0, 0), motion::MoveTiming{.duration_s = -1}, 0.02, error).empty());
  EXPECT_FALSE(error.empty());
}

}  // namespace
}  // namespace robotd::parol6
