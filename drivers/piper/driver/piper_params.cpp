#include "driver/piper_params.hpp"

#include <limits>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "kinematics/piper_kinematics.hpp"
#include "robotd/driver/json_reader.hpp"
#include "robotd/kinematics/arm_model.hpp"

namespace robotd::piper {
namespace {

struct SdkLimit {
  double effort_max_nm;
  double mit_torque_scale;
  double effort_nm_per_a;
};

// piper_sdk's effort limits (spec §8.1; its joint angle limits are the arm model's). MIT torque:
// the arm executes 4× the wire value on J1–J3 (SDK Q&A, maintainer on FW 1.5-8), so ±8 on the
// wire is ±32 N·m there. Effort: the SDK's current factors (1.18125 J1–J3, 0.95844 J4–J6 N·m/A)
// with the same 4× on J1–J3.
constexpr std::array<SdkLimit, kArmJoints> kSdkLimits{{
    {32.0, 0.25, 4.725},
    {32.0, 0.25, 4.725},
    {32.0, 0.25, 4.725},
    {8.0, 1.0, 0.95844},
    {8.0, 1.0, 0.95844},
    {8.0, 1.0, 0.95844},
}};

constexpr double kArmMaxSpeedRadS = 3.0;  // 0x474's documented range
constexpr double kArmMaxAccRadS2 = 5.0;   // 0x475's documented range

std::string format_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

PiperJointParams sdk_joint(std::size_t index) {
  const SdkLimit& sdk = kSdkLimits[index];
  // Both DH variants share the SDK's joint limits.
  const kinematics::ArmModel& arm = *kinematics::find_arm_model(arm_model_name(DhVariant::kOffset));
  PiperJointParams joint;
  joint.name = "joint" + std::to_string(index + 1);
  joint.limits = driver::JointLimits{.position_min_rad = arm.min_rad[index],
                                     .position_max_rad = arm.max_rad[index],
                                     .velocity_max_rad_s = kArmMaxSpeedRadS,
                                     .acceleration_max_rad_s2 = kArmMaxAccRadS2,
                                     .effort_max_nm = sdk.effort_max_nm,
                                     .kp_max = 500.0,
                                     .kd_max = 5.0};
  joint.mit_torque_scale = sdk.mit_torque_scale;
  joint.effort_nm_per_a = sdk.effort_nm_per_a;
  return joint;
}

PiperJointParams sdk_gripper() {
  PiperJointParams gripper;
  gripper.name = "gripper";
  gripper.limits = driver::JointLimits{.position_min_rad = 0.0,  // metres: the gripper is prismatic
                                       .position_max_rad = 0.07,
                                       .velocity_max_rad_s = 0.1,
                                       .acceleration_max_rad_s2 = 1.0,
                                       .effort_max_nm = 5.0,
                                       .kp_max = 500.0,
                                       .kd_max = 5.0};
  gripper.default_kp = 0;
  gripper.default_kd = 0;
  return gripper;
}

void read_joint(JsonReader& reader, PiperJointParams& joint) {
  driver::JointLimits& limits = joint.limits;
  const NumberRange positive{.min = 1e-9};
  const NumberRange non_negative{.min = 0};
  limits.position_min_rad = reader.number_or("position_min_rad", limits.position_min_rad);
  limits.position_max_rad = reader.number_or("position_max_rad", limits.position_max_rad);
  limits.velocity_max_rad_s = reader.number_or("velocity_max_rad_s", limits.velocity_max_rad_s, positive);
  limits.acceleration_max_rad_s2 =
      reader.number_or("acceleration_max_rad_s2", limits.acceleration_max_rad_s2, positive);
  limits.effort_max_nm = reader.number_or("effort_max_nm", limits.effort_max_nm, positive);
  limits.kp_max = reader.number_or("kp_max", limits.kp_max, NumberRange{.min = 1e-9, .max = 500});
  limits.kd_max = reader.number_or("kd_max", limits.kd_max, NumberRange{.min = 1e-9, .max = 5});
  joint.default_kp = reader.number_or("default_kp", joint.default_kp, non_negative);
  joint.default_kd = reader.number_or("default_kd", joint.default_kd, non_negative);
  joint.mit_torque_scale = reader.number_or("mit_torque_scale", joint.mit_torque_scale, positive);
  joint.effort_nm_per_a = reader.number_or("effort_nm_per_a", joint.effort_nm_per_a, non_negative);
  if (!(limits.position_min_rad < limits.position_max_rad)) {
    reader.error("position_min_rad", "expected less than position_max_rad (" + format_number(limits.position_max_rad) +
                                         "), got " + format_number(limits.position_min_rad));
  }
  if (joint.default_kp > limits.kp_max) {
    reader.error("default_kp", "expected at most kp_max (" + format_number(limits.kp_max) + "), got " +
                                   format_number(joint.default_kp));
  }
  if (joint.default_kd > limits.kd_max) {
    reader.error("default_kd", "expected at most kd_max (" + format_number(limits.kd_max) + "), got " +
                                   format_number(joint.default_kd));
  }
  // An arm joint's DAMPING is MIT with kp = 0 and kd = default_kd, and KEEP of a joint that was not
  // tracking holds it with both: 0 would let it go while robotd reports DAMPING or KEEP.
  if (joint.name != "gripper") {
    for (const auto& [key, gain] :
         {std::pair{"default_kp", joint.default_kp}, std::pair{"default_kd", joint.default_kd}}) {
      if (reader.has(key) && !(gain > 0)) {
        reader.error(key, "expected more than 0 for " + joint.name + ", got " + format_number(gain) +
                              ": DAMPING (kp = 0, kd = default_kd) and KEEP of a joint that was not tracking hold "
                              "the joint with these gains, so 0 would let it go");
      }
    }
  }
  reader.finish();
}

void read_joint_overrides(JsonReader& reader, PiperParams& out) {
  for (auto& [name, joint_reader] : reader.object_map("joints")) {
    PiperJointParams* joint = nullptr;
    for (PiperJointParams& candidate : out.joints) {
      if (candidate.name == name) joint = &candidate;
    }
    if (name == "gripper") joint = &out.gripper_joint;
    if (joint == nullptr) {
      reader.error("joints", "unknown joint \"" + name + "\"; expected joint1 … joint6 or gripper");
      continue;
    }
    read_joint(joint_reader, *joint);
  }
}

void read_codec_options(JsonReader& reader, CodecOptions& codec) {
  auto units = reader.object("units");
  if (!units) return;
  // The spec's ⚠ unit conflicts, for arms whose firmware proves the other reading right.
  codec.max_speed_unit_rad_s =
      units->number_or("max_speed_rad_s_per_count", codec.max_speed_unit_rad_s, NumberRange{.min = 1e-6, .max = 1});
  codec.max_acc_unit_rad_s2 =
      units->number_or("max_acc_rad_s2_per_count", codec.max_acc_unit_rad_s2, NumberRange{.min = 1e-6, .max = 1});
  codec.motor_position_unit_rad = units->number_or("motor_position_rad_per_count", codec.motor_position_unit_rad,
                                                   NumberRange{.min = 1e-6, .max = 1});
  units->finish();
}

/// "feedback_id_offset" / "control_id_offset": where the arm's MasterSlaveConfig moved its ids.
void read_id_offsets(JsonReader& reader, CodecOptions& codec) {
  for (auto [key, offset] : {std::pair{"feedback_id_offset", &codec.feedback_id_offset},
                             std::pair{"control_id_offset", &codec.control_id_offset}}) {
    const std::int64_t value =
        reader.integer_or(key, 0, std::numeric_limits<std::int64_t>::min(), std::numeric_limits<std::int64_t>::max());
    if (value < 0 || value > 0xFF || !id_offset_valid(static_cast<std::uint8_t>(value))) {
      reader.error(key, "expected 0, 16 (0x10) or 32 (0x20), the offsets MasterSlaveConfig (0x470) takes, got " +
                            std::to_string(value));
      continue;
    }
    *offset = static_cast<std::uint8_t>(value);
  }
}

void read_firmware(JsonReader& reader, PiperParams& out) {
  out.firmware = reader.string_or("firmware", out.firmware);
  if (out.firmware == "auto") return;
  constexpr std::size_t kVersionLength = 8;  // "S-V1.8-2"
  if (out.firmware.size() != kVersionLength || software_version(out.firmware) != out.firmware) {
    reader.error("firmware",
                 "expected \"auto\" or a software version such as \"S-V1.8-2\", got \"" + out.firmware + "\"");
    return;
  }
  out.codec.mit_layout = mit_layout_for(out.firmware);
}

}  // namespace

Result<PiperParams> parse_piper_params(const nlohmann::json& params) {
  std::vector<std::string> errors;
  JsonReader reader(params, "", errors);
  PiperParams out;
  for (std::size_t j = 0; j < kArmJoints; ++j) out.joints[j] = sdk_joint(j);
  out.gripper_joint = sdk_gripper();

  out.model = reader.string_or("model", out.model);
  out.role =
      reader.string_or("role", "follower", {"follower", "leader"}) == "leader" ? ArmRole::kLeader : ArmRole::kFollower;
  reader.require("can", R"(the CAN link, e.g. {"transport": "socketcan", "interface": "can0"})");
  if (auto can = reader.object("can")) out.can = transport::read_can_link(*can);
  out.check_interface = reader.boolean_or("check_interface", out.check_interface);
  out.connect_timeout_ms = static_cast<int>(reader.integer_or("connect_timeout_ms", out.connect_timeout_ms, 50, 10000));
  out.feedback_timeout_ms =
      static_cast<int>(reader.integer_or("feedback_timeout_ms", out.feedback_timeout_ms, 20, 10000));
  out.reply_timeout_ms = static_cast<int>(reader.integer_or("reply_timeout_ms", out.reply_timeout_ms, 10, 10000));
  out.command_rate_hz = reader.number_or("command_rate_hz", out.command_rate_hz, NumberRange{.min = 1, .max = 500});
  out.speed_percent = static_cast<int>(reader.integer_or("speed_percent", out.speed_percent, 1, 100));
  out.high_follow = reader.boolean_or("high_follow", out.high_follow);
  read_firmware(reader, out);
  out.dh = reader.string_or("dh", "offset", {"offset", "plain"}) == "plain" ? DhVariant::kPlain : DhVariant::kOffset;
  const std::string enable = reader.string_or("enable", "on_session", {"on_session", "on_connect", "manual"});
  out.enable = enable == "on_connect" ? EnablePolicy::kOnConnect
               : enable == "manual"   ? EnablePolicy::kManual
                                      : EnablePolicy::kOnSession;
  out.disable_on_release = reader.boolean_or("disable_on_release", out.disable_on_release);
  out.gripper = reader.boolean_or("gripper", out.gripper);
  out.gripper_effort_nm = reader.number_or("gripper_effort_nm", out.gripper_effort_nm, NumberRange{.min = 0, .max = 5});
  read_codec_options(reader, out.codec);
  read_id_offsets(reader, out.codec);
  read_joint_overrides(reader, out);
  reader.finish();

  if (!errors.empty()) return make_error(ErrorCode::kInvalidArgument, join_errors(errors));
  return out;
}

}  // namespace robotd::piper
