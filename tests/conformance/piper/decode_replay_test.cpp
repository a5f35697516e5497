// Crafted feedback frames, decoded by robotd's codec and by the SDK's ParseCANFrame: the same
// values (in the SDK's integer units) from what robotd keeps, and the same frames dropped as
// impossible.
#include <cstdint>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "codec/piper_frames.hpp"
#include "conformance_report.hpp"
#include "differences.hpp"
#include "sdk_units.hpp"
#include "vector_file.hpp"

namespace robotd::piper::conformance {
namespace {

using nlohmann::json;
using robotd::conformance::hex_bytes;
using robotd::conformance::load_json_lines;
using robotd::conformance::record;

std::string joint_key(int joint) { return "joint_" + std::to_string(joint); }
std::string motor_key(int joint) { return "motor_" + std::to_string(joint); }

json counts_or_null(const std::optional<double>& value, double unit) {
  return value ? json(counts_of(*value, unit)) : json(nullptr);
}

constexpr double kMilli = 0.001;
const CodecOptions kSdkOptions{};  // SDK 0.6.1: 8-bit MIT torque, 0.001 units for speed and motor position

/// What robotd decoded, laid out as the SDK's getter reports it (only the fields robotd keeps).
json sdk_view(const Frame& frame) {
  return std::visit(
      [](const auto& value) -> json {
        using T = std::decay_t<decltype(value)>;
        if constexpr (std::is_same_v<T, ArmStatus>) {
          return {{"arm_status",
                   {{"ctrl_mode", static_cast<int>(value.ctrl_mode)},
                    {"arm_status", value.arm_status},
                    {"mode_feed", static_cast<int>(value.mode_feed)},
                    {"teach_status", value.teach_status},
                    {"motion_status", value.motion_status},
                    {"trajectory_num", value.trajectory_index},
                    {"err_code", value.angle_limit_bits << 8 | value.comm_error_bits}}}};
        } else if constexpr (std::is_same_v<T, EndPoseFeedbackPart>) {
          if (value.part == 0)
            return {{"end_pose", {{"X_axis", micrometres_of(value.first)}, {"Y_axis", micrometres_of(value.second)}}}};
          if (value.part == 1)
            return {{"end_pose", {{"Z_axis", micrometres_of(value.first)}, {"RX_axis", milli_deg_of(value.second)}}}};
          return {{"end_pose", {{"RY_axis", milli_deg_of(value.first)}, {"RZ_axis", milli_deg_of(value.second)}}}};
        } else if constexpr (std::is_same_v<T, JointFeedbackPair> || std::is_same_v<T, JointTargetPair>) {
          const char* getter = std::is_same_v<T, JointFeedbackPair> ? "joint_state" : "joint_ctrl";
          return {{getter,
                   {{joint_key(2 * value.pair + 1), milli_deg_of(value.first_rad)},
                    {joint_key(2 * value.pair + 2), milli_deg_of(value.second_rad)}}}};
        } else if constexpr (std::is_same_v<T, GripperFeedback>) {
          return {{"gripper_state",
                   {{"grippers_angle", micrometres_of(value.stroke_m)},
                    {"grippers_effort", counts_of(value.effort_nm, kMilli)},
                    {"status_code", value.status_bits}}}};
        } else if constexpr (std::is_same_v<T, GripperControl>) {
          return {{"gripper_ctrl",
                   {{"grippers_angle", micrometres_of(value.stroke_m)},
                    {"grippers_effort", counts_of(value.effort_nm, kMilli)},
                    {"status_code", static_cast<int>(value.enable)},
                    {"set_zero", value.set_zero ? kMagic : 0}}}};
        } else if constexpr (std::is_same_v<T, HighSpeedInfo>) {
          return {{motor_key(value.joint),
                   {{"motor_speed", counts_of(value.speed_rad_s, kMilli)},
                    {"current", counts_of(value.current_a, kMilli)},
                    {"pos", counts_of(value.position_rad, kSdkOptions.motor_position_unit_rad)}}}};
        } else if constexpr (std::is_same_v<T, LowSpeedInfo>) {
          return {{motor_key(value.joint),
                   {{"vol", counts_of(value.voltage_v, 0.1)},
                    {"foc_temp", value.driver_temperature_c},
                    {"motor_temp", value.motor_temperature_c},
                    {"foc_status_code", value.status_bits},
                    {"bus_current", counts_of(value.bus_current_a, kMilli)}}}};
        } else if constexpr (std::is_same_v<T, JointLimitReply>) {
          return {{"current_motor_angle_limit_max_vel",
                   {{"motor_num", value.joint},
                    {"max_angle_limit", deci_deg_of(value.max_angle_rad)},
                    {"min_angle_limit", deci_deg_of(value.min_angle_rad)},
                    {"max_joint_spd", counts_of(value.max_speed_rad_s, kSdkOptions.max_speed_unit_rad_s)}}}};
        } else if constexpr (std::is_same_v<T, EndVelAccReply>) {
          return {{"current_end_vel_acc_param",
                   {{"end_max_linear_vel", counts_or_null(value.values.max_linear_velocity_m_s, kMilli)},
                    {"end_max_angular_vel", counts_or_null(value.values.max_angular_velocity_rad_s, kMilli)},
                    {"end_max_linear_acc", counts_or_null(value.values.max_linear_acceleration_m_s2, kMilli)},
                    {"end_max_angular_acc", counts_or_null(value.values.max_angular_acceleration_rad_s2, kMilli)}}}};
        } else if constexpr (std::is_same_v<T, CrashProtectionReply>) {
          json levels;
          for (int j = 0; j < kArmJoints; ++j) {
            levels[joint_key(j + 1) + "_protection_level"] = value.levels[static_cast<std::size_t>(j)];
          }
          return {{"crash_protection_level_feedback", levels}};
        } else if constexpr (std::is_same_v<T, JointAccReply>) {
          return {{"current_motor_max_acc_limit",
                   {{"joint_motor_num", value.joint},
                    {"max_joint_acc", counts_of(value.max_acc_rad_s2, kSdkOptions.max_acc_unit_rad_s2)}}}};
        } else if constexpr (std::is_same_v<T, GripperParamReply>) {
          return {{"arm_gripper_teaching_param_feedback",
                   {{"teaching_range_per", value.params.teaching_range_percent},
                    {"max_range_config", value.params.max_range_mm},
                    {"teaching_friction", value.params.teaching_friction}}}};
        } else if constexpr (std::is_same_v<T, SetAck>) {
          return {{"instruction_response",
                   {{"instruction_index", value.command}, {"is_set_zero_successfully", value.zero_set ? 1 : 0}}}};
        } else if constexpr (std::is_same_v<T, ModeControl>) {
          return {{"mode_ctrl",
                   {{"ctrl_mode", static_cast<int>(value.ctrl_mode)},
                    {"move_mode", static_cast<int>(value.move_mode)},
                    {"move_spd_rate_ctrl", value.speed_percent},
                    {"mit_mode", value.mit ? kMitFlag : 0},
                    {"residence_time", value.residence_time_s}}}};
        } else {
          return {{"unexpected frame type", true}};
        }
      },
      frame);
}

/// The SDK's values at the fields robotd reports (the SDK's getters report more: defaults of
/// fields the frame does not carry, derived flags).
json sdk_fields(const json& sdk_result, const json& robotd_view) {
  json fields = json::object();
  const json flat = robotd_view.flatten();
  for (const auto& [path, value] : flat.items()) {
    const json::json_pointer pointer(path);
    fields[path] = sdk_result.contains(pointer) ? sdk_result.at(pointer) : json("missing in the SDK's getter");
  }
  return fields;
}

TEST(DecodeReplay, FeedbackDecodesAsTheSdkReadsIt) {
  const std::vector<json> vectors = load_json_lines("decodes.jsonl");
  ASSERT_FALSE(vectors.empty());
  for (const json& vector : vectors) {
    const json key{{"id", vector.at("id")}, {"data", vector.at("data")}};
    const std::vector<std::uint8_t> data = hex_bytes(vector.at("data").get<std::string>());
    const CanMessage message = transport::classic_frame(vector.at("id").get<std::uint32_t>(), data);
    const std::optional<Frame> frame = decode(message, kSdkOptions);
    const bool accepted = frame.has_value() && plausible(*frame);
    const bool sdk_accepted = vector.at("accepted").get<bool>();
    const char* group = sdk_accepted ? "decode" : "abnormal filter";
    if (!sdk_accepted || !accepted) {
      record(group, judge(group, key, json{{"accepted", sdk_accepted}}, json{{"accepted", accepted}}));
      continue;
    }
    const json robotd = sdk_view(*frame).flatten();
    record(group, judge(group, key, sdk_fields(vector.at("result"), sdk_view(*frame)), robotd));
  }
}

}  // namespace
}  // namespace robotd::piper::conformance
