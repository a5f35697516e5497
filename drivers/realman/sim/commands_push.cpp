// The UDP real-time push (spec §6): its settings and its datagram.
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "controller.hpp"
#include "error_fields.hpp"

namespace robotd::realman::sim {
namespace {

constexpr double kQuaternionScale = 1e6;
constexpr double kCentidegreesPerRad = 18'000.0 / std::numbers::pi;

}  // namespace

nlohmann::json Controller::set_realtime_push(const CommandRequest& request) {
  push_ = push_.updated(request);
  return {{"command", "set_realtime_push"}, {"state", true}};
}

nlohmann::json Controller::get_realtime_push(const CommandRequest& /*request*/) {
  nlohmann::json reply = {{"command", "get_realtime_push"}};
  reply.update(push_.fields());
  return reply;
}

std::string Controller::push_datagram(std::int64_t now_ns) const {
  nlohmann::json joint_status = {
      {"joint_position", joint_list(arm_.position())},
      {"joint_current", per_joint([this](std::size_t j) { return joint_current(j); })},
      {"joint_voltage", per_joint([this](std::size_t j) { return joint_voltage(j); })},
      {"joint_temperature", per_joint([this](std::size_t j) { return joint_temperature(j); })},
      {"joint_en_flag", per_joint([this](std::size_t j) { return arm_.enabled(j) ? 1 : 0; })},
      {"joint_err_code", per_joint([this](std::size_t j) { return arm_.joint_errors(j); })}};
  if (push_.custom_on("joint_speed")) {
    joint_status["joint_speed"] =
        per_joint([this](std::size_t j) { return std::llround(arm_.velocity()[j] * kCentidegreesPerRad); });
  }
  nlohmann::json waypoint = {{"position", {0, 0, 0}}, {"euler", {0, 0, 0}}, {"quat", {0, 0, 0, 0}}};
  if (const auto pose = arm_.flange_pose()) {
    const Eigen::Quaterniond rotation(isometry_of(*pose).linear());
    const double sign = rotation.w() < 0 ? -1.0 : 1.0;  // w ≥ 0: one of the two equal quaternions
    waypoint = {
        {"position",
         {micrometres_from_m(pose->position_m[0]), micrometres_from_m(pose->position_m[1]),
          micrometres_from_m(pose->position_m[2])}},
        {"euler",
         {milliradians_from_rad(pose->euler_rad[0]), milliradians_from_rad(pose->euler_rad[1]),
          milliradians_from_rad(pose->euler_rad[2])}},
        {"quat",
         {std::llround(sign * rotation.w() * kQuaternionScale), std::llround(sign * rotation.x() * kQuaternionScale),
          std::llround(sign * rotation.y() * kQuaternionScale), std::llround(sign * rotation.z() * kQuaternionScale)}}};
  }
  nlohmann::json datagram = {
      {"state", "realtime_arm_joint_state"}, {"joint_status", joint_status}, {"waypoint", waypoint}};
  add_errors(datagram);
  if (push_.custom_on("arm_current_status")) datagram["arm_current_status"] = status_text(arm_.status(now_ns));
  if (push_.custom_on("hand")) datagram["hand"] = hand_.push_fields();
  return frame(datagram);
}

}  // namespace robotd::realman::sim
