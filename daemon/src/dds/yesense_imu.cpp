#include "dds/yesense_imu.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace robotd::dds {
namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

Quaternion normalised(const Quaternion& q) {
  const double norm = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  if (norm < 1e-12 || !std::isfinite(norm)) return Quaternion{};
  return Quaternion{q.x / norm, q.y / norm, q.z / norm, q.w / norm};
}

}  // namespace

Vector3 rpy_degrees(const Quaternion& q) {
  const Quaternion u = normalised(q);
  const double roll = std::atan2(2 * (u.w * u.x + u.y * u.z), 1 - 2 * (u.x * u.x + u.y * u.y));
  const double pitch = std::asin(std::clamp(2 * (u.w * u.y - u.z * u.x), -1.0, 1.0));
  const double yaw = std::atan2(2 * (u.w * u.z + u.x * u.y), 1 - 2 * (u.y * u.y + u.z * u.z));
  return Vector3{roll * kDegPerRad, pitch * kDegPerRad, yaw * kDegPerRad};
}

YesenseImu yesense_imu(const Imu& imu) {
  const Vector3& w = imu.angular_velocity;
  return YesenseImu{.rpy_deg = rpy_degrees(imu.orientation),
                    .acc_m_s2 = imu.linear_acceleration,
                    .gyro_deg_s = Vector3{w.x * kDegPerRad, w.y * kDegPerRad, w.z * kDegPerRad},
                    .quaternion = normalised(imu.orientation)};
}

}  // namespace robotd::dds
