// PAROL6 kinematics against the spec's FK check values (parol6_serial.md §11.1), the commander's
// roll/pitch/yaw convention, the inverse kinematics, and the commander's move timing
// (MoveJoint / MovePose trapezoid and polynomial, MoveCart along a line).
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

// --- joint moves -----------------------------------------------------------------------------------

/// Finite-difference speed of joint j between samples k − 1 and k.
double speed_at(const std::vector<JointVector>& samples, std::size_t k, std::size_t j) {
  return (samples[k][j] - samples[k - 1][j]) / kDt;
}

double peak_speed(const std::vector<JointVector>& samples, std::size_t j) {
  double peak = 0;
  for (std::size_t k = 1; k < samples.size(); ++k) peak = std::max(peak, std::abs(speed_at(samples, k, j)));
  return peak;
}

double peak_acceleration(const std::vector<JointVector>& samples, std::size_t j) {
  double peak = 0;
  for (std::size_t k = 2; k < samples.size(); ++k) {
    peak = std::max(peak, std::abs(speed_at(samples, k, j) - speed_at(samples, k - 1, j)) / kDt);
  }
  return peak;
}

constexpr JointVector kFrom = degrees_to_q({0, -90, 180, 0, 0, 180});
constexpr JointVector kTo = degrees_to_q({60, -60, 150, 30, -45, 90});

std::vector<JointVector> plan(const JointVector& from, const JointVector& to, const MoveTiming& timing,
                              const Limits& limits = joint_limits()) {
  std::string error;
  std::vector<JointVector> samples =
      plan_joint_move(from, to, timing, limits.max_speed, limits.max_acceleration, kDt, error);
  EXPECT_TRUE(error.empty()) << error;
  EXPECT_FALSE(samples.empty());
  return samples;
}

TEST(Parol6JointMove, HonoursTheDurationWithBothEndsIncluded) {
  for (const Profile profile : {Profile::kTrapezoid, Profile::kPolynomial}) {
    const auto samples = plan(kFrom, kTo, MoveTiming{.profile = profile, .duration_s = 4.0});
    EXPECT_EQ(samples.size(), 401U);
    EXPECT_EQ(samples.front(), kFrom);
    EXPECT_EQ(samples.back(), kTo);
  }
  EXPECT_EQ(plan(kFrom, kTo, MoveTiming{.duration_s = 4.004}).size(), 402U);  // rounded up to whole samples
}

TEST(Parol6JointMove, StartsAndEndsAtRest) {
  for (const Profile profile : {Profile::kTrapezoid, Profile::kPolynomial}) {
    for (const std::optional<double> duration : {std::optional<double>(4.0), std::optional<double>()}) {
      const auto samples = plan(kFrom, kTo, MoveTiming{.profile = profile, .duration_s = duration});
      ASSERT_GT(samples.size(), 10U);
      for (std::size_t j = 0; j < kJoints; ++j) {
        const double peak = peak_speed(samples, j);
        EXPECT_LT(std::abs(speed_at(samples, 1, j)), 0.02 * peak + 1e-12);
        EXPECT_LT(std::abs(speed_at(samples, samples.size() - 1, j)), 0.02 * peak + 1e-12);
      }
    }
  }
}

TEST(Parol6JointMove, TrapezoidWithADurationIsThirds) {
  const auto samples = plan(kFrom, kTo, MoveTiming{.profile = Profile::kTrapezoid, .duration_s = 3.0});
  ASSERT_EQ(samples.size(), 301U);
  for (std::size_t j = 0; j < kJoints; ++j) {
    const double distance = kTo[j] - kFrom[j];
    if (distance == 0) continue;
    // A quarter of the way after the first third, three quarters after the second.
    EXPECT_NEAR((samples[100][j] - kFrom[j]) / distance, 0.25, 1e-12);
    EXPECT_NEAR((samples[200][j] - kFrom[j]) / distance, 0.75, 1e-12);
    // Cruise at 1.5 × the mean speed through the middle third, ramps of constant acceleration.
    for (std::size_t k = 101; k <= 200; ++k) EXPECT_NEAR(speed_at(samples, k, j), 1.5 * distance / 3.0, 1e-9);
    for (std::size_t k = 2; k <= 100; ++k) {
      EXPECT_NEAR(speed_at(samples, k, j) - speed_at(samples, k - 1, j), 0.5 * distance * kDt, 1e-9);
    }
  }
}

TEST(Parol6JointMove, PolynomialIsTheQuintic) {
  const auto samples = plan(kFrom, kTo, MoveTiming{.profile = Profile::kPolynomial, .duration_s = 2.0});
  ASSERT_EQ(samples.size(), 201U);
  for (std::size_t j = 0; j < kJoints; ++j) {
    const double distance = kTo[j] - kFrom[j];
    if (distance == 0) continue;
    for (std::size_t k = 0; k < samples.size(); ++k) {
      const double tau = static_cast<double>(k) / 200.0;
      const double s = 10 * std::pow(tau, 3) - 15 * std::pow(tau, 4) + 6 * std::pow(tau, 5);
      EXPECT_NEAR(samples[k][j], kFrom[j] + s * distance, 1e-12);
    }
    EXPECT_NEAR(peak_speed(samples, j), 1.875 * std::abs(distance) / 2.0, 1e-3 * std::abs(distance));
  }
}

TEST(Parol6JointMove, AllJointsFollowOneProfileAndArriveTogether) {
  const auto samples = plan(kFrom, kTo, MoveTiming{});
  for (const JointVector& q : samples) {
    const double s = (q[0] - kFrom[0]) / (kTo[0] - kFrom[0]);
    for (std::size_t j = 1; j < kJoints; ++j) {
      if (kTo[j] == kFrom[j]) continue;
      EXPECT_NEAR((q[j] - kFrom[j]) / (kTo[j] - kFrom[j]), s, 1e-12);
    }
  }
}

TEST(Parol6JointMove, WithoutADurationTheLeadingJointReachesItsFraction) {
  const Limits limits = joint_limits();
  const MoveTiming timing{.duration_s = std::nullopt, .speed_fraction = 0.5, .acceleration_fraction = 0.5};
  const auto samples = plan(kFrom, kTo, timing, limits);
  // J6 (90° at up to 2.65 rad/s) has the longest way for its speed: it leads, at half its maximum.
  double leading = 0;
  for (std::size_t j = 0; j < kJoints; ++j) {
    const double fraction = peak_speed(samples, j) / limits.max_speed[j];
    EXPECT_LE(fraction, 0.5 + 1e-9) << "J" << j + 1;
    leading = std::max(leading, fraction);
  }
  EXPECT_GT(leading, 0.49);
}

TEST(Parol6JointMove, NeverExceedsTheJointLimitsFraction) {
  Random random;
  const Limits limits = joint_limits();
  for (int i = 0; i < 200; ++i) {
    const JointVector from = random.joints_within(limits);
    const JointVector to = random.joints_within(limits);
    const MoveTiming timing{.profile = i % 2 == 0 ? Profile::kTrapezoid : Profile::kPolynomial,
                            .duration_s = std::nullopt,
                            .speed_fraction = random.uniform(0.05, 1.0),
                            .acceleration_fraction = random.uniform(0.05, 1.0)};
    const auto samples = plan(from, to, timing, limits);
    ASSERT_GE(samples.size(), 2U);
    EXPECT_EQ(samples.front(), from);
    EXPECT_EQ(samples.back(), to);
    bool some_limit_reached = false;
    for (std::size_t j = 0; j < kJoints; ++j) {
      const double speed = peak_speed(samples, j);
      const double acceleration = peak_acceleration(samples, j);
      EXPECT_LE(speed, timing.speed_fraction * limits.max_speed[j] * (1 + 1e-9));
      EXPECT_LE(acceleration, timing.acceleration_fraction * limits.max_acceleration[j] * (1 + 1e-6));
      some_limit_reached = some_limit_reached || speed > 0.97 * timing.speed_fraction * limits.max_speed[j] ||
                           acceleration > 0.9 * timing.acceleration_fraction * limits.max_acceleration[j];
    }
    EXPECT_TRUE(some_limit_reached) << "the move is slower than it needs to be";
  }
}

TEST(Parol6JointMove, AShortMoveIsATriangle) {
  const Limits limits = joint_limits();
  JointVector to = kFrom;
  to[0] += 0.01;  // J1 never gets to cruise: 2·√(d/a) = 0.076 s
  const auto samples = plan(
      kFrom, to, MoveTiming{.duration_s = std::nullopt, .speed_fraction = 1.0, .acceleration_fraction = 1.0}, limits);
  EXPECT_EQ(samples.size(), 9U);
  EXPECT_LT(peak_speed(samples, 0), limits.max_speed[0]);
  EXPECT_LE(peak_acceleration(samples, 0), limits.max_acceleration[0] * (1 + 1e-9));
}

TEST(Parol6JointMove, RefusesADurationTooShortForAJoint) {
  const Limits limits = joint_limits();
  std::string error;
  const auto samples =
      plan_joint_move(kFrom, kTo, MoveTiming{.duration_s = 0.5}, limits.max_speed, limits.max_acceleration, kDt, error);
  EXPECT_TRUE(samples.empty());
  EXPECT_NE(error.find("J6"), std::string::npos) << error;
  EXPECT_NE(error.find("needs at least"), std::string::npos) << error;
}

TEST(Parol6JointMove, ANullMoveIsOneSampleOrHoldsForTheDuration) {
  EXPECT_EQ(plan(kFrom, kFrom, MoveTiming{}), std::vector<JointVector>{kFrom});
  const auto held = plan(kFrom, kFrom, MoveTiming{.duration_s = 0.5});
  EXPECT_EQ(held.size(), 51U);
  for (const JointVector& q : held) EXPECT_EQ(q, kFrom);
}

TEST(Parol6JointMove, RefusesBadArguments) {
  const Limits limits = joint_limits();
  const auto refused = [&](const JointVector& to, const MoveTiming& timing, double dt, const JointVector& speed) {
    std::string error;
    const bool empty = plan_joint_move(kFrom, to, timing, speed, limits.max_acceleration, dt, error).empty();
    return empty && !error.empty();
  };
  EXPECT_TRUE(refused(kTo, MoveTiming{}, 0.0, limits.max_speed));
  EXPECT_TRUE(refused(kTo, MoveTiming{}, -0.01, limits.max_speed));
  EXPECT_TRUE(refused(kTo, MoveTiming{.duration_s = 0.0}, kDt, limits.max_speed));
  EXPECT_TRUE(refused(kTo, MoveTiming{.duration_s = -1.0}, kDt, limits.max_speed));
  EXPECT_TRUE(refused(kTo, MoveTiming{.duration_s = 1e9}, kDt, limits.max_speed));
  EXPECT_TRUE(refused(kTo, MoveTiming{.duration_s = std::nullopt, .speed_fraction = 0.0}, kDt, limits.max_speed));
  EXPECT_TRUE(refused(kTo, MoveTiming{.duration_s = std::nullopt, .speed_fraction = 1.5}, kDt, limits.max_speed));
  EXPECT_TRUE(refused(kTo, MoveTiming{.duration_s = std::nullopt, .acceleration_fraction = std::nan("")}, kDt,
                      limits.max_speed));
  EXPECT_TRUE(refused(kTo, MoveTiming{.duration_s = std::nullopt, .speed_fraction = 1e-12}, kDt,
                      limits.max_speed));  // a million samples
  JointVector bad = kTo;
  bad[2] = std::nan("");
  EXPECT_TRUE(refused(bad, MoveTiming{}, kDt, limits.max_speed));
  JointVector no_speed = limits.max_speed;
  no_speed[1] = 0;
  EXPECT_TRUE(refused(kTo, MoveTiming{}, kDt, no_speed));
  EXPECT_FALSE(refused(kTo, MoveTiming{}, kDt, limits.max_speed));
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

std::vector<JointVector> plan_line(const JointVector& from, const Pose& target, const MoveTiming& timing,
                                   double linear_speed_m_s, std::string& error) {
  const Limits limits = joint_limits();
  return plan_cartesian_move(from, target, timing, limits.min_rad, limits.max_rad, limits.max_speed, linear_speed_m_s,
                             kDt, error);
}

TEST(Parol6CartesianMove, TheToolStaysOnTheLine) {
  Pose target = shifted(kWorking, 0.05, -0.04, 0.03);
  target.roll_rad += 0.2;
  target.yaw_rad -= 0.1;
  const Limits limits = joint_limits();
  for (const Profile profile : {Profile::kTrapezoid, Profile::kPolynomial}) {
    std::string error;
    const auto samples = plan_line(kWorking, target, MoveTiming{.profile = profile, .duration_s = 2.0}, 0.0, error);
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
  const auto samples = plan_line(kWorking, target, MoveTiming{}, 0.02, error);
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
      plan_line(kWorking, target, MoveTiming{.profile = Profile::kPolynomial, .duration_s = std::nullopt}, 0.02, error);
  ASSERT_FALSE(samples.empty()) << error;
  EXPECT_EQ(samples.size(), 151U);
}

/// The percentage an error message gives: "… (42% of the path) …".
std::optional<double> percent_in(const std::string& error) {
  const std::size_t end = error.find("% of the path");
  if (end == std::string::npos) return std::nullopt;
  const std::size_t start = error.rfind('(', end);
  if (start == std::string::npos) return std::nullopt;
  return std::stod(error.substr(start + 1, end - start - 1));
}

TEST(Parol6CartesianMove, FailsNearAWristSingularityNamingWhere) {
  // J5 goes from +20° to −20° while J4 turns 5°: the line passes next to J5 = 0, where J4 and J6
  // line up and J4 would have to spin.
  const JointVector from = degrees_to_q({0, -60, 150, 0, 20, 180});
  const Pose target = forward_kinematics(degrees_to_q({0, -60, 150, 5, -20, 180}));
  std::string error;
  EXPECT_TRUE(plan_line(from, target, MoveTiming{.duration_s = 2.0}, 0.0, error).empty());
  EXPECT_NE(error.find("J4 would turn at"), std::string::npos) << error;
  EXPECT_NE(error.find("singularity"), std::string::npos) << error;
  const std::optional<double> percent = percent_in(error);
  ASSERT_TRUE(percent) << error;
  EXPECT_GT(*percent, 30);
  EXPECT_LT(*percent, 70);
}

TEST(Parol6CartesianMove, PassesExactlyThroughAWristSingularityWhenNoJointMustSpin) {
  // The same line without the J4 turn only needs J5 to pass zero.
  const JointVector from = degrees_to_q({0, -60, 150, 0, 20, 180});
  const JointVector to = degrees_to_q({0, -60, 150, 0, -20, 180});
  std::string error;
  const auto samples = plan_line(from, forward_kinematics(to), MoveTiming{.duration_s = 2.0}, 0.0, error);
  ASSERT_EQ(samples.size(), 201U) << error;
  for (std::size_t j = 0; j < kJoints; ++j) EXPECT_NEAR(samples.back()[j], to[j], 1e-6) << "J" << j + 1;
}

TEST(Parol6CartesianMove, FailsAtAJointLimitNamingWhere) {
  // Around the base from J1 = 100° to where J1 would be 150°, past its 123° limit.
  const JointVector from = degrees_to_q({100, -60, 150, 0, 45, 180});
  const Pose target = forward_kinematics(degrees_to_q({150, -60, 150, 0, 45, 180}));
  std::string error;
  EXPECT_TRUE(plan_line(from, target, MoveTiming{.duration_s = 5.0}, 0.0, error).empty());
  EXPECT_NE(error.find("no joint solution"), std::string::npos) << error;
  EXPECT_NE(error.find("past a joint limit"), std::string::npos) << error;
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
  const auto samples = plan_line(kWorking, target, MoveTiming{.duration_s = 30.0}, 0.0, error);
  EXPECT_TRUE(samples.empty());
  const std::optional<double> percent = percent_in(error);
  ASSERT_TRUE(percent) << error;
  EXPECT_LT(*percent, 60) << error;  // the arm is about 0.3 m short of the target
  EXPECT_TRUE(error.find("out of reach") != std::string::npos || error.find("singularity") != std::string::npos)
      << error;
}

TEST(Parol6CartesianMove, ANullMoveIsOneSample) {
  std::string error;
  const auto samples = plan_line(kWorking, forward_kinematics(kWorking), MoveTiming{}, 0.02, error);
  EXPECT_EQ(samples, std::vector<JointVector>{kWorking}) << error;
}

TEST(Parol6CartesianMove, RefusesBadArguments) {
  std::string error;
  EXPECT_TRUE(plan_line(kWorking, shifted(kWorking, 0.01, 0, 0), MoveTiming{}, 0.0, error).empty());
  EXPECT_FALSE(error.empty());
  Pose bad = forward_kinematics(kWorking);
  bad.pitch_rad = std::nan("");
  EXPECT_TRUE(plan_line(kWorking, bad, MoveTiming{}, 0.02, error).empty());
  EXPECT_FALSE(error.empty());
  EXPECT_TRUE(plan_line(kWorking, shifted(kWorking, 0.01, 0, 0), MoveTiming{.duration_s = -1}, 0.02, error).empty());
  EXPECT_FALSE(error.empty());
}

}  // namespace
}  // namespace robotd::parol6
