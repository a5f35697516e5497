// The PI Plus IMU node's view of an IMU sample (yesense_imu_ros2): roll, pitch and yaw in
// degrees, acceleration in m/s², angular velocity in deg/s, the orientation quaternion and the
// sensor_msgs/Imu itself. robotd derives them from the /imu sample it publishes, so a PI Plus
// client reading /yesense_imu/* sees the same IMU as a client reading /imu.
#pragma once

#include "robotd/messages.hpp"

namespace robotd::dds {

struct YesenseImu {
  Vector3 rpy_deg;        // roll (about x), pitch (about y), yaw (about z), ZYX (yaw-pitch-roll) order
  Vector3 acc_m_s2;       // linear acceleration
  Vector3 gyro_deg_s;     // angular velocity
  Quaternion quaternion;  // orientation, normalised
};

/// Roll, pitch, yaw in degrees of `q` (need not be normalised): roll and yaw in [-180, 180],
/// pitch in [-90, 90], as tf2's getRPY and the Yesense's own Euler output.
Vector3 rpy_degrees(const Quaternion& q);
YesenseImu yesense_imu(const Imu& imu);

}  // namespace robotd::dds
