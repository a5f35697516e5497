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

inline std::string request_topic(std::string_view service) { return "rq/" + std::string(service) + "Request"; }
inline std::string reply_topic(std::string_view service) { return "rr/" + std::string(service) + "Reply"; }

}  // namespace robotd::wire
