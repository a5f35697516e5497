// The RealMan controller without its sockets: takes one JSON message at a time and gives the
// reply (spec §2–§6), moves the arm, the gripper and the hand through time, and produces the
// current_trajectory_state events and the UDP push datagrams. Simulator routes the bytes.
//
// Commands are dispatched by name (controller.cpp holds the table); each handler is in the
// commands_*.cpp file of its family. A handler throws Refusal for bad parameters or a state in
// which the command cannot run; the reply is then the command's normal one with its result field
// false and an "error" saying why.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "arm.hpp"
#include "command_request.hpp"
#include "dexterous_hand.hpp"
#include "gripper.hpp"
#include "push_config.hpp"
#include "sim_options.hpp"

namespace robotd::realman::sim {

/// A message for one client that nobody asked for: a current_trajectory_state event.
struct Event {
  ClientId client = 0;
  nlohmann::json message;
};

class Controller {
 public:
  Controller(const SimOptions& options, const ArmModel& model, std::int64_t now_ns);

  /// One message (a CR LF–delimited line) from `client`, received at `now_ns`: the reply, or
  /// null when the controller stays silent (movej_canfd on gen 3 and 4).
  nlohmann::json handle(std::string_view line, ClientId client, std::int64_t now_ns);
  /// Moves everything to `now_ns`.
  void advance(std::int64_t now_ns);
  /// The events since the last call, oldest first.
  std::vector<Event> take_events();

  /// Whether this generation pushes, and with which settings.
  bool pushing() const { return options_.generation != Generation::k2 && push_.enable; }
  const PushConfig& push_config() const { return push_; }
  /// One realtime_arm_joint_state datagram, with its CR LF (spec §6.2).
  std::string push_datagram(std::int64_t now_ns) const;

  // For the control channel (control_ops.cpp).
  Arm& arm() { return arm_; }
  Gripper& gripper() { return gripper_; }
  nlohmann::json state(std::int64_t now_ns) const;

 private:
  using Handler = nlohmann::json (Controller::*)(const CommandRequest&);
  struct CommandSpec {
    std::string_view reply_command;  // the "command" of a refusal ("set_gripper" for the gripper moves)
    std::string_view result_key;     // its result field; "" for queries and silent commands
    Handler handler;
    bool gen2;  // answered by a 2nd-generation controller
    bool gen3;  // answered by a 3rd- or 4th-generation controller
  };
  static const std::map<std::string, CommandSpec, std::less<>>& commands();
  nlohmann::json dispatch(const nlohmann::json& message, ClientId client, std::int64_t now_ns);

  // commands_motion.cpp
  nlohmann::json movej(const CommandRequest& request);
  nlohmann::json movej_p(const CommandRequest& request);
  nlohmann::json movel(const CommandRequest& request);
  nlohmann::json set_joint_step(const CommandRequest& request);
  nlohmann::json set_pos_step(const CommandRequest& request);
  nlohmann::json set_ort_step(const CommandRequest& request);
  nlohmann::json movej_canfd(const CommandRequest& request);
  nlohmann::json not_emulated(const CommandRequest& request);
  nlohmann::json set_arm_stop(const CommandRequest& request);
  nlohmann::json set_arm_slow_stop(const CommandRequest& request);
  nlohmann::json set_arm_pause(const CommandRequest& request);
  nlohmann::json set_arm_continue(const CommandRequest& request);
  nlohmann::json set_delete_current_trajectory(const CommandRequest& request);
  nlohmann::json set_arm_delete_trajectory(const CommandRequest& request);
  nlohmann::json set_arm_emergency_stop(const CommandRequest& request);
  nlohmann::json get_arm_current_trajectory(const CommandRequest& request);
  nlohmann::json plan(const CommandRequest& request, Segment segment, std::string_view reply_command);
  Segment segment_of(const CommandRequest& request, std::string type) const;
  EulerPose pose_field(const CommandRequest& request) const;
  JointValues joints_field(const CommandRequest& request, const char* key) const;

  // commands_state.cpp
  nlohmann::json get_current_arm_state(const CommandRequest& request);
  nlohmann::json get_joint_degree(const CommandRequest& request);
  nlohmann::json get_arm_all_state(const CommandRequest& request);
  nlohmann::json get_controller_state(const CommandRequest& request);
  nlohmann::json get_current_joint_temperature(const CommandRequest& request);
  nlohmann::json get_current_joint_current(const CommandRequest& request);
  nlohmann::json get_current_joint_voltage(const CommandRequest& request);
  nlohmann::json get_joint_en_state(const CommandRequest& request);
  nlohmann::json get_joint_err_flag(const CommandRequest& request);
  nlohmann::json get_arm_plan_num(const CommandRequest& request);
  nlohmann::json get_arm_software_info(const CommandRequest& request);
  nlohmann::json get_arm_software_version(const CommandRequest& request);
  nlohmann::json set_arm_power(const CommandRequest& request);
  nlohmann::json get_arm_power_state(const CommandRequest& request);
  nlohmann::json set_joint_en_state(const CommandRequest& request);
  nlohmann::json set_joint_clear_err(const CommandRequest& request);
  nlohmann::json clear_system_err(const CommandRequest& request);
  nlohmann::json set_init_pose(const CommandRequest& request);
  nlohmann::json get_init_pose(const CommandRequest& request);
  nlohmann::json get_joint_min_pos(const CommandRequest& request);
  nlohmann::json get_joint_max_pos(const CommandRequest& request);
  nlohmann::json joint_list(const JointValues& values) const;  // millidegrees, DOF entries
  nlohmann::json pose_list() const;                            // the flange, µm and mrad
  /// A joint's synthetic readings in the wire's units (0.001 mA, 0.001 V, 0.001 °C).
  std::int64_t joint_current(std::size_t joint) const;
  std::int64_t joint_voltage(std::size_t joint) const;
  std::int64_t joint_temperature(std::size_t joint) const;
  /// value(j) for every joint j, as a list.
  template <class Value>
  nlohmann::json per_joint(Value value) const {
    nlohmann::json list = nlohmann::json::array();
    for (std::size_t j = 0; j < arm_.dof(); ++j) list.push_back(value(j));
    return list;
  }
  /// A 1-based joint number from a request, as an index; Refusal naming `key` otherwise.
  std::size_t joint_number(const char* key, std::int64_t number) const;

  // commands_arm_parameters.cpp
  nlohmann::json get_current_work_frame(const CommandRequest& request);
  nlohmann::json get_current_tool_frame(const CommandRequest& request);
  nlohmann::json get_install_pose(const CommandRequest& request);
  nlohmann::json get_joint_max_speed(const CommandRequest& request);
  nlohmann::json get_joint_max_acc(const CommandRequest& request);
  nlohmann::json get_DH_data(const CommandRequest& request);

  // commands_effectors.cpp
  nlohmann::json set_gripper_route(const CommandRequest& request);
  nlohmann::json set_gripper_release(const CommandRequest& request);
  nlohmann::json set_gripper_pick(const CommandRequest& request);
  nlohmann::json set_gripper_pick_on(const CommandRequest& request);
  nlohmann::json set_gripper_position(const CommandRequest& request);
  nlohmann::json get_gripper_state(const CommandRequest& request);
  nlohmann::json set_hand_posture(const CommandRequest& request);
  nlohmann::json set_hand_seq(const CommandRequest& request);
  nlohmann::json set_hand_angle(const CommandRequest& request);
  nlohmann::json set_hand_speed(const CommandRequest& request);
  nlohmann::json set_hand_force(const CommandRequest& request);
  nlohmann::json hand_follow_angle(const CommandRequest& request);
  nlohmann::json hand_follow_pos(const CommandRequest& request);
  nlohmann::json gripper_moved(const CommandRequest& request);
  nlohmann::json hand_moved(const CommandRequest& request, const char* command);
  void await_block(std::optional<ClientId>& waiting, const CommandRequest& request, int device);

  // commands_push.cpp
  nlohmann::json set_realtime_push(const CommandRequest& request);
  nlohmann::json get_realtime_push(const CommandRequest& request);

  void add_errors(nlohmann::json& object) const;
  void emit_trajectory_end(const TrajectoryEnd& end);
  void emit_device_end(ClientId client, int device, bool reached);

  SimOptions options_;
  Arm arm_;
  Gripper gripper_;
  DexterousHand hand_;
  PushConfig push_;
  JointValues init_pose_{};
  std::optional<ClientId> gripper_waiting_;  // a block:true gripper move's client
  std::optional<ClientId> hand_waiting_;
  std::vector<Event> events_;
  std::int64_t advanced_ns_;

  std::map<std::string, std::uint64_t, std::less<>> command_counts_;
  std::map<std::string, std::int64_t, std::less<>> command_last_ns_;  // CLOCK_MONOTONIC, when last read
  std::uint64_t requests_ = 0;
  std::uint64_t malformed_ = 0;
  std::uint64_t unknown_ = 0;
  std::uint64_t refused_ = 0;
};

}  // namespace robotd::realman::sim
