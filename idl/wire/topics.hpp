// DDS names of robotd's topics and services, mangled the rmw_cyclonedds way: "rt/" + ROS topic
// name, "rq/" + service + "Request", "rr/" + service + "Reply".
#pragma once

#include <string>
#include <string_view>

namespace robotd::wire {

inline constexpr std::string_view kControlCommandTopic = "rt/control_command";
inline constexpr std::string_view kSessionStatusTopic = "rt/session_status";
inline constexpr std::string_view kJointStatesTopic = "rt/joint_states";
inline constexpr std::string_view kDeviceStatusTopic = "rt/device_status";
inline constexpr std::string_view kImuTopic = "rt/imu";
inline constexpr std::string_view kEndPoseTopic = "rt/end_pose";
inline constexpr std::string_view kPolicyDataTopic = "rt/policy_data";
/// The joystick source's default ROS topic name (config "joystick.topic"); DDS name "rt/joy".
inline constexpr std::string_view kDefaultJoyTopicName = "joy";

// The PI Plus IMU node's topics (yesense_imu_ros2), published for every device with an IMU.
inline constexpr std::string_view kYesenseRpyTopic = "rt/yesense_imu/rpy";    // Vector3, degrees
inline constexpr std::string_view kYesenseAccTopic = "rt/yesense_imu/acc";    // Vector3, m/s²
inline constexpr std::string_view kYesenseGyroTopic = "rt/yesense_imu/gyro";  // Vector3, deg/s
inline constexpr std::string_view kYesenseQuatTopic = "rt/yesense_imu/quat";  // Quaternion
inline constexpr std::string_view kYesenseImuTopic = "rt/yesense_imu/imu";    // Imu, as /imu

/// "rt/" + a ROS topic name given with or without its leading '/'.
inline std::string data_topic(std::string_view ros_name) {
  if (ros_name.starts_with('/')) ros_name.remove_prefix(1);
  return "rt/" + std::string(ros_name);
}
/// A device's TickState topic: ROS name "/<device>/tick_state".
inline std::string tick_state_topic(std::string_view device) { return "rt/" + std::string(device) + "/tick_state"; }
inline std::string request_topic(std::string_view service) { return "rq/" + std::string(service) + "Request"; }
inline std::string reply_topic(std::string_view service) { return "rr/" + std::string(service) + "Reply"; }

}  // namespace robotd::wire
