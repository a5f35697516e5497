// The rate limiter turns any target into a move within the joint's velocity, acceleration and
// position limits: a far target becomes a trapezoid that stops on the target, not past it.
#include "control/joint_limiter.hpp"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "loop_tick.hpp"

namespace robotd::control {
namespace {

constexpr double kEpsilon = 1e-12;  // floating-point slack on the bounds

MotionLimits limits(double velocity_max = 1.0, double acceleration_max = 5.0, double position_min = -10.0,
                    double position_max = 10.0) {
  MotionLimits l;
  l.position_min = position_min;
  l.position_max = position_max;
  l.velocity_max = velocity_max;
  l.acceleration_max = acceleration_max;
  return l;
}

// The setpoint after each of `steps` periods toward a fixed `target`, starting at rest at `start`.
std::vector<LimiterState> move(double start, double target, const MotionLimits& l, int steps, double dt = kDt) {
  std::vector<LimiterState> trajectory{LimiterState{start, 0.0}};
  for (int i = 0; i < steps; ++i) trajectory.push_back(limit_step(trajectory.back(), target, 0.0, l, dt));
  return trajectory;
}

// The first step at which the setpoint sits on `target` at rest, or -1.
int arrival_step(const std::vector<LimiterState>& trajectory, double target) {
  for (std::size_t i = 0; i < trajectory.size(); ++i) {
    if (std::fabs(trajectory[i].position - target) < 1e-9 && std::fabs(trajectory[i].velocity) < 1e-9) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

TEST(JointLimiter, FarTargetNeverMovesFasterThanTheVelocityLimit) {
  const MotionLimits l = limits(1.0, 5.0);
  const auto trajectory = move(0.0, 2.0, l, 3000);
  for (std::size_t i = 1; i < trajectory.size(); ++i) {
    ASSERT_LE(std::fabs(trajectory[i].position - trajectory[i - 1].position), l.velocity_max * kDt + kEpsilon)
        << "step " << i;
    ASSERT_LE(std::fabs(trajectory[i].velocity), l.velocity_max + kEpsilon) << "step " << i;
  }
}

TEST(JointLimiter, FarTargetNeverChangesVelocityFasterThanTheAccelerationLimit) {
  const MotionLimits l = limits(1.0, 5.0);
  const auto trajectory = move(0.0, 2.0, l, 3000);
  for (std::size_t i = 1; i < trajectory.size(); ++i) {
    ASSERT_LE(std::fabs(trajectory[i].velocity - trajectory[i - 1].velocity), l.acceleration_max * kDt + kEpsilon)
        << "step " << i;
  }
}

TEST(JointLimiter, FarTargetIsReachedAndHeldAtRest) {
  const auto trajectory = move(0.0, 2.0, limits(1.0, 5.0), 4000);
  const int arrived = arrival_step(trajectory, 2.0);
  ASSERT_GE(arrived, 0) << "final position " << trajectory.back().position;
  for (std::size_t i = static_cast<std::size_t>(arrived); i < trajectory.size(); ++i) {
    ASSERT_NEAR(trajectory[i].position, 2.0, 1e-9) << "step " << i;
    ASSERT_NEAR(trajectory[i].velocity, 0.0, 1e-9) << "step " << i;
  }
}

TEST(JointLimiter, LongMoveTakesTheTrapezoidsTime) {
  // Cruise-limited: D / vmax + vmax / amax = 2 / 1 + 1 / 5 = 2.2 s.
  const auto trajectory = move(0.0, 2.0, limits(1.0, 5.0), 4000);
  const double arrival_s = arrival_step(trajectory, 2.0) * kDt;
  EXPECT_NEAR(arrival_s, 2.2, 3 * kDt);
}

TEST(JointLimiter, ShortMoveTakesTheTrianglesTime) {
  // Never reaches vmax: 2·√(D / amax) = 2·√(0.05 / 5) = 0.2 s.
  const auto trajectory = move(0.0, -0.05, limits(1.0, 5.0), 1000);
  const double arrival_s = arrival_step(trajectory, -0.05) * kDt;
  EXPECT_NEAR(arrival_s, 0.2, 3 * kDt);
}

TEST(JointLimiter, BrakingIsExactSoTheSetpointStopsOnTheTargetWithoutOvershoot) {
  for (const double velocity_max : {0.3, 1.0, 4.0}) {
    for (const double acceleration_max : {2.0, 5.0, 40.0}) {
      for (const double distance : {-3.1, -0.7, 0.013, 0.25, 1.0, 2.0}) {
        for (const double dt : {0.001, 0.004}) {
          const MotionLimits l = limits(velocity_max, acceleration_max);
          const auto trajectory = move(0.0, distance, l, 20000, dt);
          const double direction = distance > 0 ? 1.0 : -1.0;
          double overshoot = 0;
          for (std::size_t i = 1; i < trajectory.size(); ++i) {
            overshoot = std::fmax(overshoot, (trajectory[i].position - distance) * direction);
            ASSERT_LE(std::fabs(trajectory[i].velocity - trajectory[i - 1].velocity), acceleration_max * dt + kEpsilon);
          }
          EXPECT_LE(overshoot, 1e-12) << "vmax " << velocity_max << " amax " << acceleration_max << " distance "
                                      << distance << " dt " << dt;
          EXPECT_NEAR(trajectory.back().position, distance, 1e-9);
        }
      }
    }
  }
}

TEST(JointLimiter, StoppingSpeedIsTheSpeedWhoseDiscreteBrakeCoversTheDistanceExactly) {
  const MotionLimits l = limits(10.0, 5.0);
  for (const double distance : {1e-6, 0.003, 0.05, 0.4, 2.0}) {
    const double speed = stopping_speed(distance, l, kDt);
    // This period at `speed`, then a·dt less every period until rest.
    double covered = 0;
    double v = speed;
    while (v > 0) {
      covered += v * kDt;
      v -= 5.0 * kDt;
    }
    EXPECT_NEAR(covered, distance, 1e-12) << distance;
  }
  EXPECT_EQ(stopping_speed(0.0, l, kDt), 0.0);
  EXPECT_EQ(stopping_speed(-1.0, l, kDt), 0.0);
}

TEST(JointLimiter, AStreamRunningIntoAPositionLimitBrakesInTimeAndNeverCrossesIt) {
  // The target moves toward the limit at full speed and beyond it: the setpoint must brake to
  // rest on the limit within the acceleration limit, not be clamped there at speed.
  const MotionLimits l = limits(1.0, 5.0, -1.0, 0.5);
  LimiterState state{0.0, 0.0};
  double previous_velocity = 0;
  for (int i = 0; i < 3000; ++i) {
    const double t = i * kDt;
    state = limit_step(state, 0.2 + 1.0 * t, 1.0, l, kDt);
    ASSERT_LE(state.position, l.position_max + kEpsilon) << i;
    ASSERT_LE(std::fabs(state.velocity - previous_velocity), 5.0 * kDt + kEpsilon) << i;
    previous_velocity = state.velocity;
  }
  EXPECT_NEAR(state.position, 0.5, 1e-9);
  EXPECT_NEAR(state.velocity, 0.0, 1e-9);
}

TEST(JointLimiter, ASetpointOutsideTheLimitsComesBackInsideAndNeverMovesFurtherOut) {
  const MotionLimits l = limits(1.0, 5.0, -1.0, 1.0);
  LimiterState state{1.6, 0.0};  // a joint measured 0.6 rad beyond its (narrowed) limit
  double previous_velocity = 0;
  double previous_position = state.position;
  for (int i = 0; i < 3000; ++i) {
    state = limit_step(state, 5.0, 0.0, l, kDt);  // even a target further out
    ASSERT_LE(state.position, previous_position + kEpsilon) << i;
    ASSERT_LE(std::fabs(state.velocity - previous_velocity), 5.0 * kDt + kEpsilon) << i;
    previous_velocity = state.velocity;
    previous_position = state.position;
  }
  EXPECT_NEAR(state.position, 1.0, 1e-9);
}

TEST(JointLimiter, BrakingPointIsWhereAFullBrakeFromTheNextPeriodComesToRest) {
  const MotionLimits l = limits(2.0, 10.0);
  const LimiterState moving{0.3, 0.95};
  const double point = braking_point(moving, l, kDt);
  LimiterState state = moving;
  for (int i = 0; i < 500; ++i) state = limit_step(state, point, 0.0, l, kDt);
  EXPECT_NEAR(state.position, point, 1e-12);
  // and it did brake from the first period: 0.94 rad/s after one step
  EXPECT_NEAR(limit_step(moving, point, 0.0, l, kDt).velocity, 0.94, 1e-12);
}

TEST(JointLimiter, TargetBeyondThePositionLimitSettlesOnTheLimit) {
  const MotionLimits l = limits(1.0, 5.0, -0.5, 1.0);
  const auto trajectory = move(0.0, 5.0, l, 3000);
  for (const auto& state : trajectory) ASSERT_LE(state.position, l.position_max);
  EXPECT_NEAR(trajectory.back().position, 1.0, 1e-9);
  EXPECT_NEAR(trajectory.back().velocity, 0.0, 1e-9);

  const auto below = move(0.0, -5.0, l, 3000);
  for (const auto& state : below) ASSERT_GE(state.position, l.position_min);
  EXPECT_NEAR(below.back().position, -0.5, 1e-9);
}

TEST(JointLimiter, StreamedSineWithVelocityFeedForwardIsTrackedWithinOnePeriodsMotion) {
  // Within the limits: peak speed A·ω = 0.6 rad/s, peak acceleration A·ω² = 1.2 rad/s².
  const MotionLimits l = limits(1.0, 5.0);
  constexpr double kAmplitude = 0.3;
  constexpr double kOmega = 2.0;
  LimiterState state{0.0, kAmplitude * kOmega};
  double worst_lag = 0;
  for (int i = 1; i <= 10000; ++i) {
    const double t = i * kDt;
    const double target = kAmplitude * std::sin(kOmega * t);
    const double target_velocity = kAmplitude * kOmega * std::cos(kOmega * t);
    state = limit_step(state, target, target_velocity, l, kDt);
    worst_lag = std::fmax(worst_lag, std::fabs(state.position - target));
  }
  EXPECT_LE(worst_lag, 1.5 * kAmplitude * kOmega * kDt);
}

TEST(JointLimiter, ReversalMidMoveBrakesWithinTheAccelerationLimitAndReachesTheNewTarget) {
  const MotionLimits l = limits(1.0, 5.0);
  auto trajectory = move(0.0, 2.0, l, 500);  // cruising at vmax toward 2
  ASSERT_NEAR(trajectory.back().velocity, 1.0, 1e-9);
  for (int i = 0; i < 3000; ++i) trajectory.push_back(limit_step(trajectory.back(), -1.0, 0.0, l, kDt));
  for (std::size_t i = 1; i < trajectory.size(); ++i) {
    ASSERT_LE(std::fabs(trajectory[i].velocity - trajectory[i - 1].velocity), l.acceleration_max * kDt + kEpsilon)
        << "step " << i;
  }
  EXPECT_NEAR(trajectory.back().position, -1.0, 1e-9);
  EXPECT_NEAR(trajectory.back().velocity, 0.0, 1e-9);
}

TEST(JointLimiter, ClampBoundsAValueToTheInterval) {
  EXPECT_EQ(clamp(3.0, -1.0, 2.0), 2.0);
  EXPECT_EQ(clamp(-3.0, -1.0, 2.0), -1.0);
  EXPECT_EQ(clamp(0.5, -1.0, 2.0), 0.5);
}

}  // namespace
}  // namespace robotd::control
