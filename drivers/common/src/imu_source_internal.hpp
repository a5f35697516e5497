// What the IMU sources share inside robotd_imu (imu_source.cpp defines them).
#pragma once

#include <string>

#include "robotd/imu/imu_reading.hpp"

namespace robotd::imu {

/// The fields `reading` carries, e.g. "quaternion, gyro, accel, euler, temperature, sample time".
std::string content_of(const ImuReading& reading);

}  // namespace robotd::imu
