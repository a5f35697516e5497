// One IMU sample as a source decodes it, in SI units, with what the device sent marked: the
// orientation, rates and accelerations a driver hands robotd (driver::ImuSample) plus what an
// IMU may add (Euler angles, temperature, the device's own sample time). Trivially copyable, no
// heap: it crosses the RT boundary through a seqlock.
#pragma once

#include <array>
#include <cstdint>

#include "robotd/driver/types.hpp"

namespace robotd::imu {

/// Roll about x, pitch about y, yaw about z, applied yaw first (R = Rz(yaw)·Ry(pitch)·Rx(roll)).
struct EulerRad {
  double roll = 0;
  double pitch = 0;
  double yaw = 0;
};

struct ImuReading {
  std::uint16_t sequence = 0;  // the device's frame counter (Yesense: TID, 1 … 60000)

  bool has_orientation = false;
  bool has_angular_velocity = false;
  bool has_linear_acceleration = false;
  bool has_euler = false;
  bool has_temperature = false;
  bool has_sample_time = false;

  std::array<double, 4> orientation_xyzw{0, 0, 0, 1};  // unit quaternion, sensor frame to reference frame
  std::array<double, 3> angular_velocity_rad_s{};      // sensor axes
  std::array<double, 3> linear_acceleration_m_s2{};    // sensor axes, as the device reports it (gravity included)
  EulerRad euler_rad{};
  double temperature_c = 0;
  std::uint32_t sample_time_us = 0;  // the device's clock; wraps (Yesense: 32 bits of µs, ~71.6 min)
};

/// What a driver puts in Feedback::imu; fields the device did not send stay at their defaults.
inline driver::ImuSample to_sample(const ImuReading& reading) noexcept {
  driver::ImuSample sample;
  sample.orientation_xyzw = reading.orientation_xyzw;
  sample.angular_velocity_rad_s = reading.angular_velocity_rad_s;
  sample.linear_acceleration_m_s2 = reading.linear_acceleration_m_s2;
  return sample;
}

}  // namespace robotd::imu
