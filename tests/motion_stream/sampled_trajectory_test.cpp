// Checking and resampling a sampled trajectory (no robotd).
#include "robotd/motion/sampled_trajectory.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace robotd::motion {
namespace {

// Two joints: joint 0 goes 0, 1, 2 (1 rad per 10 ms), joint 1 stays at 5; velocities 100 and 0.
SampledTrajectory ramp() { return SampledTrajectory{0.01, {{0, 5}, {1, 5}, {2, 5}}, {{100, 0}, {100, 0}, {100, 0}}}; }

std::string problem(const SampledTrajectory& trajectory, std::size_t joints) {
  auto checked = check_trajectory(trajectory, joints);
  EXPECT_FALSE(checked);
  return checked ? "" : checked.error().message;
}

TEST(SampledTrajectoryTest, AWellFormedTrajectoryPassesTheCheck) {
  EXPECT_TRUE(check_trajectory(ramp(), 2));
  EXPECT_DOUBLE_EQ(ramp().duration_s(), 0.02);
  EXPECT_EQ(ramp().joint_count(), 2U);
}

TEST(SampledTrajectoryTest, MalformedTrajectoriesSayWhatIsWrongAndWhatIsExpected) {
  SampledTrajectory no_step = ramp();
  no_step.dt_s = 0;
  EXPECT_EQ(problem(no_step, 2), "trajectory dt_s is 0: expected a step > 0 s");
  EXPECT_EQ(problem(SampledTrajectory{0.01, {}, {}}, 2), "the trajectory has no samples: expected at least one");
  SampledTrajectory short_velocities = ramp();
  short_velocities.velocities.pop_back();
  EXPECT_EQ(problem(short_velocities, 2),
            "the trajectory has 3 position samples and 2 velocity samples: expected as many of each");
  EXPECT_EQ(problem(ramp(), 3), "positions[0] has 2 values: expected 3, one per joint of the session");
  SampledTrajectory not_finite = ramp();
  not_finite.velocities[1][1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(problem(not_finite, 2), "velocities[1][1] is nan: expected a finite number");
}

TEST(SampledTrajectoryTest, ResamplingInterpolatesLinearlyAtTheNewStep) {
  const SampledTrajectory out = resample(ramp(), 0.004);
  ASSERT_EQ(out.positions.size(), 6U);  // 0, 4, 8, 12, 16, 20 ms
  EXPECT_DOUBLE_EQ(out.dt_s, 0.004);
  for (std::size_t k = 0; k < out.positions.size(); ++k) {
    EXPECT_NEAR(out.positions[k][0], 0.4 * static_cast<double>(k), 1e-12) << k;
    EXPECT_EQ(out.positions[k][1], 5.0) << k;
    EXPECT_EQ(out.velocities[k][0], 100.0) << k;
  }
}

TEST(SampledTrajectoryTest, ResamplingEndsExactlyWhereTheTrajectoryEnds) {
  const SampledTrajectory out = resample(ramp(), 0.003);  // 20 ms is not a multiple of 3 ms
  ASSERT_EQ(out.positions.size(), 8U);                    // 0, 3, ..., 18 ms, then 20 ms
  EXPECT_NEAR(out.positions[6][0], 1.8, 1e-12);
  EXPECT_EQ(out.positions.back(), (std::vector<double>{2, 5}));
}

TEST(SampledTrajectoryTest, ACoarserStepKeepsTheEnds) {
  const SampledTrajectory out = resample(ramp(), 0.5);
  ASSERT_EQ(out.positions.size(), 2U);
  EXPECT_EQ(out.positions.front(), (std::vector<double>{0, 5}));
  EXPECT_EQ(out.positions.back(), (std::vector<double>{2, 5}));
}

TEST(SampledTrajectoryTest, ASingleSampleStaysOneSample) {
  const SampledTrajectory out = resample(SampledTrajectory{0.01, {{1, 2}}, {{0, 0}}}, 0.001);
  ASSERT_EQ(out.positions.size(), 1U);
  EXPECT_EQ(out.positions[0], (std::vector<double>{1, 2}));
}

}  // namespace
}  // namespace robotd::motion
