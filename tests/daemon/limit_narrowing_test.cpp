// The run-time rule for a device's limits: narrow only, never widen, never to an empty range.
#include "control/limit_narrowing.hpp"

#include <cmath>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace robotd::control {
namespace {

using ::testing::HasSubstr;

driver::JointLimits joint(double low, double high, double velocity = 1.0) {
  driver::JointLimits limits;
  limits.position_min_rad = low;
  limits.position_max_rad = high;
  limits.velocity_max_rad_s = velocity;
  return limits;
}

std::vector<std::string> joint_names() { return {"j1", "j2"}; }

TEST(LimitNarrowingTest, TighterValuesAreTakenAndListed) {
  std::vector<driver::JointLimits> limits{joint(-2, 2), joint(-1, 1)};
  auto changes = narrow_limits(limits, std::vector{joint(-1.5, 2), joint(-1, 0.5, 0.4)}, joint_names());
  ASSERT_TRUE(changes) << changes.error().message;
  ASSERT_EQ(changes.value().size(), 3U);
  EXPECT_STREQ(changes.value()[0].key, "position_min_rad");
  EXPECT_EQ(changes.value()[0].joint, 0U);
  EXPECT_DOUBLE_EQ(changes.value()[0].from, -2);
  EXPECT_DOUBLE_EQ(changes.value()[0].to, -1.5);
  EXPECT_DOUBLE_EQ(limits[0].position_min_rad, -1.5);
  EXPECT_DOUBLE_EQ(limits[1].position_max_rad, 0.5);
  EXPECT_DOUBLE_EQ(limits[1].velocity_max_rad_s, 0.4);
}

TEST(LimitNarrowingTest, WiderOrNonFiniteValuesNeverWidenALimit) {
  std::vector<driver::JointLimits> limits{joint(-1, 1, 0.5), joint(-1, 1)};
  driver::JointLimits wide = joint(-3, 3, 2.0);
  wide.acceleration_max_rad_s2 = 100;
  driver::JointLimits nan = joint(std::nan(""), std::nan(""), std::nan(""));
  auto changes = narrow_limits(limits, std::vector{wide, nan}, joint_names());
  ASSERT_TRUE(changes) << changes.error().message;
  EXPECT_TRUE(changes.value().empty());
  EXPECT_DOUBLE_EQ(limits[0].position_min_rad, -1);
  EXPECT_DOUBLE_EQ(limits[0].position_max_rad, 1);
  EXPECT_DOUBLE_EQ(limits[0].velocity_max_rad_s, 0.5);
  EXPECT_DOUBLE_EQ(limits[0].acceleration_max_rad_s2, 5.0);
  EXPECT_DOUBLE_EQ(limits[1].position_min_rad, -1);
}

TEST(LimitNarrowingTest, ANarrowingThatLeavesNoPositionRangeIsRefusedAndChangesNothing) {
  std::vector<driver::JointLimits> limits{joint(-2, 2), joint(-1, 1)};
  auto changes = narrow_limits(limits, std::vector{joint(-1, 1), joint(1.5, 3)}, joint_names());
  ASSERT_FALSE(changes);
  EXPECT_THAT(changes.error().message, HasSubstr("joint 'j2'"));
  EXPECT_THAT(changes.error().message, HasSubstr("leaves no position range"));
  EXPECT_DOUBLE_EQ(limits[0].position_min_rad, -2);  // the other joint's narrowing is not taken either
  EXPECT_DOUBLE_EQ(limits[1].position_max_rad, 1);
}

}  // namespace
}  // namespace robotd::control
