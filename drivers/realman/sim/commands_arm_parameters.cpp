// The coordinate frames, the mounting and the joint parameters: what the vendor SDK (RM_API2)
// reads at rm_create_robot_arm and refuses to connect without. Shapes and units are those the
// SDK parses and its setters send (tests/conformance/realman). The simulator has no frames of its
// own: the base work frame, the flange as tool, mounted upright.
#include <cmath>
#include <numbers>

#include "controller.hpp"
#include "planned_path.hpp"

namespace robotd::realman::sim {
namespace {

constexpr double kMilliRpmPerRadS = 1000.0 * 60.0 / (2.0 * std::numbers::pi);
// The planned moves' own limits: full speed, reached in one ramp.
constexpr double kMaxJointAccelerationRadS2 = kMaxJointSpeedRadS / MotionProfile::kRampS;

}  // namespace

nlohmann::json Controller::get_current_work_frame(const CommandRequest& /*request*/) {
  return {{"state", "current_work_frame"}, {"frame_name", "Base"}, {"pose", {0, 0, 0, 0, 0, 0}}};
}

nlohmann::json Controller::get_current_tool_frame(const CommandRequest& /*request*/) {
  // payload 0.001 kg; position: the payload's centre of mass, 0.001 mm.
  return {{"state", "current_tool_frame"},
          {"tool_name", "Arm_Tip"},
          {"pose", {0, 0, 0, 0, 0, 0}},
          {"payload", 0},
          {"position", {0, 0, 0}}};
}

nlohmann::json Controller::get_install_pose(const CommandRequest& /*request*/) {
  return {{"state", "install_pose"}, {"pose", {0, 0, 0}}};  // whole degrees, as the SDK sends them
}

nlohmann::json Controller::get_joint_max_speed(const CommandRequest& /*request*/) {
  const auto speed = std::llround(kMaxJointSpeedRadS * kMilliRpmPerRadS);
  return {{"state", "joint_max_speed"}, {"joint_speed", per_joint([speed](std::size_t) { return speed; })}};
}

nlohmann::json Controller::get_joint_max_acc(const CommandRequest& /*request*/) {
  const auto acceleration = std::llround(kMaxJointAccelerationRadS2 * kMilliRpmPerRadS);
  return {{"state", "joint_max_acc"}, {"joint_acc", per_joint([acceleration](std::size_t) { return acceleration; })}};
}

nlohmann::json Controller::get_DH_data(const CommandRequest& /*request*/) {
  // Each joint as [alpha 0.001°, a 0.001 mm, d 0.001 mm, offset 0.001°]; zeros for a model
  // without a table (ECO65).
  nlohmann::json reply = {{"command", "get_DH_data"}};
  const auto& kinematics = arm_.kinematics();
  for (std::size_t j = 0; j < arm_.dof(); ++j) {
    const DhRow row = kinematics ? kinematics->row(j) : DhRow{};
    reply["joint_" + std::to_string(j + 1)] = {millidegrees_from_rad(row.alpha_rad), micrometres_from_m(row.a_m),
                                               micrometres_from_m(row.d_m), millidegrees_from_rad(row.offset_rad)};
  }
  return reply;
}

}  // namespace robotd::realman::sim
