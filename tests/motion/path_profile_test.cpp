// The two shapes of s(t) against their definitions: the trapezoid in thirds and the quintic.
#include "robotd/motion/path_profile.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace robotd::motion {
namespace {

TEST(PathProfile, ThirdsTrapezoidCoversAQuarterInEachRampAndCruisesInTheMiddleThird) {
  const PathProfile profile = PathProfile::over(Shape::kTrapezoid, 3.0);
  EXPECT_EQ(profile.shape(), Shape::kTrapezoid);
  EXPECT_DOUBLE_EQ(profile.ramp_s(), 1.0);
  EXPECT_NEAR(profile.position(1.0), 0.25, 1e-12);
  EXPECT_NEAR(profile.position(2.0), 0.75, 1e-12);
  for (const double t : {1.0, 1.25, 1.5, 1.75, 2.0}) EXPECT_NEAR(profile.rate(t), 1.5 / 3.0, 1e-12) << t;
  // Constant acceleration 1.5/T over T/3 in the first third, the mirror image in the last.
  EXPECT_NEAR(profile.rate(0.5), 0.25, 1e-12);
  EXPECT_NEAR(profile.rate(2.5), 0.25, 1e-12);
  EXPECT_NEAR(profile.position(0.5), 0.5 * 0.5 * 0.25, 1e-12);
  EXPECT_DOUBLE_EQ(profile.peak_rate(), kThirdsPeakRate / 3.0);
  EXPECT_DOUBLE_EQ(profile.peak_acceleration(), kThirdsPeakAcceleration / 9.0);
}

TEST(PathProfile, QuinticIsHalfWayAtHalfTimeAndAtRestWithNoAccelerationAtBothEnds) {
  const double duration = 2.0;
  const PathProfile profile = PathProfile::polynomial(duration);
  EXPECT_NEAR(profile.position(1.0), 0.5, 1e-15);
  EXPECT_NEAR(profile.position(0.5), 10 * std::pow(0.25, 3) - 15 * std::pow(0.25, 4) + 6 * std::pow(0.25, 5), 1e-15);
  EXPECT_NEAR(profile.rate(1.0), kQuinticPeakRate / duration, 1e-12);
  EXPECT_DOUBLE_EQ(profile.rate(0.0), 0.0);
  EXPECT_DOUBLE_EQ(profile.rate(duration), 0.0);
  // d²s/dt² = 60τ(1 − τ)(1 − 2τ)/T²: a step of h off either end has acceleration O(h).
  const double h = 1e-4;
  EXPECT_NEAR(profile.rate(h) / h, 0.0, 1e-3);
  EXPECT_NEAR(profile.rate(duration - h) / h, 0.0, 1e-3);
  // Its peak acceleration, 10/√3 / T², at τ = (3 − √3)/6.
  const double tau = (3 - std::sqrt(3.0)) / 6;
  const double at = tau * duration;
  EXPECT_NEAR((profile.rate(at + h) - profile.rate(at - h)) / (2 * h), profile.peak_acceleration(), 1e-6);
}

TEST(PathProfile, RateIsTheDerivativeOfPositionAndBothStayPutOutsideTheMove) {
  for (const PathProfile& profile : {PathProfile::polynomial(1.7), PathProfile::trapezoid(1.7, 0.4)}) {
    const double h = 1e-6;
    for (int step = 0; step < 34; ++step) {
      const double t = 0.01 + 0.05 * step;
      EXPECT_NEAR((profile.position(t + h) - profile.position(t - h)) / (2 * h), profile.rate(t), 1e-6) << t;
    }
    EXPECT_EQ(profile.position(-1.0), 0.0);
    EXPECT_EQ(profile.position(1.7), 1.0);
    EXPECT_EQ(profile.position(9.0), 1.0);
    EXPECT_EQ(profile.rate(-1.0), 0.0);
    EXPECT_EQ(profile.rate(9.0), 0.0);
  }
}

}  // namespace
}  // namespace robotd::motion
