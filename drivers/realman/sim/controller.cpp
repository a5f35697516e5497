#include "controller.hpp"

#include <algorithm>

#include <spdlog/spdlog.h>

#include "error_fields.hpp"

namespace robotd::realman::sim {
namespace {

constexpr std::size_t kQuotedLineBytes = 60;

std::string quoted_start(std::string_view line) {
  return "\"" + std::string(line.substr(0, kQuotedLineBytes)) + (line.size() > kQuotedLineBytes ? "…\"" : "\"");
}

nlohmann::json error_reply(std::string_view command, const std::string& error) {
  return {{"command", command}, {"error", error}};
}

}  // namespace

Controller::Controller(const SimOptions& options, const ArmModel& model, std::int64_t now_ns)
    : options_(options), arm_(options.model, model, now_ns), advanced_ns_(now_ns) {}

const std::map<std::string, Controller::CommandSpec, std::less<>>& Controller::commands() {
  using C = Controller;
  static const std::map<std::string, CommandSpec, std::less<>> table = {
      // §3 motion
      {"movej", {"movej", "receive_state", &C::movej, true, true}},
      {"movej_p", {"movej_p", "receive_state", &C::movej_p, true, true}},
      {"movel", {"movel", "receive_state", &C::movel, true, true}},
      {"set_joint_step", {"set_joint_step", "receive_state", &C::set_joint_step, true, true}},
      {"set_pos_step", {"set_pos_step", "receive_state", &C::set_pos_step, true, true}},
      {"set_ort_step", {"set_ort_step", "receive_state", &C::set_ort_step, true, true}},
      {"movej_canfd", {"movej_canfd", "", &C::movej_canfd, true, true}},
      {"movec", {"movec", "receive_state", &C::not_emulated, true, true}},
      {"moves", {"moves", "receive_state", &C::not_emulated, true, true}},
      {"movep_canfd", {"movep_canfd", "", &C::not_emulated, true, true}},
      {"movej_follow", {"movej_follow", "", &C::not_emulated, false, true}},
      {"movep_follow", {"movep_follow", "", &C::not_emulated, false, true}},
      {"set_arm_stop", {"set_arm_stop", "arm_stop", &C::set_arm_stop, true, true}},
      {"set_arm_slow_stop", {"set_arm_slow_stop", "arm_slow_stop", &C::set_arm_slow_stop, true, true}},
      {"set_arm_pause", {"set_arm_pause", "arm_pause", &C::set_arm_pause, true, true}},
      {"set_arm_continue", {"set_arm_continue", "arm_continue", &C::set_arm_continue, true, true}},
      {"set_delete_current_trajectory",
       {"set_delete_current_trajectory", "delete_current_trajectory", &C::set_delete_current_trajectory, true, true}},
      {"set_arm_delete_trajectory",
       {"set_arm_delete_trajectory", "arm_delete_trajectory", &C::set_arm_delete_trajectory, true, true}},
      {"set_arm_emergency_stop",
       {"set_arm_emergency_stop", "arm_emergency_stop", &C::set_arm_emergency_stop, true, true}},
      {"get_arm_current_trajectory", {"get_arm_current_trajectory", "", &C::get_arm_current_trajectory, true, true}},
      // §4 state, enable, errors; §8 limits
      {"get_current_arm_state", {"get_current_arm_state", "", &C::get_current_arm_state, true, true}},
      {"get_joint_degree", {"get_joint_degree", "", &C::get_joint_degree, true, true}},
      {"get_arm_all_state", {"get_arm_all_state", "", &C::get_arm_all_state, true, true}},
      {"get_controller_state", {"get_controller_state", "", &C::get_controller_state, true, true}},
      {"get_current_joint_temperature",
       {"get_current_joint_temperature", "", &C::get_current_joint_temperature, true, true}},
      {"get_current_joint_current", {"get_current_joint_current", "", &C::get_current_joint_current, true, true}},
      {"get_current_joint_voltage", {"get_current_joint_voltage", "", &C::get_current_joint_voltage, true, true}},
      {"get_joint_en_state", {"get_joint_en_state", "", &C::get_joint_en_state, true, true}},
      {"get_joint_err_flag", {"get_joint_err_flag", "", &C::get_joint_err_flag, true, true}},
      {"get_arm_plan_num", {"get_arm_plan_num", "", &C::get_arm_plan_num, true, true}},
      {"get_arm_software_info", {"get_arm_software_info", "", &C::get_arm_software_info, false, true}},
      {"get_arm_software_version", {"get_arm_software_version", "", &C::get_arm_software_version, true, false}},
      {"set_arm_power", {"set_arm_power", "arm_power", &C::set_arm_power, true, true}},
      {"get_arm_power_state", {"get_arm_power_state", "", &C::get_arm_power_state, true, true}},
      {"set_joint_en_state", {"set_joint_en_state", "joint_en_state", &C::set_joint_en_state, true, true}},
      {"set_joint_clear_err", {"set_joint_clear_err", "joint_clear_err", &C::set_joint_clear_err, true, true}},
      {"clear_system_err", {"clear_system_err", "clear_state", &C::clear_system_err, true, true}},
      {"set_init_pose", {"set_init_pose", "init_pose", &C::set_init_pose, true, true}},
      {"get_init_pose", {"get_init_pose", "", &C::get_init_pose, true, true}},
      {"get_joint_min_pos", {"get_joint_min_pos", "", &C::get_joint_min_pos, true, true}},
      {"get_joint_max_pos", {"get_joint_max_pos", "", &C::get_joint_max_pos, true, true}},
      // The frames, the mounting and the joint parameters the vendor SDK reads at connect
      {"get_current_work_frame", {"get_current_work_frame", "", &C::get_current_work_frame, true, true}},
      {"get_current_tool_frame", {"get_current_tool_frame", "", &C::get_current_tool_frame, true, true}},
      {"get_install_pose", {"get_install_pose", "", &C::get_install_pose, true, true}},
      {"get_joint_max_speed", {"get_joint_max_speed", "", &C::get_joint_max_speed, true, true}},
      {"get_joint_max_acc", {"get_joint_max_acc", "", &C::get_joint_max_acc, true, true}},
      {"get_DH_data", {"get_DH_data", "", &C::get_DH_data, true, true}},
      // §5 end effectors
      {"set_gripper_route", {"set_gripper_route", "state", &C::set_gripper_route, true, true}},
      {"set_gripper_release", {"set_gripper", "state", &C::set_gripper_release, true, true}},
      {"set_gripper_pick", {"set_gripper", "state", &C::set_gripper_pick, true, true}},
      {"set_gripper_pick_on", {"set_gripper", "state", &C::set_gripper_pick_on, true, true}},
      {"set_gripper_position", {"set_gripper", "state", &C::set_gripper_position, true, true}},
      {"get_gripper_state", {"get_gripper_state", "", &C::get_gripper_state, true, true}},
      {"set_hand_posture", {"set_hand_posture", "set_state", &C::set_hand_posture, true, true}},
      {"set_hand_seq", {"set_hand_seq", "set_state", &C::set_hand_seq, true, true}},
      {"set_hand_angle", {"set_hand_angle", "set_state", &C::set_hand_angle, true, true}},
      {"set_hand_speed", {"set_hand_speed", "set_state", &C::set_hand_speed, true, true}},
      {"set_hand_force", {"set_hand_force", "set_state", &C::set_hand_force, true, true}},
      {"hand_follow_angle", {"hand_follow_angle", "set_state", &C::hand_follow_angle, true, true}},
      {"hand_follow_pos", {"hand_follow_pos", "set_state", &C::hand_follow_pos, true, true}},
      // §6 UDP push (3rd generation on)
      {"set_realtime_push", {"set_realtime_push", "state", &C::set_realtime_push, false, true}},
      {"get_realtime_push", {"get_realtime_push", "", &C::get_realtime_push, false, true}},
  };
  return table;
}

nlohmann::json Controller::handle(std::string_view line, ClientId client, std::int64_t now_ns) {
  ++requests_;
  advance(now_ns);
  nlohmann::json message;
  try {
    message = nlohmann::json::parse(line);
  } catch (const nlohmann::json::exception& error) {  // parse_error, or out_of_range for 1e400
    ++malformed_;
    return error_reply("", std::string("malformed JSON: ") + error.what() + " in " + quoted_start(line));
  }
  if (!message.is_object()) {
    ++malformed_;
    return error_reply("", "malformed JSON: " + quoted_start(line) + " is not a JSON object");
  }
  const auto command = message.find("command");
  if (command == message.end() || !command->is_string()) {
    ++malformed_;
    return error_reply("", "malformed request: " + quoted_start(line) + " has no \"command\" string");
  }
  return dispatch(message, client, now_ns);
}

nlohmann::json Controller::dispatch(const nlohmann::json& message, ClientId client, std::int64_t now_ns) {
  const std::string name = message.at("command").get<std::string>();
  ++command_counts_[name];
  command_last_ns_[name] = now_ns;
  const auto& table = commands();
  const auto found = table.find(name);
  const bool answered =
      found != table.end() && (options_.generation == Generation::k2 ? found->second.gen2 : found->second.gen3);
  if (!answered) {
    ++unknown_;
    return error_reply(name, "unknown command '" + name + "'");
  }
  const CommandSpec& spec = found->second;
  try {
    nlohmann::json reply = (this->*spec.handler)(CommandRequest(message, client, now_ns));
    if (!options_.quiet && name != "movej_canfd") spdlog::debug("{} -> {}", message.dump(), reply.dump());
    return reply;
  } catch (const Refusal& refusal) {
    ++refused_;
    if (!options_.quiet) spdlog::info("refused {}: {}", message.dump(), refusal.what());
    if (spec.result_key.empty()) return error_reply(name, refusal.what());
    return {{"command", spec.reply_command}, {spec.result_key, false}, {"error", refusal.what()}};
  }
}

void Controller::advance(std::int64_t now_ns) {
  const double dt_s = static_cast<double>(now_ns - advanced_ns_) * 1e-9;
  if (dt_s <= 0) return;
  advanced_ns_ = now_ns;
  arm_.advance(now_ns);
  for (const TrajectoryEnd& end : arm_.take_ends()) emit_trajectory_end(end);
  if (gripper_.advance(dt_s) && gripper_waiting_) {
    emit_device_end(*gripper_waiting_, 1, true);
    gripper_waiting_.reset();
  }
  if (hand_.advance(dt_s) && hand_waiting_) {
    emit_device_end(*hand_waiting_, 2, true);
    hand_waiting_.reset();
  }
}

std::vector<Event> Controller::take_events() {
  for (const TrajectoryEnd& end : arm_.take_ends()) emit_trajectory_end(end);  // from commands (stops)
  std::vector<Event> events;
  events.swap(events_);
  return events;
}

void Controller::emit_trajectory_end(const TrajectoryEnd& end) {
  events_.push_back(Event{.client = end.client,
                          .message = {{"state", "current_trajectory_state"},
                                      {"trajectory_state", end.reached},
                                      {"device", 0},
                                      {"trajectory_connect", end.more_segments ? 1 : 0}}});
}

void Controller::emit_device_end(ClientId client, int device, bool reached) {
  events_.push_back(
      Event{.client = client,
            // trajectory_connect as for a last arm segment: the vendor SDK refuses a completion without it.
            .message = {{"state", "current_trajectory_state"},
                        {"trajectory_state", reached},
                        {"device", device},
                        {"trajectory_connect", 0}}});
}

void Controller::add_errors(nlohmann::json& object) const {
  add_error_fields(object, options_.error_shape, arm_.system_errors());
}

nlohmann::json Controller::state(std::int64_t now_ns) const {
  const std::size_t dof = arm_.dof();
  const JointValues target = arm_.target();
  nlohmann::json joints_rad = nlohmann::json::array();
  nlohmann::json targets_rad = nlohmann::json::array();
  nlohmann::json enabled = nlohmann::json::array();
  nlohmann::json joint_errors = nlohmann::json::array();
  for (std::size_t j = 0; j < dof; ++j) {
    joints_rad.push_back(arm_.position()[j]);
    targets_rad.push_back(target[j]);
    enabled.push_back(arm_.enabled(j));
    joint_errors.push_back(arm_.joint_errors(j));
  }
  const TrajectoryQueue& trajectories = arm_.trajectories();
  const Segment* active = trajectories.active();
  const PassThroughCounters& pass = arm_.pass_through_counters();
  nlohmann::json pose = nullptr;
  if (const auto flange = arm_.flange_pose())
    pose = {{"position_m", flange->position_m}, {"euler_rad", flange->euler_rad}};
  return {
      {"ok", true},
      {"model", options_.model},
      {"dof", dof},
      {"generation", static_cast<int>(options_.generation)},
      {"error_shape", error_shape_name(options_.error_shape)},
      {"joints_rad", joints_rad},
      {"targets_rad", targets_rad},
      {"pose", pose},
      {"enabled", enabled},
      {"power", arm_.powered()},
      {"emergency_stop", arm_.emergency_stop()},
      {"errors", arm_.system_errors()},
      {"joint_errors", joint_errors},
      {"status", status_text(arm_.status(now_ns))},
      {"trajectory",
       {{"type", active != nullptr ? nlohmann::json(active->type) : nlohmann::json(nullptr)},
        {"paused", trajectories.paused()},
        {"slowing", trajectories.slowing()},
        {"released", trajectories.released()},
        {"held", trajectories.held()}}},
      {"pass_through",
       {{"frames", pass.frames},
        {"accepted", pass.accepted},
        {"ignored", pass.ignored},
        {"refused", pass.refused},
        {"last_rejection", pass.last_rejection},
        {"follow", pass.follow ? nlohmann::json(*pass.follow) : nlohmann::json(nullptr)},
        {"interval_us", arm_.frame_intervals().summary_us()}}},
      {"push", push_.fields()},
      {"gripper", gripper_.control_state()},
      {"hand", hand_.control_state()},
      {"init_pose_rad", std::vector<double>(init_pose_.begin(), init_pose_.begin() + static_cast<std::ptrdiff_t>(dof))},
      {"commands", command_counts_},
      {"commands_last_ns", command_last_ns_},
      {"requests", requests_},
      {"malformed", malformed_},
      {"unknown", unknown_},
      {"refused", refused_}};
}

}  // namespace robotd::realman::sim
