// Motion commands (spec §3): planned moves, pass-through, stops.
#include <limits>

#include "controller.hpp"
#include "error_fields.hpp"

namespace robotd::realman::sim {
namespace {

constexpr std::int64_t kAnyInt32 = std::numeric_limits<std::int32_t>::max();
constexpr std::int64_t kPoseRange = 100'000'000;  // µm and mrad: the IK judges what is reachable
constexpr std::int64_t kMaxRadio = 1000;

}  // namespace

JointValues Controller::joints_field(const CommandRequest& request, const char* key) const {
  const auto millidegrees = request.integers(key, arm_.dof(), -kAnyInt32, kAnyInt32, "0.001°");
  JointValues joints{};
  for (std::size_t j = 0; j < millidegrees.size(); ++j) joints[j] = rad_from_millidegrees(millidegrees[j]);
  return joints;
}

EulerPose Controller::pose_field(const CommandRequest& request) const {
  const auto values =
      request.integers("pose", 6, -kPoseRange, kPoseRange, "x, y, z in 0.001 mm; rx, ry, rz in 0.001 rad");
  EulerPose pose;
  for (std::size_t i = 0; i < 3; ++i) {
    pose.position_m[i] = m_from_micrometres(values[i]);
    pose.euler_rad[i] = rad_from_milliradians(values[i + 3]);
  }
  return pose;
}

Segment Controller::segment_of(const CommandRequest& request, std::string type) const {
  Segment segment;
  segment.type = std::move(type);
  segment.speed_percent = static_cast<int>(request.integer("v", 1, 100));
  segment.client = request.client();
  return segment;
}

nlohmann::json Controller::plan(const CommandRequest& request, Segment segment, std::string_view reply_command) {
  request.optional_integer("r", 0, 100);  // blending is not emulated; the value is still checked
  const bool connect = request.optional_integer("trajectory_connect", 0, 1).value_or(0) == 1;
  if (auto planned = arm_.plan(std::move(segment), connect); !planned) throw Refusal(planned.error().message);
  return {{"command", reply_command}, {"receive_state", true}};
}

nlohmann::json Controller::movej(const CommandRequest& request) {
  Segment segment = segment_of(request, "movej");
  segment.joints = joints_field(request, "joint");
  return plan(request, std::move(segment), "movej");
}

nlohmann::json Controller::movej_p(const CommandRequest& request) {
  // A joint-space move, reported as "movej" by get_arm_current_trajectory: the vendor SDK's
  // blocking movej_p polls it and gives up on a type it does not know.
  Segment segment = segment_of(request, "movej");
  segment.pose = pose_field(request);
  auto joints = arm_.solve(*segment.pose);
  if (!joints) throw Refusal(joints.error().message);
  segment.joints = joints.value();
  return plan(request, std::move(segment), "movej_p");
}

nlohmann::json Controller::movel(const CommandRequest& request) {
  Segment segment = segment_of(request, "movel");
  segment.pose = pose_field(request);
  return plan(request, std::move(segment), "movel");
}

nlohmann::json Controller::set_joint_step(const CommandRequest& request) {
  const auto step = request.integers("joint_step", 2, -kAnyInt32, kAnyInt32, "joint number, step in 0.001°");
  const std::size_t joint = joint_number("joint_step", step[0]);
  Segment segment = segment_of(request, "movej");
  segment.joints = arm_.next_start();
  segment.joints[joint] += rad_from_millidegrees(step[1]);
  return plan(request, std::move(segment), "set_joint_step");
}

nlohmann::json Controller::set_pos_step(const CommandRequest& request) {
  const std::string axis = request.string("step_type");
  const int index = axis == "x_step" ? 0 : axis == "y_step" ? 1 : axis == "z_step" ? 2 : -1;
  if (index < 0) throw Refusal("\"step_type\" must be \"x_step\", \"y_step\" or \"z_step\", got \"" + axis + "\"");
  const std::int64_t step = request.integer("step", -kPoseRange, kPoseRange);
  auto flange = arm_.next_start_flange();
  if (!flange) throw Refusal(flange.error().message);
  Eigen::Isometry3d goal = flange.value();
  goal.translation()[index] += m_from_micrometres(step);
  Segment segment = segment_of(request, "movel");
  segment.pose = euler_pose_of(goal);
  return plan(request, std::move(segment), "set_pos_step");
}

nlohmann::json Controller::set_ort_step(const CommandRequest& request) {
  const std::string axis = request.string("step_type");
  const int index = axis == "rx_step" ? 0 : axis == "ry_step" ? 1 : axis == "rz_step" ? 2 : -1;
  if (index < 0) throw Refusal("\"step_type\" must be \"rx_step\", \"ry_step\" or \"rz_step\", got \"" + axis + "\"");
  const std::int64_t step = request.integer("step", -kPoseRange, kPoseRange);
  auto flange = arm_.next_start_flange();
  if (!flange) throw Refusal(flange.error().message);
  Eigen::Isometry3d goal = flange.value();
  // about the work (base) frame's axis, through the flange
  goal.linear() =
      Eigen::AngleAxisd(rad_from_milliradians(step), Eigen::Vector3d::Unit(index)).toRotationMatrix() * goal.linear();
  Segment segment = segment_of(request, "movel");
  segment.pose = euler_pose_of(goal);
  return plan(request, std::move(segment), "set_ort_step");
}

nlohmann::json Controller::movej_canfd(const CommandRequest& request) {
  try {
    PassThroughFrame frame;
    frame.joints = joints_field(request, "joint");
    frame.follow = request.optional_boolean("follow").value_or(false);
    request.optional_integer("expand", -kAnyInt32, kAnyInt32);  // no extension joint is simulated
    request.optional_integer("trajectory_mode", 0, 2);
    request.optional_integer("radio", 0, kMaxRadio);
    arm_.pass_through(frame, request.now_ns());
  } catch (const Refusal& refusal) {
    arm_.malformed_frame(refusal.what(), request.now_ns());  // silent: the stream has no replies
  }
  if (options_.generation != Generation::k2) return nullptr;
  return {
      {"state", "joint_state"}, {"joint", joint_list(arm_.position())}, {"arm_err", first_error(arm_.system_errors())}};
}

nlohmann::json Controller::not_emulated(const CommandRequest& request) {
  throw Refusal(request.body().at("command").get<std::string>() + " is not emulated by robotd-realman-sim");
}

nlohmann::json Controller::set_arm_stop(const CommandRequest& /*request*/) {
  arm_.stop();
  return {{"command", "set_arm_stop"}, {"arm_stop", true}};
}

nlohmann::json Controller::set_arm_slow_stop(const CommandRequest& /*request*/) {
  arm_.slow_stop();
  return {{"command", "set_arm_slow_stop"}, {"arm_slow_stop", true}};
}

nlohmann::json Controller::set_arm_pause(const CommandRequest& /*request*/) {
  arm_.pause();
  return {{"command", "set_arm_pause"}, {"arm_pause", true}};
}

nlohmann::json Controller::set_arm_continue(const CommandRequest& /*request*/) {
  arm_.resume();
  return {{"command", "set_arm_continue"}, {"arm_continue", true}};
}

nlohmann::json Controller::set_delete_current_trajectory(const CommandRequest& /*request*/) {
  if (auto deleted = arm_.delete_current(); !deleted) throw Refusal(deleted.error().message);
  return {{"command", "set_delete_current_trajectory"}, {"delete_current_trajectory", true}};
}

nlohmann::json Controller::set_arm_delete_trajectory(const CommandRequest& /*request*/) {
  if (auto deleted = arm_.delete_all(); !deleted) throw Refusal(deleted.error().message);
  return {{"command", "set_arm_delete_trajectory"}, {"arm_delete_trajectory", true}};
}

nlohmann::json Controller::set_arm_emergency_stop(const CommandRequest& request) {
  arm_.set_emergency_stop(request.optional_boolean("arm_emergency_stop").value_or(true));
  return {{"command", "set_arm_emergency_stop"}, {"arm_emergency_stop", true}};
}

nlohmann::json Controller::get_arm_current_trajectory(const CommandRequest& /*request*/) {
  const Segment* active = arm_.trajectories().active();
  nlohmann::json data;
  if (active != nullptr && active->type == "movel") {
    const EulerPose& pose = *active->pose;
    data = {micrometres_from_m(pose.position_m[0]),   micrometres_from_m(pose.position_m[1]),
            micrometres_from_m(pose.position_m[2]),   milliradians_from_rad(pose.euler_rad[0]),
            milliradians_from_rad(pose.euler_rad[1]), milliradians_from_rad(pose.euler_rad[2])};
  } else {
    data = joint_list(arm_.target());
  }
  return {{"state", "arm_current_trajectory"}, {"type", active != nullptr ? active->type : "none"}, {"data", data}};
}

}  // namespace robotd::realman::sim
