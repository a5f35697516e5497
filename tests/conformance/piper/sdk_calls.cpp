#include "sdk_calls.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>

#include "sdk_units.hpp"

namespace robotd::piper::conformance {
namespace {

using nlohmann::json;
using Frames = std::vector<CanMessage>;

constexpr int kUnchangedCount = 0x7FFF;  // the SDK's "leave unchanged" argument

std::uint8_t u8(const json& args, std::size_t i) { return args.at(i).get<std::uint8_t>(); }
int integer(const json& args, std::size_t i) { return args.at(i).get<int>(); }
double number(const json& args, std::size_t i) { return args.at(i).get<double>(); }

Frames one(const CanMessage& message) { return {message}; }

/// robotd's codec refuses what refusal() names, where the SDK raises for the same argument.
template <typename Frame>
CanMessage checked(const Frame& frame) {
  if (const char* reason = refusal(frame)) throw std::invalid_argument(reason);
  return encode(frame);
}

/// A byte the SDK takes as 0x00 or 0xAE ("do it"): robotd takes a boolean there (its ops read
/// JSON true/false), so any other byte cannot reach robotd's codec at all.
bool magic_flag(const json& args, std::size_t i) {
  const std::uint8_t value = u8(args, i);
  if (value != 0x00 && value != kMagic) throw std::invalid_argument("a flag byte is 0x00 or 0xAE");
  return value == kMagic;
}
template <std::size_t N>
Frames all(const std::array<CanMessage, N>& messages) {
  return {messages.begin(), messages.end()};
}

Frames motion_control(std::uint8_t stop, std::uint8_t track, std::uint8_t drag) {
  return one(checked(
      MotionControl{.emergency_stop = static_cast<EmergencyStop>(stop), .track_ctrl = track, .drag_teach_ctrl = drag}));
}

/// 0x151: robotd's MIT flag is a boolean (0xAD or 0x00); it refuses the SDK's 0xFF ("invalid"),
/// a deliberate difference (differences.json).
Frames mode_control(const json& args, std::uint8_t residence, std::uint8_t installation) {
  const std::uint8_t mit = u8(args, 3);
  if (mit != 0x00 && mit != kMitFlag) throw std::invalid_argument("the MIT byte is 0xAD or 0x00");
  return one(checked(ModeControl{.ctrl_mode = static_cast<ControlMode>(u8(args, 0)),
                                 .move_mode = static_cast<MoveMode>(u8(args, 1)),
                                 .speed_percent = u8(args, 2),
                                 .mit = mit == 0xAD,
                                 .residence_time_s = residence,
                                 .installation = installation}));
}

std::optional<double> unless_unchanged(int count, double unit) {
  if (count == kUnchangedCount) return std::nullopt;
  return count * unit;
}
std::optional<double> deci_deg_unless_unchanged(int count) {
  if (count == kUnchangedCount) return std::nullopt;
  return rad_of_deci_deg(count);
}

constexpr std::uint8_t kNoPayload = 0x03;  // 0x477 byte 4 when the payload is not set

/// 0x472 byte 1: 0x01 angle limits and speed, 0x02 acceleration; robotd takes a boolean.
bool limit_query(const json& args, std::size_t i) {
  const std::uint8_t value = u8(args, i);
  if (value != 0x01 && value != 0x02) throw std::invalid_argument("the limit query is 0x01 or 0x02");
  return value == 0x02;
}

Frames joint_limit_queries(bool acceleration) {
  Frames frames;
  for (std::uint8_t joint = 1; joint <= kArmJoints; ++joint) {
    frames.push_back(checked(JointLimitQuery{.joint = joint, .acceleration = acceleration}));
  }
  return frames;
}

constexpr double kAccUnit = 0.01;     // 0x475 max joint acc: 0.01 rad/s² per count (CodecOptions default)
constexpr double kSpeedUnit = 0.001;  // 0x474 max joint speed
constexpr double kEndUnit = 0.001;    // 0x479

Frames joint_config(std::uint8_t joint, bool set_zero, bool apply_acc, int acc, bool clear_error) {
  return one(checked(JointConfig{.joint = joint,
                                 .set_zero = set_zero,
                                 .apply_max_acc = apply_acc,
                                 .max_acc_rad_s2 = acc * kAccUnit,
                                 .clear_error = clear_error}));
}

const std::map<std::string, std::function<Frames(const json&)>, std::less<>>& calls() {
  static const std::map<std::string, std::function<Frames(const json&)>, std::less<>> table{
      {"MotionCtrl_1", [](const json& a) { return motion_control(u8(a, 0), u8(a, 1), u8(a, 2)); }},
      {"EmergencyStop", [](const json& a) { return motion_control(u8(a, 0), 0, 0); }},
      {"ResetPiper", [](const json&) { return motion_control(0x02, 0, 0); }},
      {"MotionCtrl_2", [](const json& a) { return mode_control(a, u8(a, 4), u8(a, 5)); }},
      {"ModeCtrl", [](const json& a) { return mode_control(a, 0, 0); }},
      {"EndPoseCtrl",
       [](const json& a) {
         return all(encode_end_pose_target(CartesianPose{.x_m = metres_of_micrometres(number(a, 0)),
                                                         .y_m = metres_of_micrometres(number(a, 1)),
                                                         .z_m = metres_of_micrometres(number(a, 2)),
                                                         .rx_rad = rad_of_milli_deg(number(a, 3)),
                                                         .ry_rad = rad_of_milli_deg(number(a, 4)),
                                                         .rz_rad = rad_of_milli_deg(number(a, 5))}));
       }},
      {"JointCtrl",
       [](const json& a) {
         std::array<double, kArmJoints> q{};
         for (std::size_t j = 0; j < q.size(); ++j) q[j] = rad_of_milli_deg(number(a, j));
         return all(encode_joint_targets(q));
       }},
      {"MoveCAxisUpdateCtrl", [](const json& a) { return one(checked(MoveCPoint{.index = u8(a, 0)})); }},
      {"GripperCtrl",
       [](const json& a) {
         return one(checked(GripperControl{.stroke_m = metres_of_micrometres(number(a, 0)),
                                           .effort_nm = number(a, 1) * 0.001,
                                           .enable = static_cast<GripperEnable>(u8(a, 2)),
                                           .set_zero = magic_flag(a, 3)}));
       }},
      {"MasterSlaveConfig",
       [](const json& a) {
         return one(checked(MasterSlaveConfig{.linkage = u8(a, 0),
                                              .feedback_offset = u8(a, 1),
                                              .control_offset = u8(a, 2),
                                              .linkage_offset = u8(a, 3)}));
       }},
      {"DisableArm", [](const json& a) { return one(checked(MotorEnable{.motor = u8(a, 0), .enable = false})); }},
      {"EnableArm", [](const json& a) { return one(checked(MotorEnable{.motor = u8(a, 0), .enable = true})); }},
      {"EnablePiper", [](const json&) { return one(checked(MotorEnable{.motor = kAllJoints, .enable = true})); }},
      {"DisablePiper", [](const json&) { return one(checked(MotorEnable{.motor = kAllJoints, .enable = false})); }},
      {"SearchMotorMaxAngleSpdAccLimit",
       [](const json& a) {
         return one(checked(JointLimitQuery{.joint = u8(a, 0), .acceleration = limit_query(a, 1)}));
       }},
      {"SearchAllMotorMaxAngleSpd", [](const json&) { return joint_limit_queries(false); }},
      {"SearchAllMotorMaxAccLimit", [](const json&) { return joint_limit_queries(true); }},
      {"SearchPiperFirmwareVersion", [](const json&) { return one(firmware_request()); }},
      {"PiperInit",
       [](const json&) {
         Frames frames = joint_limit_queries(false);
         const Frames acc = joint_limit_queries(true);
         frames.insert(frames.end(), acc.begin(), acc.end());
         frames.push_back(firmware_request());
         return frames;
       }},
      {"MotorAngleLimitMaxSpdSet",
       [](const json& a) {
         return one(checked(JointLimitSet{.joint = u8(a, 0),
                                          .max_angle_rad = deci_deg_unless_unchanged(integer(a, 1)),
                                          .min_angle_rad = deci_deg_unless_unchanged(integer(a, 2)),
                                          .max_speed_rad_s = unless_unchanged(integer(a, 3), kSpeedUnit)}));
       }},
      {"MotorMaxSpdSet",
       [](const json& a) {
         return one(
             checked(JointLimitSet{.joint = u8(a, 0), .max_speed_rad_s = unless_unchanged(integer(a, 1), kSpeedUnit)}));
       }},
      {"JointConfig",
       [](const json& a) {
         return joint_config(u8(a, 0), magic_flag(a, 1), magic_flag(a, 2), integer(a, 3), magic_flag(a, 4));
       }},
      {"JointMaxAccConfig", [](const json& a) { return joint_config(u8(a, 0), false, true, integer(a, 1), false); }},
      {"ArmParamEnquiryAndConfig",
       [](const json& a) {
         ParamEnquiry enquiry{.query = u8(a, 0), .setting = u8(a, 1), .feedback_48x = u8(a, 2)};
         if (magic_flag(a, 3)) {
           enquiry.payload = u8(a, 4);
         } else if (u8(a, 4) > kNoPayload) {
           throw std::invalid_argument("the payload is 0 (empty), 1 (half), 2 (full) or 3 (none)");
         }
         return one(checked(enquiry));
       }},
      {"EndSpdAndAccParamSet",
       [](const json& a) {
         return one(
             checked(EndVelAccSet{.values = EndVelAcc{.max_linear_velocity_m_s = number(a, 0) * kEndUnit,
                                                      .max_angular_velocity_rad_s = number(a, 1) * kEndUnit,
                                                      .max_linear_acceleration_m_s2 = number(a, 2) * kEndUnit,
                                                      .max_angular_acceleration_rad_s2 = number(a, 3) * kEndUnit}}));
       }},
      {"CrashProtectionConfig",
       [](const json& a) {
         CrashProtectionSet set;
         for (std::size_t j = 0; j < set.levels.size(); ++j) set.levels[j] = u8(a, j);
         return one(encode(set));
       }},
      {"GripperTeachingPendantParamConfig",
       [](const json& a) {
         return one(checked(GripperParamSet{.params = GripperParams{.teaching_range_percent = u8(a, 0),
                                                                    .max_range_mm = u8(a, 1),
                                                                    .teaching_friction = u8(a, 2)}}));
       }},
      {"ReqMasterArmMoveToHome",
       [](const json& a) { return one(encode(MasterArmHomeRequest{.mode = static_cast<MasterArmHome>(u8(a, 0))})); }},
      {"JointMitCtrl",
       [](const json& a) {
         return one(encode(MitControl{.joint = integer(a, 0),
                                      .position_rad = number(a, 1),
                                      .velocity_rad_s = number(a, 2),
                                      .kp = number(a, 3),
                                      .kd = number(a, 4),
                                      .torque = number(a, 5)}));
       }},
  };
  return table;
}

}  // namespace

std::vector<CanMessage> robotd_frames(std::string_view call, const json& args) {
  const auto it = calls().find(call);
  if (it == calls().end()) throw NotOffered("robotd's codec has no counterpart of " + std::string(call));
  return it->second(args);
}

}  // namespace robotd::piper::conformance
