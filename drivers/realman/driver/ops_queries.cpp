// Queries, answered in robotd's units (the controller's 0.001 units converted here).
#include "driver/realman_ops.hpp"

namespace robotd::realman {
namespace {

constexpr double kMilli = 1e-3;

/// body[key] as an array of numbers each times `scale`; [] when absent.
nlohmann::json scaled(const nlohmann::json& body, const char* key, double scale) {
  nlohmann::json out = nlohmann::json::array();
  const auto found = body.find(key);
  if (found == body.end() || !found->is_array()) return out;
  for (const auto& value : *found) out.push_back(value.is_number() ? value.get<double>() * scale : 0.0);
  return out;
}

nlohmann::json error_texts(const std::vector<std::uint16_t>& codes) {
  nlohmann::json out = nlohmann::json::array();
  for (const std::uint16_t code : codes) out.push_back(system_error_text(code));
  return out;
}

nlohmann::json joint_errors(const nlohmann::json& bits) {
  nlohmann::json out = nlohmann::json::array();
  if (!bits.is_array()) return out;
  for (const auto& value : bits) {
    const auto code = static_cast<std::uint16_t>(value.is_number_integer() ? value.get<int>() : 0);
    out.push_back({{"bits", code}, {"text", joint_error_text(code)}});
  }
  return out;
}

nlohmann::json flags(const nlohmann::json& values) {
  nlohmann::json out = nlohmann::json::array();
  if (!values.is_array()) return out;
  for (const auto& value : values) out.push_back(value.is_number() && value.get<double>() != 0);
  return out;
}

}  // namespace

Result<nlohmann::json> RealmanOps::get_current_arm_state(const nlohmann::json& args) {
  OpArguments arguments("get_current_arm_state", args);
  if (auto error = arguments.finish()) return *error;
  auto reply = request(plain_request("get_current_arm_state"));
  if (!reply) return reply.error();
  auto state = parse_current_arm_state(Message{MessageKind::kReply, "current_arm_state", reply.value().body});
  if (!state) return state.error();
  const ArmState& arm = state.value();
  nlohmann::json joints = nlohmann::json::array();
  for (std::size_t j = 0; j < arm.dof; ++j) joints.push_back(arm.joints_rad[j]);
  nlohmann::json out{{"joints_rad", joints}, {"errors", error_texts(arm.errors)}};
  if (arm.has_pose) {
    out["pose"] = {{"position_m", arm.pose.position_m}, {"euler_rad", arm.pose.euler_rad}};
  }
  return out;
}

Result<nlohmann::json> RealmanOps::get_joint_err_flag(const nlohmann::json& args) {
  OpArguments arguments("get_joint_err_flag", args);
  if (auto error = arguments.finish()) return *error;
  auto reply = request(plain_request("get_joint_err_flag"));
  if (!reply) return reply.error();
  const nlohmann::json& body = reply.value().body;
  nlohmann::json out{{"joints", joint_errors(body.value("err_flag", nlohmann::json::array()))}};
  // brake_state: 1 = the brake is NOT released.
  nlohmann::json released = nlohmann::json::array();
  for (const bool held : flags(body.value("brake_state", nlohmann::json::array()))) released.push_back(!held);
  out["brake_released"] = released;
  return out;
}

Result<nlohmann::json> RealmanOps::get_joint_en_state(const nlohmann::json& args) {
  OpArguments arguments("get_joint_en_state", args);
  if (auto error = arguments.finish()) return *error;
  auto reply = request(plain_request("get_joint_en_state"));
  if (!reply) return reply.error();
  return nlohmann::json{{"enabled", flags(reply.value().body.value("en_state", nlohmann::json::array()))}};
}

Result<nlohmann::json> RealmanOps::get_arm_all_state(const nlohmann::json& args) {
  OpArguments arguments("get_arm_all_state", args);
  if (auto error = arguments.finish()) return *error;
  auto reply = request(plain_request("get_arm_all_state"));
  if (!reply) return reply.error();
  const nlohmann::json all = reply.value().body.value("all_state", nlohmann::json::object());
  return nlohmann::json{{"temperature_c", scaled(all, "temperature", kMilli)},
                        {"current_a", scaled(all, "current", kMilli * kMilli)},  // 0.001 mA
                        {"voltage_v", scaled(all, "voltage", kMilli)},
                        {"enabled", flags(all.value("en_flag", nlohmann::json::array()))},
                        {"joint_errors", joint_errors(all.value("err_flag", nlohmann::json::array()))},
                        {"errors", error_texts(collect_errors(all))}};
}

Result<nlohmann::json> RealmanOps::get_controller_state(const nlohmann::json& args) {
  OpArguments arguments("get_controller_state", args);
  if (auto error = arguments.finish()) return *error;
  auto reply = request(plain_request("get_controller_state"));
  if (!reply) return reply.error();
  const nlohmann::json& body = reply.value().body;
  const auto number = [&](const char* key) { return body.value(key, 0.0); };
  const auto error = static_cast<std::uint16_t>(body.value("err_flag", 0));
  return nlohmann::json{{"voltage_v", number("voltage") * kMilli},
                        {"current_a", number("current") * kMilli},
                        {"temperature_c", number("temperature") * kMilli},
                        {"error", error == 0 ? std::string() : system_error_text(error)}};
}

Result<nlohmann::json> RealmanOps::verbatim(const std::string& op, const nlohmann::json& args) {
  OpArguments arguments(op, args);
  if (auto error = arguments.finish()) return *error;
  auto reply = request(plain_request(op));
  if (!reply) return reply.error();
  return reply.value().body;
}

Result<nlohmann::json> RealmanOps::state(const nlohmann::json& args) {
  OpArguments arguments("state", args);
  if (auto error = arguments.finish()) return *error;
  const ArmFeedback feedback = driver_.link_.feedback();
  const LinkCounters counters = driver_.link_.counters();
  const std::size_t dof = driver_.params_.model.dof;
  nlohmann::json joints = nlohmann::json::array();
  for (std::size_t j = 0; j < dof; ++j) {
    joints.push_back({{"position_rad", feedback.position_rad[j]},
                      {"velocity_rad_s", feedback.velocity_rad_s[j]},
                      {"enabled", feedback.enabled[j]},
                      {"error", joint_error_text(feedback.joint_errors[j])}});
  }
  nlohmann::json out{{"connected", driver_.connected_.load()},
                     {"link_lost", driver_.link_.health().lost},
                     {"joints", joints},
                     {"fault", feedback.fault.text.data()},
                     {"arm_status", driver_.link_.last_arm_status()},
                     {"session_streaming", driver_.session_streaming_.load()},
                     {"pushes", counters.pushes},
                     {"stream_frames", counters.stream_frames},
                     {"clipped_frames", counters.clipped_frames}};
  if (feedback.has_pose) {
    out["pose"] = {{"position_m", feedback.pose.position_m}, {"orientation_xyzw", feedback.pose.orientation_xyzw}};
  }
  return out;
}

}  // namespace robotd::realman
