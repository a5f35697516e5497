// The requests robotd sends (§3 motion, §4 state and enable, §5 end effectors, §6.1 UDP push),
// with the field names and types of the protocol doc.
#include <array>
#include <span>
#include <string_view>
#include <utility>

#include "realman_codec.hpp"

namespace robotd::realman {
namespace {

nlohmann::json millidegrees(std::span<const double> joints_rad) {
  nlohmann::json out = nlohmann::json::array();
  for (const double joint : joints_rad) out.push_back(millidegrees_from_rad(joint));
  return out;
}

/// [x, y, z] in µm and [rx, ry, rz] in 0.001 rad.
nlohmann::json wire_pose(const EulerPose& pose) {
  nlohmann::json out = nlohmann::json::array();
  for (const double axis : pose.position_m) out.push_back(micrometres_from_m(axis));
  for (const double angle : pose.euler_rad) out.push_back(milliradians_from_rad(angle));
  return out;
}

nlohmann::json new_request(std::string_view command) {
  nlohmann::json message = nlohmann::json::object();
  message["command"] = command;
  return message;
}

nlohmann::json planned_move(std::string_view name, std::string_view target_field, nlohmann::json target,
                            const PlannedMove& move) {
  nlohmann::json message = new_request(name);
  message[target_field] = std::move(target);
  message["v"] = move.speed_percent;
  message["r"] = move.blend_percent;
  message["trajectory_connect"] = move.trajectory_connect ? 1 : 0;
  return message;
}

}  // namespace

nlohmann::json movej_request(std::span<const double> joints_rad, const PlannedMove& move) {
  return planned_move("movej", "joint", millidegrees(joints_rad), move);
}

nlohmann::json movel_request(const EulerPose& pose, const PlannedMove& move) {
  return planned_move("movel", "pose", wire_pose(pose), move);
}

nlohmann::json movej_p_request(const EulerPose& pose, const PlannedMove& move) {
  return planned_move("movej_p", "pose", wire_pose(pose), move);
}

nlohmann::json movej_canfd_request(std::span<const double> joints_rad, const PassThrough& pass_through) {
  nlohmann::json message = new_request("movej_canfd");
  message["joint"] = millidegrees(joints_rad);
  message["follow"] = pass_through.follow;
  // Older firmware does not know these fields: send them only when asked for.
  if (pass_through.trajectory_mode) message["trajectory_mode"] = *pass_through.trajectory_mode;
  if (pass_through.radio) message["radio"] = *pass_through.radio;
  return message;
}

nlohmann::json plain_request(std::string_view command) { return new_request(command); }

nlohmann::json set_joint_en_state_request(int joint_number, bool enable) {
  nlohmann::json message = new_request("set_joint_en_state");
  message["joint_en_state"] = {joint_number, enable ? 1 : 0};
  return message;
}

nlohmann::json set_joint_clear_err_request(int joint_number) {
  nlohmann::json message = new_request("set_joint_clear_err");
  message["joint_clear_err"] = joint_number;
  return message;
}

nlohmann::json set_arm_power_request(bool on) {
  nlohmann::json message = new_request("set_arm_power");
  message["arm_power"] = on ? 1 : 0;
  return message;
}

nlohmann::json set_realtime_push_request(const RealtimePushConfig& config) {
  nlohmann::json message = new_request("set_realtime_push");
  message["cycle"] = config.cycle;
  message["enable"] = config.enable;
  message["port"] = config.port;
  message["ip"] = config.ip;
  message["custom"] = {
      {"joint_speed", config.joint_speed}, {"arm_current_status", config.arm_current_status}, {"hand", config.hand}};
  return message;
}

nlohmann::json set_gripper_route_request(int min, int max) {
  nlohmann::json message = new_request("set_gripper_route");
  message["min"] = min;
  message["max"] = max;
  return message;
}

nlohmann::json set_gripper_release_request(int speed, bool block) {
  nlohmann::json message = new_request("set_gripper_release");
  message["speed"] = speed;
  message["block"] = block;
  return message;
}

nlohmann::json set_gripper_pick_request(int speed, int force, bool block) {
  nlohmann::json message = new_request("set_gripper_pick");
  message["speed"] = speed;
  message["force"] = force;
  message["block"] = block;
  return message;
}

nlohmann::json set_gripper_pick_on_request(int speed, int force, bool block) {
  nlohmann::json message = new_request("set_gripper_pick_on");
  message["speed"] = speed;
  message["force"] = force;
  message["block"] = block;
  return message;
}

nlohmann::json set_gripper_position_request(int position, bool block) {
  nlohmann::json message = new_request("set_gripper_position");
  message["position"] = position;
  message["block"] = block;
  return message;
}

nlohmann::json set_hand_posture_request(int posture_number, bool block) {
  nlohmann::json message = new_request("set_hand_posture");
  message["posture_num"] = posture_number;
  message["block"] = block;
  return message;
}

nlohmann::json set_hand_seq_request(int sequence_number, bool block) {
  nlohmann::json message = new_request("set_hand_seq");
  message["seq_num"] = sequence_number;
  message["block"] = block;
  return message;
}

nlohmann::json set_hand_angle_request(const std::array<int, 6>& angles, bool block) {
  nlohmann::json message = new_request("set_hand_angle");
  message["hand_angle"] = angles;
  message["block"] = block;
  return message;
}

nlohmann::json set_hand_speed_request(int speed) {
  nlohmann::json message = new_request("set_hand_speed");
  message["hand_speed"] = speed;
  return message;
}

nlohmann::json set_hand_force_request(int force) {
  nlohmann::json message = new_request("set_hand_force");
  message["hand_force"] = force;
  return message;
}

}  // namespace robotd::realman
