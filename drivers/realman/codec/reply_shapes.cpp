// How each command's reply is recognised and judged: the tables of §2–§6. A reply names itself
// by the value of "command" (setters, stops, motions) or "state" (most queries).
#include <algorithm>
#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "realman_codec.hpp"

namespace robotd::realman {
namespace {

/// The reply is {"command": <own name>, "receive_state": bool}; current_trajectory_state follows.
constexpr auto kPlannedMotions = std::to_array<std::string_view>(
    {"movej", "movel", "movej_p", "movec", "moves", "set_joint_step", "set_pos_step", "set_ort_step"});

/// Streams the controller does not answer (gen 3+; gen 2's state echo is not awaited).
constexpr auto kUnanswered =
    std::to_array<std::string_view>({"movej_canfd", "movep_canfd", "movej_follow", "movep_follow"});

struct Setter {
  std::string_view command;
  std::string_view result_field;
};
/// The reply is {"command": <own name>, <result_field>: bool}.
constexpr auto kSetters = std::to_array<Setter>({
    {"set_arm_stop", "arm_stop"},
    {"set_arm_slow_stop", "arm_slow_stop"},
    {"set_arm_pause", "arm_pause"},
    {"set_arm_continue", "arm_continue"},
    {"set_delete_current_trajectory", "delete_current_trajectory"},
    {"set_arm_delete_trajectory", "arm_delete_trajectory"},
    // The spec does not pin this 4th-gen reply down; taken to follow set_arm_stop's pattern.
    {"set_arm_emergency_stop", "arm_emergency_stop"},
    {"set_arm_power", "arm_power"},
    {"set_joint_en_state", "joint_en_state"},
    {"set_joint_clear_err", "joint_clear_err"},
    {"clear_system_err", "clear_state"},
    {"set_init_pose", "init_pose"},
    {"set_realtime_push", "state"},
    {"set_gripper_route", "state"},
    {"set_hand_posture", "set_state"},
    {"set_hand_seq", "set_state"},
    {"set_hand_angle", "set_state"},
    {"set_hand_speed", "set_state"},
    {"set_hand_force", "set_state"},
});

/// Doc and ROS1 answer these with the generic "set_gripper"; the specific name is accepted too.
constexpr auto kGripperMoves = std::to_array<std::string_view>(
    {"set_gripper_release", "set_gripper_pick", "set_gripper_pick_on", "set_gripper_position"});

struct Query {
  std::string_view command;
  std::string_view key;
};
/// Any reply with the key is the data asked for.
constexpr auto kQueries = std::to_array<Query>({
    {"get_current_arm_state", "current_arm_state"},
    {"get_joint_degree", "joint_degree"},
    {"get_arm_all_state", "arm_all_state"},
    {"get_controller_state", "controller_state"},
    {"get_current_joint_temperature", "current_joint_temperature"},
    {"get_current_joint_current", "current_joint_current"},
    {"get_current_joint_voltage", "current_joint_voltage"},
    {"get_joint_en_state", "joint_en_state"},
    {"get_joint_err_flag", "joint_err_flag"},
    {"get_arm_plan_num", "arm_plan_num"},
    {"get_arm_power_state", "arm_power_state"},
    {"get_init_pose", "arm_init_pose"},
    {"get_joint_min_pos", "joint_min_pos"},
    {"get_joint_max_pos", "joint_max_pos"},
    {"get_arm_current_trajectory", "arm_current_trajectory"},
    {"get_arm_software_version", "arm_software_version"},
    {"get_arm_software_info", "arm_software_info"},  // as "command", not "state"
    {"get_realtime_push", "get_realtime_push"},      // as "command"
    {"get_gripper_state", "get_gripper_state"},      // as "command"
});

template <class Range>
bool contains(const Range& names, std::string_view command) {
  return std::find(names.begin(), names.end(), command) != names.end();
}

}  // namespace

std::optional<ReplyShape> reply_shape(std::string_view command) {
  const std::string own_name(command);
  if (contains(kPlannedMotions, command)) {
    return ReplyShape{.keys = {own_name}, .result_field = "receive_state", .has_reply = true, .completes_later = true};
  }
  if (contains(kUnanswered, command)) {
    return ReplyShape{.keys = {}, .result_field = "", .has_reply = false, .completes_later = false};
  }
  if (contains(kGripperMoves, command)) {
    return ReplyShape{
        .keys = {"set_gripper", own_name}, .result_field = "state", .has_reply = true, .completes_later = false};
  }
  const auto setter =
      std::find_if(kSetters.begin(), kSetters.end(), [&](const Setter& row) { return row.command == command; });
  if (setter != kSetters.end()) {
    return ReplyShape{.keys = {own_name},
                      .result_field = std::string(setter->result_field),
                      .has_reply = true,
                      .completes_later = false};
  }
  const auto query =
      std::find_if(kQueries.begin(), kQueries.end(), [&](const Query& row) { return row.command == command; });
  if (query != kQueries.end()) {
    return ReplyShape{
        .keys = {std::string(query->key)}, .result_field = "", .has_reply = true, .completes_later = false};
  }
  return std::nullopt;
}

}  // namespace robotd::realman
