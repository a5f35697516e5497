// The PI Plus IMU topics' values derived from an /imu sample: rpy and gyro in degrees.
#include "dds/yesense_imu.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace robotd::dds {
namespace {

// roll about x, then pitch about y, then yaw about z: q = yaw * pitch * roll.
Quaternion from_rpy_deg(double roll, double pitch, double yaw) {
  const double k = std::numbers::pi / 360.0;  // half angle, rad per degree
  const double cr = std::cos(roll * k), sr = std::sin(roll * k);
  const double cp = std::cos(pitch * k), sp = std::sin(pitch * k);
  const double cy = std::cos(yaw * k), sy = std::sin(yaw * k);
  return {sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy,
          cr * cp * cy + sr * sp * sy};
}

TEST(YesenseImu, IdentityIsLevel) {
  const Vector3 rpy = rpy_degrees(Quaternion{});
  EXPECT_DOUBLE_EQ(rpy.x, 0.0);
  EXPECT_DOUBLE_EQ(rpy.y, 0.0);
  EXPECT_DOUBLE_EQ(rpy.z, 0.0);
}

TEST(YesenseImu, QuarterTurnAboutZIsYawNinetyDegrees) {
  const double half = std::sqrt(0.5);
  const Vector3 rpy = rpy_degrees(Quaternion{0, 0, half, half});
  EXPECT_NEAR(rpy.x, 0.0, 1e-9);
  EXPECT_NEAR(rpy.y, 0.0, 1e-9);
  EXPECT_NEAR(rpy.z, 90.0, 1e-9);
}

TEST(YesenseImu, RollPitchYawRoundTripInDegrees) {
  const Vector3 rpy = rpy_degrees(from_rpy_deg(10, -20, 150));
  EXPECT_NEAR(rpy.x, 10.0, 1e-9);
  EXPECT_NEAR(rpy.y, -20.0, 1e-9);
  EXPECT_NEAR(rpy.z, 150.0, 1e-9);
}

TEST(YesenseImu, UnnormalisedQuaternionGivesTheSameAngles) {
  Quaternion q = from_rpy_deg(30, 40, -60);
  q = {q.x * 3, q.y * 3, q.z * 3, q.w * 3};
  const Vector3 rpy = rpy_degrees(q);
  EXPECT_NEAR(rpy.x, 30.0, 1e-9);
  EXPECT_NEAR(rpy.y, 40.0, 1e-9);
  EXPECT_NEAR(rpy.z, -60.0, 1e-9);
}

TEST(YesenseImu, GyroIsInDegreesPerSecondAndAccelerationUnchanged) {
  Imu imu;
  imu.angular_velocity = {std::numbers::pi, -std::numbers::pi / 2, 0.1};
  imu.linear_acceleration = {0.1, -0.2, 9.81};
  const YesenseImu yesense = yesense_imu(imu);
  EXPECT_NEAR(yesense.gyro_deg_s.x, 180.0, 1e-9);
  EXPECT_NEAR(yesense.gyro_deg_s.y, -90.0, 1e-9);
  EXPECT_NEAR(yesense.gyro_deg_s.z, 0.1 * 180.0 / std::numbers::pi, 1e-9);
  EXPECT_DOUBLE_EQ(yesense.acc_m_s2.z, 9.81);
  EXPECT_DOUBLE_EQ(yesense.acc_m_s2.y, -0.2);
}

}  // namespace
}  // namespace robotd::dds
