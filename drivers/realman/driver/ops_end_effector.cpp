// The EG2-4C2 gripper and the five-finger hand: 0..1000 ranges checked before sending.
#include <algorithm>
#include <cmath>

#include "driver/realman_ops.hpp"

namespace robotd::realman {
namespace {

/// The check's message, prefixed with the op, as an error; nullopt when it passed.
std::optional<Error> failed(std::string_view op, const Result<void>& check) {
  if (check) return std::nullopt;
  return make_error(ErrorCode::kInvalidArgument, std::string(op) + ": " + check.error().message);
}

}  // namespace

Result<nlohmann::json> RealmanOps::gripper(const std::string& op, const nlohmann::json& args) {
  OpArguments arguments(op, args);
  JsonReader& reader = arguments.reader();
  constexpr std::int64_t kAny = 1'000'000;  // the range check below says what is allowed
  if (op == "set_gripper_route") {
    reader.require("min", "the smallest opening, 0..1000");
    reader.require("max", "the largest opening, 0..1000");
    const auto min = reader.integer("min", -kAny, kAny);
    const auto max = reader.integer("max", -kAny, kAny);
    if (auto error = arguments.finish()) return *error;
    const int lo = static_cast<int>(*min);
    const int hi = static_cast<int>(*max);
    if (auto error = failed(op, check_gripper_route(lo, hi))) return *error;
    return send(set_gripper_route_request(lo, hi), std::nullopt, 0);
  }
  if (op == "set_gripper_position") {
    reader.require("position", "the opening, 1..1000");
    const auto position = reader.integer("position", -kAny, kAny);
    const bool block = arguments.block();
    const double timeout_s = arguments.timeout_s();
    if (auto error = arguments.finish()) return *error;
    if (auto error = failed(op, check_gripper_position(static_cast<int>(*position)))) return *error;
    return send(set_gripper_position_request(static_cast<int>(*position), block),
                block ? std::optional(Device::kGripper) : std::nullopt, timeout_s);
  }
  const bool picks = op == "set_gripper_pick" || op == "set_gripper_pick_on";
  if (!picks && op != "set_gripper_release") {
    return make_error(ErrorCode::kInvalidArgument, "unknown op \"" + op + "\"");
  }
  reader.require("speed", "1..1000");
  if (picks) reader.require("force", "the force threshold, 50..1000");
  const auto speed = reader.integer("speed", -kAny, kAny);
  const auto force = picks ? reader.integer("force", -kAny, kAny) : std::optional<std::int64_t>(0);
  const bool block = arguments.block();
  const double timeout_s = arguments.timeout_s();
  if (auto error = arguments.finish()) return *error;
  if (auto error = failed(op, check_gripper_speed(static_cast<int>(*speed)))) return *error;
  if (picks) {
    if (auto error = failed(op, check_gripper_force(static_cast<int>(*force)))) return *error;
  }
  const auto device = block ? std::optional(Device::kGripper) : std::nullopt;
  const int s = static_cast<int>(*speed);
  const int f = static_cast<int>(*force);
  if (op == "set_gripper_release") return send(set_gripper_release_request(s, block), device, timeout_s);
  if (op == "set_gripper_pick") return send(set_gripper_pick_request(s, f, block), device, timeout_s);
  return send(set_gripper_pick_on_request(s, f, block), device, timeout_s);
}

Result<nlohmann::json> RealmanOps::get_gripper_state(const nlohmann::json& args) {
  OpArguments arguments("get_gripper_state", args);
  if (auto error = arguments.finish()) return *error;
  auto reply = request(plain_request("get_gripper_state"));
  if (!reply) return reply.error();
  auto state = parse_gripper_state(Message{MessageKind::kReply, "get_gripper_state", reply.value().body});
  if (!state) return state.error();
  const GripperState& gripper = state.value();
  return nlohmann::json{{"enabled", gripper.enabled},
                        {"online", gripper.online},
                        {"error_bits", gripper.error_bits},
                        {"error", gripper_error_text(gripper.error_bits)},
                        {"mode", gripper.mode},
                        {"mode_text", gripper_mode_text(gripper.mode)},
                        {"force_g", gripper.force_g},
                        {"temperature_c", gripper.temperature_c},
                        {"opening", gripper.opening}};
}

Result<nlohmann::json> RealmanOps::hand(const std::string& op, const nlohmann::json& args) {
  OpArguments arguments(op, args);
  JsonReader& reader = arguments.reader();
  constexpr std::int64_t kAny = 1'000'000;
  if (op == "set_hand_speed" || op == "set_hand_force") {
    const char* key = op == "set_hand_speed" ? "speed" : "force";
    reader.require(key, "1..1000");
    const auto value = reader.integer(key, -kAny, kAny);
    if (auto error = arguments.finish()) return *error;
    const int v = static_cast<int>(*value);
    if (op == "set_hand_speed") {
      if (auto error = failed(op, check_hand_speed(v))) return *error;
      return send(set_hand_speed_request(v), std::nullopt, 0);
    }
    if (auto error = failed(op, check_hand_force(v))) return *error;
    return send(set_hand_force_request(v), std::nullopt, 0);
  }
  const bool block = arguments.block();
  const double timeout_s = arguments.timeout_s();
  const auto device = block ? std::optional(Device::kHand) : std::nullopt;
  if (op == "set_hand_angle") {
    reader.require("angles", "6 angles, each 0..1000 or -1 to keep");
    // Bounded so that the conversion to int below is defined; check_hand_angles says 0..1000.
    const auto angles = reader.number_array("angles", {.min = -kAny, .max = kAny});
    if (angles && angles->size() != 6) {
      reader.error("angles", "expected 6 angles (little, ring, middle, index, thumb bend, thumb rotation), got " +
                                 std::to_string(angles->size()));
    } else if (angles && std::any_of(angles->begin(), angles->end(), [](double a) { return a != std::floor(a); })) {
      reader.error("angles", "expected whole numbers 0..1000 (or -1 to keep)");
    }
    if (auto error = arguments.finish()) return *error;
    std::array<int, 6> values{};
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<int>((*angles)[i]);
    if (auto error = failed(op, check_hand_angles(values))) return *error;
    return send(set_hand_angle_request(values, block), device, timeout_s);
  }
  const bool posture = op == "set_hand_posture";
  if (!posture && op != "set_hand_seq") return make_error(ErrorCode::kInvalidArgument, "unknown op \"" + op + "\"");
  const char* key = posture ? "posture" : "sequence";
  reader.require(key, "1..40");
  const auto number = reader.integer(key, -kAny, kAny);
  if (auto error = arguments.finish()) return *error;
  const int n = static_cast<int>(*number);
  if (auto error = failed(op, check_hand_preset(key, n))) return *error;
  return send(posture ? set_hand_posture_request(n, block) : set_hand_seq_request(n, block), device, timeout_s);
}

}  // namespace robotd::realman
