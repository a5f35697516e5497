// Range checks of the arguments the protocol doc bounds (§3.1, §5.1, §5.2), so a bad value is
// refused with a clear message instead of being sent.
#include <array>
#include <cstddef>
#include <string>
#include <string_view>

#include "realman_codec.hpp"

namespace robotd::realman {
namespace {

constexpr int kGripperMin = 1;
constexpr int kGripperMax = 1000;
constexpr int kHandPresets = 40;
constexpr int kHandAngleKeep = -1;

/// "speed 0 is out of range: the gripper's speed is 1..1000 (dimensionless)".
Result<void> check_range(std::string_view argument, int value, int min, int max, std::string_view subject,
                         std::string_view unit) {
  if (value >= min && value <= max) return {};
  return make_error(ErrorCode::kInvalidArgument,
                    std::string(argument) + " " + std::to_string(value) + " is out of range: " + std::string(subject) +
                        " is " + std::to_string(min) + ".." + std::to_string(max) + " (" + std::string(unit) + ")");
}

}  // namespace

Result<void> check_speed_percent(int v) {
  return check_range("v", v, 1, 100, "a planned move's speed", "percent of the arm's maximum");
}

Result<void> check_blend_percent(int r) {
  return check_range("r", r, 0, 100, "a planned move's blend radius", "percent");
}

Result<void> check_gripper_route(int min, int max) {
  constexpr std::string_view kSubject = "the gripper's opening limit";
  if (auto checked = check_range("min", min, 0, kGripperMax, kSubject, "dimensionless"); !checked) return checked;
  if (auto checked = check_range("max", max, 0, kGripperMax, kSubject, "dimensionless"); !checked) return checked;
  if (min <= max) return {};
  return make_error(ErrorCode::kInvalidArgument, "min " + std::to_string(min) + " is above max " + std::to_string(max) +
                                                     ": the gripper's route needs min <= max");
}

Result<void> check_gripper_speed(int speed) {
  return check_range("speed", speed, kGripperMin, kGripperMax, "the gripper's speed", "dimensionless");
}

Result<void> check_gripper_force(int force) {
  return check_range("force", force, 50, kGripperMax, "the gripper's force threshold", "dimensionless");
}

Result<void> check_gripper_position(int position) {
  return check_range("position", position, kGripperMin, kGripperMax, "the gripper's opening", "dimensionless");
}

Result<void> check_hand_preset(std::string_view name, int number) {
  return check_range(name, number, 1, kHandPresets, "a preset number", "presets stored in the hand");
}

Result<void> check_hand_angles(const std::array<int, 6>& angles) {
  constexpr std::array<std::string_view, 6> kFingers{"little finger", "ring finger", "middle finger",
                                                     "index finger",  "thumb bend",  "thumb rotation"};
  for (std::size_t i = 0; i < angles.size(); ++i) {
    if (angles[i] == kHandAngleKeep) continue;
    const std::string argument = "angle " + std::to_string(i + 1) + " (" + std::string(kFingers[i]) + ")";
    if (auto checked = check_range(argument, angles[i], 0, 1000, "a finger's angle", "dimensionless; -1 keeps it");
        !checked) {
      return checked;
    }
  }
  return {};
}

Result<void> check_hand_speed(int speed) {
  return check_range("speed", speed, 1, 1000, "the hand's finger speed", "dimensionless");
}

Result<void> check_hand_force(int force) {
  return check_range("force", force, 1, 1000, "the hand's force threshold", "dimensionless");
}

}  // namespace robotd::realman
