// End-effector commands (spec §5): the two-finger gripper and the five-finger hand.
#include "controller.hpp"

namespace robotd::realman::sim {
namespace {

constexpr int kGripperDevice = 1;
constexpr int kHandDevice = 2;

}  // namespace

void Controller::await_block(std::optional<ClientId>& waiting, const CommandRequest& request, int device) {
  // A move that replaces one still awaited ends that one: its client hears it did not arrive.
  if (waiting) emit_device_end(*waiting, device, false);
  waiting.reset();
  if (request.optional_boolean("block").value_or(false)) waiting = request.client();
}

nlohmann::json Controller::gripper_moved(const CommandRequest& request) {
  await_block(gripper_waiting_, request, kGripperDevice);
  return {{"command", "set_gripper"}, {"state", true}};
}

nlohmann::json Controller::set_gripper_route(const CommandRequest& request) {
  const auto min = request.integer("min", 0, 1000);
  const auto max = request.integer("max", 0, 1000);
  if (min > max) throw Refusal("\"min\" " + std::to_string(min) + " is above \"max\" " + std::to_string(max));
  gripper_.set_route(static_cast<int>(min), static_cast<int>(max));
  return {{"command", "set_gripper_route"}, {"state", true}};
}

nlohmann::json Controller::set_gripper_release(const CommandRequest& request) {
  const auto speed = request.integer("speed", 1, 1000);
  request.optional_boolean("block");
  gripper_.release(static_cast<int>(speed));
  return gripper_moved(request);
}

nlohmann::json Controller::set_gripper_pick(const CommandRequest& request) {
  const auto speed = request.integer("speed", 1, 1000);
  const auto force = request.integer("force", 50, 1000);
  request.optional_boolean("block");
  gripper_.pick(static_cast<int>(speed), static_cast<int>(force), false);
  return gripper_moved(request);
}

nlohmann::json Controller::set_gripper_pick_on(const CommandRequest& request) {
  const auto speed = request.integer("speed", 1, 1000);
  const auto force = request.integer("force", 50, 1000);
  request.optional_boolean("block");
  gripper_.pick(static_cast<int>(speed), static_cast<int>(force), true);
  return gripper_moved(request);
}

nlohmann::json Controller::set_gripper_position(const CommandRequest& request) {
  const auto position = request.integer("position", 1, 1000);
  request.optional_boolean("block");
  gripper_.move_to(static_cast<int>(position));
  return gripper_moved(request);
}

nlohmann::json Controller::get_gripper_state(const CommandRequest& /*request*/) {
  nlohmann::json reply = {{"command", "get_gripper_state"}};
  reply.update(gripper_.state_fields());
  return reply;
}

nlohmann::json Controller::hand_moved(const CommandRequest& request, const char* command) {
  await_block(hand_waiting_, request, kHandDevice);
  return {{"command", command}, {"set_state", true}};
}

nlohmann::json Controller::set_hand_posture(const CommandRequest& request) {
  const auto posture = request.integer("posture_num", 1, DexterousHand::kPresets);
  request.optional_boolean("block");
  hand_.set_posture(static_cast<int>(posture));
  return hand_moved(request, "set_hand_posture");
}

nlohmann::json Controller::set_hand_seq(const CommandRequest& request) {
  const auto sequence = request.integer("seq_num", 1, DexterousHand::kPresets);
  request.optional_boolean("block");
  hand_.run_sequence(static_cast<int>(sequence));
  return hand_moved(request, "set_hand_seq");
}

nlohmann::json Controller::set_hand_angle(const CommandRequest& request) {
  const auto values = request.integers("hand_angle", DexterousHand::kDof, -1, 1000, "0 … 1000, −1 keeps");
  request.optional_boolean("block");
  DexterousHand::Angles angles{};
  for (std::size_t i = 0; i < angles.size(); ++i) angles[i] = static_cast<int>(values[i]);
  hand_.set_angles(angles);
  return hand_moved(request, "set_hand_angle");
}

nlohmann::json Controller::hand_follow_angle(const CommandRequest& request) {
  const auto values = request.integers("hand_angle", DexterousHand::kDof, 0, 1000, "0 … 1000");
  DexterousHand::Angles angles{};
  for (std::size_t i = 0; i < angles.size(); ++i) angles[i] = static_cast<int>(values[i]);
  hand_.set_angles(angles);
  return hand_moved(request, "hand_follow_angle");
}

nlohmann::json Controller::hand_follow_pos(const CommandRequest& request) {
  const auto values = request.integers("hand_pos", DexterousHand::kDof, 0, 1000, "0 … 1000");
  DexterousHand::Angles angles{};
  for (std::size_t i = 0; i < angles.size(); ++i) angles[i] = static_cast<int>(values[i]);
  hand_.set_angles(angles);  // the simulated hand's positions are its angles
  return hand_moved(request, "hand_follow_pos");
}

nlohmann::json Controller::set_hand_speed(const CommandRequest& request) {
  hand_.set_speed(static_cast<int>(request.integer("hand_speed", 1, 1000)));
  return {{"command", "set_hand_speed"}, {"set_state", true}};
}

nlohmann::json Controller::set_hand_force(const CommandRequest& request) {
  hand_.set_force(static_cast<int>(request.integer("hand_force", 1, 1000)));
  return {{"command", "set_hand_force"}, {"set_state", true}};
}

}  // namespace robotd::realman::sim
