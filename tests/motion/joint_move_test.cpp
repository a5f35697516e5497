// Joint moves against the RBTscript rules, checked on the sampled positions and velocities:
// t with "trap" is thirds and with nothing else the quintic, t overrides v/a, v/a apply to the
// leading joint and the others scale onto its path, a path too short for v falls back to thirds,
// the default is a conservative trapezoid, and no joint passes its limits.
#include "robotd/motion/joint_move.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <string>

#include <gtest/gtest.h>

namespace robotd::motion {
namespace {

constexpr double kDt = 1.0 / 128;  // exact in binary, so that sample times land on the thirds

JointLimits six_joint_limits() {
  return {.min_rad = Joints(6, -3.0),
          .max_rad = Joints(6, 3.0),
          .max_speed_rad_s = {1.0, 1.0, 2.0, 2.0, 3.0, 3.0},
          .max_acceleration_rad_s2 = {2.0, 2.0, 4.0, 4.0, 6.0, 6.0}};
}

const Joints& home() {
  static const Joints joints(6, 0.0);
  return joints;
}
/// J1 leads from home: it has the most way for its speed (1 rad at 1 rad/s) and for its acceleration.
const Joints& goal() {
  static const Joints joints{1.0, -0.5, 1.2, 0.3, -2.4, 0.0};
  return joints;
}

Trajectory plan(const Joints& from, const Joints& to, const MoveTiming& timing,
                const JointLimits& limits = six_joint_limits()) {
  Result<Trajectory> result = plan_joint_move(from, to, timing, limits, kDt);
  EXPECT_TRUE(result.ok()) << result.error().message;
  return result.ok() ? std::move(result).value() : Trajectory{};
}

std::string refusal(const Joints& to, const MoveTiming& timing, const JointLimits& limits = six_joint_limits(),
                    double dt_s = kDt) {
  const Result<Trajectory> result = plan_joint_move(home(), to, timing, limits, dt_s);
  return result.ok() ? std::string("(planned)") : result.error().message;
}

double peak_speed(const Trajectory& trajectory, std::size_t j) {
  double peak = 0;
  for (const Joints& velocity : trajectory.velocities) peak = std::max(peak, std::abs(velocity[j]));
  return peak;
}

double peak_acceleration(const Trajectory& trajectory, std::size_t j) {
  double peak = 0;
  for (std::size_t k = 1; k < trajectory.velocities.size(); ++k) {
    peak = std::max(peak, std::abs(trajectory.velocities[k][j] - trajectory.velocities[k - 1][j]) / kDt);
  }
  return peak;
}

/// Every joint at the same fraction of its way at every sample, and at its goal at the end.
void expect_one_path(const Trajectory& trajectory, const Joints& from, const Joints& to) {
  ASSERT_FALSE(trajectory.positions.empty());
  EXPECT_EQ(trajectory.positions.front(), from);
  EXPECT_EQ(trajectory.positions.back(), to);
  EXPECT_EQ(trajectory.velocities.back(), Joints(to.size(), 0.0));
  EXPECT_EQ(trajectory.velocities.front(), Joints(to.size(), 0.0));
  const std::size_t lead = 0;
  for (std::size_t k = 0; k < trajectory.positions.size(); ++k) {
    const double s = (trajectory.positions[k][lead] - from[lead]) / (to[lead] - from[lead]);
    const double rate = trajectory.velocities[k][lead] / (to[lead] - from[lead]);
    for (std::size_t j = 0; j < to.size(); ++j) {
      const double way = to[j] - from[j];
      if (way == 0) {
        EXPECT_EQ(trajectory.positions[k][j], from[j]);
        continue;
      }
      EXPECT_NEAR((trajectory.positions[k][j] - from[j]) / way, s, 1e-12) << "J" << j + 1 << " sample " << k;
      EXPECT_NEAR(trajectory.velocities[k][j] / way, rate, 1e-12) << "J" << j + 1 << " sample " << k;
    }
  }
}

TEST(JointMove, TrapWithTIsOneThirdAcceleratingOneCruisingOneDecelerating) {
  const Trajectory trajectory = plan(home(), goal(), {.duration_s = 3.0, .shape = Shape::kTrapezoid});
  ASSERT_EQ(trajectory.positions.size(), 385U);  // 3 s of 1/128 s, both ends
  EXPECT_EQ(trajectory.shape, Shape::kTrapezoid);
  EXPECT_DOUBLE_EQ(trajectory.duration_s, 3.0);
  expect_one_path(trajectory, home(), goal());
  for (std::size_t j = 0; j < 6; ++j) {
    const double way = goal()[j] - home()[j];
    // A quarter of the way after the first second, three quarters after the second.
    EXPECT_NEAR(trajectory.positions[128][j], home()[j] + 0.25 * way, 1e-12);
    EXPECT_NEAR(trajectory.positions[256][j], home()[j] + 0.75 * way, 1e-12);
    // Cruise at 1.5 × the mean speed through the middle third; ramps of constant acceleration.
    for (std::size_t k = 128; k <= 256; ++k) EXPECT_NEAR(trajectory.velocities[k][j], 1.5 * way / 3.0, 1e-12);
    for (std::size_t k = 1; k <= 128; ++k) {
      EXPECT_NEAR(trajectory.velocities[k][j] - trajectory.velocities[k - 1][j], 0.5 * way * kDt, 1e-12);
    }
  }
}

TEST(JointMove, TAloneIsTheQuintic) {
  const Trajectory trajectory = plan(home(), goal(), {.duration_s = 2.0});
  ASSERT_EQ(trajectory.positions.size(), 257U);
  EXPECT_EQ(trajectory.shape, Shape::kPolynomial);
  expect_one_path(trajectory, home(), goal());
  for (std::size_t j = 0; j < 6; ++j) {
    const double way = goal()[j] - home()[j];
    for (std::size_t k = 0; k < trajectory.positions.size(); ++k) {
      const double tau = static_cast<double>(k) / 256.0;
      const double s = 10 * std::pow(tau, 3) - 15 * std::pow(tau, 4) + 6 * std::pow(tau, 5);
      const double rate = 30 * tau * tau * (1 - tau) * (1 - tau) / 2.0;
      EXPECT_NEAR(trajectory.positions[k][j], home()[j] + s * way, 1e-12);
      EXPECT_NEAR(trajectory.velocities[k][j], rate * way, 1e-12);
    }
    EXPECT_NEAR(trajectory.positions[128][j], home()[j] + 0.5 * way, 1e-12);  // half way at half time
    // No acceleration at either end: it grows from 0 as 60τ/T², so over the first and the last
    // sample it averages under 3 % of its peak (10/√3 / T²).
    const double peak_acceleration = kQuinticPeakAcceleration / 4.0 * std::abs(way);
    EXPECT_LE(std::abs(trajectory.velocities[1][j]) / kDt, 0.03 * peak_acceleration);
    EXPECT_LE(std::abs(trajectory.velocities[255][j]) / kDt, 0.03 * peak_acceleration);
  }
}

TEST(JointMove, TOverridesVAndA) {
  for (const Shape shape : {Shape::kPolynomial, Shape::kTrapezoid}) {
    const Trajectory timed = plan(home(), goal(), {.duration_s = 4.0, .shape = shape});
    const Trajectory with_percent =
        plan(home(), goal(), {.duration_s = 4.0, .speed_percent = 100.0, .acceleration_percent = 1.0, .shape = shape});
    EXPECT_DOUBLE_EQ(with_percent.duration_s, 4.0);
    EXPECT_EQ(with_percent.shape, shape);
    EXPECT_EQ(with_percent.positions, timed.positions);
    EXPECT_EQ(with_percent.velocities, timed.velocities);
  }
}

TEST(JointMove, TIsRoundedUpToWholeSamples) {
  EXPECT_EQ(plan(home(), goal(), {.duration_s = 4.0 + kDt / 2}).positions.size(), 514U);
  EXPECT_EQ(plan(home(), goal(), {.duration_s = 4.0}).positions.size(), 513U);
}

TEST(JointMove, VAndAApplyToTheLeadingJointAndTheOthersScaleOntoItsPath) {
  const JointLimits limits = six_joint_limits();
  const Trajectory trajectory = plan(home(), goal(), {.speed_percent = 50.0, .acceleration_percent = 50.0});
  EXPECT_EQ(trajectory.shape, Shape::kTrapezoid);
  EXPECT_NE(trajectory.how.find("leading joint J1"), std::string::npos) << trajectory.how;
  expect_one_path(trajectory, home(), goal());
  // J1 cruises at 50 % of 1 rad/s and ramps at 50 % of 2 rad/s²: 0.5 s ramps, 2.5 s in all.
  EXPECT_NEAR(trajectory.duration_s, 2.5, kDt);
  EXPECT_NEAR(peak_speed(trajectory, 0), 0.5, 0.01 * 0.5);
  EXPECT_NEAR(peak_acceleration(trajectory, 0), 1.0, 1e-9);
  for (std::size_t j = 1; j < 6; ++j) {
    EXPECT_LT(peak_speed(trajectory, j), 0.5 * limits.max_speed_rad_s[j]) << "J" << j + 1;
    EXPECT_LT(peak_acceleration(trajectory, j), 0.5 * limits.max_acceleration_rad_s2[j] + 1e-9) << "J" << j + 1;
    EXPECT_NEAR(peak_speed(trajectory, j), peak_speed(trajectory, 0) * std::abs(goal()[j]), 1e-12) << "J" << j + 1;
  }
}

TEST(JointMove, TheLeadingJointIsTheOneThatNeedsTheLongest) {
  // J5 has more way (2.4 rad) but three times J1's speed: J1 (1 rad at 1 rad/s) still leads.
  EXPECT_NE(plan(home(), goal(), {.speed_percent = 50.0}).how.find("leading joint J1"), std::string::npos);
  Joints to = goal();
  to[4] = -2.9;  // 2.9 rad at 3 rad/s is no longer than J1's; 3.3 rad would be (but is past the limit)
  JointLimits slow_j5 = six_joint_limits();
  slow_j5.max_speed_rad_s[4] = 1.5;
  slow_j5.max_acceleration_rad_s2[4] = 3.0;
  const Trajectory trajectory = plan(home(), to, {.speed_percent = 50.0, .acceleration_percent = 50.0}, slow_j5);
  EXPECT_NE(trajectory.how.find("leading joint J5"), std::string::npos) << trajectory.how;
  EXPECT_NEAR(peak_speed(trajectory, 4), 0.5 * 1.5, 0.01 * 0.75);
  EXPECT_LT(peak_speed(trajectory, 0), 0.5 * 1.0);
}

TEST(JointMove, APathTooShortForVFallsBackToThirdsAtA) {
  Joints to(6, 0.0);
  to[0] = 0.0625;  // 100 % of 1 rad/s would need at least 0.5 rad of ramps at 6.25 % of 2 rad/s²
  const Trajectory trajectory = plan(home(), to, {.speed_percent = 100.0, .acceleration_percent = 6.25});
  EXPECT_NE(trajectory.how.find("thirds"), std::string::npos) << trajectory.how;
  // Thirds at 0.125 rad/s²: 4.5 · 0.0625 / T² = 0.125, T = 1.5 s = 192 samples.
  ASSERT_EQ(trajectory.positions.size(), 193U);
  EXPECT_NEAR(trajectory.positions[64][0], 0.25 * 0.0625, 1e-12);
  EXPECT_NEAR(trajectory.positions[128][0], 0.75 * 0.0625, 1e-12);
  for (std::size_t k = 64; k <= 128; ++k) EXPECT_NEAR(trajectory.velocities[k][0], 1.5 * 0.0625 / 1.5, 1e-12);
  EXPECT_NEAR(peak_acceleration(trajectory, 0), 0.0625 * 2.0, 1e-9);
}

TEST(JointMove, NothingGivenIsAConservativeTrapezoid) {
  const Trajectory trajectory = plan(home(), goal(), {});
  EXPECT_EQ(trajectory.shape, Shape::kTrapezoid);
  expect_one_path(trajectory, home(), goal());
  // The leading joint at the default percentages: 0.2 rad/s and 0.4 rad/s², 0.5 s ramps.
  EXPECT_NEAR(peak_speed(trajectory, 0), kDefaultSpeedPercent / 100, 0.01 * 0.2);
  EXPECT_NEAR(peak_acceleration(trajectory, 0), kDefaultAccelerationPercent / 100 * 2.0, 1e-9);
  EXPECT_NEAR(trajectory.duration_s, 1 / 0.2 + 0.5, kDt);
  // One percentage given: the other keeps its default.
  const Trajectory faster = plan(home(), goal(), {.speed_percent = 40.0});
  EXPECT_NEAR(peak_speed(faster, 0), 0.4, 0.01 * 0.4);
  EXPECT_NEAR(peak_acceleration(faster, 0), kDefaultAccelerationPercent / 100 * 2.0, 1e-9);
}

TEST(JointMove, PolyWithoutTKeepsToTheDefaultPercentages) {
  const Trajectory trajectory = plan(home(), goal(), {.shape = Shape::kPolynomial});
  EXPECT_EQ(trajectory.shape, Shape::kPolynomial);
  expect_one_path(trajectory, home(), goal());
  const double speed = peak_speed(trajectory, 0) / 0.2;
  const double acceleration = peak_acceleration(trajectory, 0) / 0.4;
  EXPECT_LE(speed, 1.0);
  EXPECT_LE(acceleration, 1.0 + 1e-9);
  EXPECT_GT(std::max(speed, acceleration), 0.98);  // and no slower than it has to be
  // v or a given: a trapezoid, as the commander does.
  EXPECT_EQ(plan(home(), goal(), {.speed_percent = 30.0, .shape = Shape::kPolynomial}).shape, Shape::kTrapezoid);
}

TEST(JointMove, NoJointPassesVAndAPercentOfItsLimits) {
  std::mt19937 random(21);
  std::uniform_real_distribution<double> position(-3.0, 3.0);
  std::uniform_real_distribution<double> percent(1.0, 100.0);
  const JointLimits limits = six_joint_limits();
  for (int i = 0; i < 100; ++i) {
    Joints from(6);
    Joints to(6);
    for (std::size_t j = 0; j < 6; ++j) {
      from[j] = position(random);
      to[j] = position(random);
    }
    const MoveTiming timing{.speed_percent = percent(random), .acceleration_percent = percent(random)};
    const Trajectory trajectory = plan(from, to, timing, limits);
    EXPECT_EQ(trajectory.positions.front(), from);
    EXPECT_EQ(trajectory.positions.back(), to);
    bool a_limit_binds = false;
    for (std::size_t j = 0; j < 6; ++j) {
      const double speed = peak_speed(trajectory, j) / (*timing.speed_percent / 100 * limits.max_speed_rad_s[j]);
      const double acceleration =
          peak_acceleration(trajectory, j) / (*timing.acceleration_percent / 100 * limits.max_acceleration_rad_s2[j]);
      EXPECT_LE(speed, 1 + 1e-9) << "move " << i << " J" << j + 1;
      EXPECT_LE(acceleration, 1 + 1e-9) << "move " << i << " J" << j + 1;
      a_limit_binds = a_limit_binds || speed > 0.95 || acceleration > 0.95;
    }
    EXPECT_TRUE(a_limit_binds) << "move " << i << " is slower than it needs to be: " << trajectory.how;
  }
}

TEST(JointMove, VelocitiesIntegrateToThePositions) {
  // What RBTscript's `speed` mode follows: the velocity curve alone must arrive where the
  // positions do (trapezoid rule between samples).
  for (const MoveTiming& timing :
       {MoveTiming{.duration_s = 2.0}, MoveTiming{.duration_s = 3.0, .shape = Shape::kTrapezoid},
        MoveTiming{.speed_percent = 70.0, .acceleration_percent = 30.0}}) {
    const Trajectory trajectory = plan(home(), goal(), timing);
    Joints integrated = home();
    for (std::size_t k = 1; k < trajectory.velocities.size(); ++k) {
      for (std::size_t j = 0; j < 6; ++j) {
        integrated[j] += 0.5 * (trajectory.velocities[k - 1][j] + trajectory.velocities[k][j]) * kDt;
        EXPECT_NEAR(integrated[j], trajectory.positions[k][j], 1e-4)
            << trajectory.how << " J" << j + 1 << " sample " << k;
      }
    }
  }
}

TEST(JointMove, PlansArmsOfAnyJointCount) {
  for (const std::size_t dof : {1U, 5U, 7U}) {
    const JointLimits limits{.min_rad = Joints(dof, -1.0),
                             .max_rad = Joints(dof, 1.0),
                             .max_speed_rad_s = Joints(dof, 1.0),
                             .max_acceleration_rad_s2 = Joints(dof, 1.0)};
    Joints to(dof, 0.5);
    to[dof - 1] = -0.9;
    const Trajectory trajectory = plan(Joints(dof, 0.0), to, {.duration_s = 3.0}, limits);
    ASSERT_EQ(trajectory.positions.size(), 385U);
    EXPECT_EQ(trajectory.positions.back(), to);
    EXPECT_EQ(trajectory.positions[192].size(), dof);
    EXPECT_NEAR(trajectory.positions[192][dof - 1], -0.45, 1e-12);
  }
}

TEST(JointMove, ANullMoveIsOneSampleOrHoldsForT) {
  const Trajectory there = plan(home(), home(), {});
  EXPECT_EQ(there.positions, std::vector<Joints>{home()});
  EXPECT_EQ(there.duration_s, 0.0);
  const Trajectory held = plan(home(), home(), {.duration_s = 0.5});
  EXPECT_EQ(held.positions.size(), 65U);
  for (const Joints& q : held.positions) EXPECT_EQ(q, home());
}

TEST(JointMove, RefusesATTooShortForAJointWithTheTThatWouldDo) {
  const std::string error = refusal(goal(), {.duration_s = 0.5});
  // J1: 1.875 · 1 rad / 1 rad/s.
  EXPECT_NE(error.find("J1 would reach"), std::string::npos) << error;
  EXPECT_NE(error.find("needs t ≥ 1.88 s"), std::string::npos) << error;
  EXPECT_EQ(refusal(goal(), {.duration_s = 1.875}), "(planned)");
}

TEST(JointMove, RefusesAGoalOutsideTheJointLimits) {
  Joints to = goal();
  to[2] = 3.5;
  EXPECT_EQ(refusal(to, {}), "joint move: J3 goal 3.5 rad is outside its limits [-3, 3] rad");
}

TEST(JointMove, RefusesBadArgumentsSayingWhatIsExpected) {
  EXPECT_EQ(refusal(Joints(5, 0.0), {}), "joint move: the goal has 5 values, expected one per joint (6)");
  EXPECT_EQ(refusal(goal(), {.speed_percent = 0.0}), "joint move: v must be a percentage in (0, 100], got 0");
  EXPECT_EQ(refusal(goal(), {.acceleration_percent = 150.0}),
            "joint move: a must be a percentage in (0, 100], got 150");
  EXPECT_EQ(refusal(goal(), {.duration_s = -1.0}), "joint move: t must be a positive duration, got -1 s");
  EXPECT_NE(refusal(goal(), {.duration_s = 1e9}).find("more than a million samples"), std::string::npos);
  EXPECT_NE(refusal(goal(), {.speed_percent = 1e-9}).find("more than a million samples"), std::string::npos);
  EXPECT_EQ(refusal(goal(), {}, six_joint_limits(), 0.0), "joint move: the sample period must be positive, got 0 s");
  Joints bad = goal();
  bad[1] = std::nan("");
  EXPECT_EQ(refusal(bad, {}), "joint move: the goal must be finite");
  JointLimits no_speed = six_joint_limits();
  no_speed.max_speed_rad_s[1] = 0;
  EXPECT_EQ(refusal(goal(), {}, no_speed), "joint move: J2's maximum speed and acceleration must be positive");
  JointLimits short_limits = six_joint_limits();
  short_limits.max_rad.pop_back();
  EXPECT_EQ(refusal(goal(), {}, short_limits),
            "joint move: the joint limit max_rad has 5 values, expected one per joint (6)");
}

}  // namespace
}  // namespace robotd::motion
