// Ops that change the arm's stored parameters; each waits for the arm's 0x476 acknowledge.
// Joint limits, speeds and accelerations go to the joint drivers' flash: not for real-time use.
#include "driver/piper_ops.hpp"

namespace robotd::piper {
namespace {

constexpr std::uint8_t kAckJointLimits = 0x74;
constexpr std::uint8_t kAckJointConfig = 0x75;
constexpr std::uint8_t kAckParams = 0x77;
constexpr std::uint8_t kAckEndLimits = 0x79;
constexpr std::uint8_t kAckCrash = 0x7A;

std::vector<std::uint8_t> joints_of(std::uint8_t joint) {
  if (joint != kAllJoints) return {joint};
  return {1, 2, 3, 4, 5, 6};
}

nlohmann::json joint_json(std::uint8_t joint) {
  return joint == kAllJoints ? nlohmann::json("all") : nlohmann::json(joint);
}

}  // namespace

Result<nlohmann::json> PiperOps::set_joint_limits(const nlohmann::json& args) {
  OpArguments arguments("set_joint_limits", args);
  JsonReader& reader = arguments.reader();
  const auto joint = arguments.joint(/*allow_all=*/false);
  const NumberRange angle{.min = -3.2, .max = 3.2};
  JointLimitSet set;
  set.min_angle_rad = reader.number("min_angle_rad", angle);
  set.max_angle_rad = reader.number("max_angle_rad", angle);
  set.max_speed_rad_s = reader.number("max_speed_rad_s", NumberRange{.min = 0, .max = 3});
  if (!set.min_angle_rad && !set.max_angle_rad && !set.max_speed_rad_s) {
    reader.error("max_angle_rad", "give at least one of min_angle_rad, max_angle_rad, max_speed_rad_s");
  }
  if (set.min_angle_rad && set.max_angle_rad && !(*set.min_angle_rad < *set.max_angle_rad)) {
    reader.error("min_angle_rad", "expected less than max_angle_rad");
  }
  if (auto error = arguments.finish()) return *error;
  set.joint = *joint;
  const auto frame = checked_encode("set_joint_limits", set, driver_.codec_);
  if (!frame) return frame.error();
  auto acked = driver_.set_and_await_ack(frame.value(), kAckJointLimits);
  if (!acked) return acked.error();
  return nlohmann::json{{"acknowledged", "MotorAngleLimitMaxSpdSet"}, {"joint", *joint}};
}

Result<nlohmann::json> PiperOps::set_max_speed(const nlohmann::json& args) {
  OpArguments arguments("set_max_speed", args);
  const auto joint = arguments.joint(/*allow_all=*/true);
  arguments.reader().require("max_speed_rad_s", "a speed in rad/s, 0..3");
  const auto speed = arguments.reader().number("max_speed_rad_s", NumberRange{.min = 0, .max = 3});
  if (auto error = arguments.finish()) return *error;
  for (const std::uint8_t each : joints_of(*joint)) {
    const auto frame =
        checked_encode("set_max_speed", JointLimitSet{.joint = each, .max_speed_rad_s = speed}, driver_.codec_);
    if (!frame) return frame.error();
    auto acked = driver_.set_and_await_ack(frame.value(), kAckJointLimits);
    if (!acked) return make_error(acked.error().code, "joint " + std::to_string(each) + ": " + acked.error().message);
  }
  return nlohmann::json{{"acknowledged", "MotorMaxSpdSet"}, {"joint", joint_json(*joint)}, {"max_speed_rad_s", *speed}};
}

Result<nlohmann::json> PiperOps::joint_config(const nlohmann::json& args) {
  OpArguments arguments("joint_config", args);
  JsonReader& reader = arguments.reader();
  const auto joint = arguments.joint(/*allow_all=*/true);
  JointConfig config;
  config.set_zero = reader.boolean_or("set_zero", false);
  const auto acc = reader.number("max_acc_rad_s2", NumberRange{.min = 0, .max = 5});
  config.apply_max_acc = acc.has_value();
  if (acc) config.max_acc_rad_s2 = *acc;
  config.clear_error = reader.boolean_or("clear_error", false);
  if (!config.set_zero && !acc && !config.clear_error) {
    reader.error("set_zero", "give at least one of set_zero, max_acc_rad_s2, clear_error");
  }
  if (auto error = arguments.finish()) return *error;
  // A new zero moves the frame robotd's streamed targets are in: streaming stays off until a
  // session takes joints again, so a hold robotd kept from before never reaches the arm.
  if (config.set_zero) {
    if (auto refused = take_arm_for("joint_config")) return *refused;
  }
  config.joint = *joint;
  const auto frame = checked_encode("joint_config", config, driver_.codec_);
  if (!frame) return frame.error();
  auto acked = driver_.set_and_await_ack(frame.value(), kAckJointConfig);
  if (!acked) return acked.error();
  nlohmann::json reply{{"acknowledged", "JointConfig"}, {"joint", joint_json(*joint)}};
  if (config.set_zero) reply["zero_set"] = acked.value().zero_set;
  return reply;
}

Result<nlohmann::json> PiperOps::set_max_acc(const nlohmann::json& args) {
  OpArguments arguments("set_max_acc", args);
  const auto joint = arguments.joint(/*allow_all=*/true);
  arguments.reader().require("max_acc_rad_s2", "an acceleration in rad/s², 0..5");
  const auto acc = arguments.reader().number("max_acc_rad_s2", NumberRange{.min = 0, .max = 5});
  if (auto error = arguments.finish()) return *error;
  const auto frame = checked_encode(
      "set_max_acc", JointConfig{.joint = *joint, .apply_max_acc = true, .max_acc_rad_s2 = *acc}, driver_.codec_);
  if (!frame) return frame.error();
  auto acked = driver_.set_and_await_ack(frame.value(), kAckJointConfig);
  if (!acked) return acked.error();
  return nlohmann::json{{"acknowledged", "JointMaxAccConfig"}, {"joint", joint_json(*joint)}, {"max_acc_rad_s2", *acc}};
}

Result<nlohmann::json> PiperOps::param_config(const nlohmann::json& args) {
  OpArguments arguments("param_config", args);
  JsonReader& reader = arguments.reader();
  ParamEnquiry enquiry;
  const bool reset_end = reader.boolean_or("reset_end_limits", false);
  const bool reset_joints = reader.boolean_or("reset_joint_limits", false);
  if (reset_end && reset_joints) reader.error("reset_joint_limits", "one reset per call (the frame carries one)");
  enquiry.setting = reset_end ? 1 : reset_joints ? 2 : 0;
  if (const auto feedback = reader.string("feedback_48x", {"enable", "disable"})) {
    enquiry.feedback_48x = *feedback == "enable" ? 1 : 2;
  }
  if (const auto payload = reader.string("payload", {"empty", "half", "full"})) {
    enquiry.payload = static_cast<std::uint8_t>(*payload == "empty" ? 0 : *payload == "half" ? 1 : 2);
  }
  if (enquiry.setting == 0 && enquiry.feedback_48x == 0 && !enquiry.payload) {
    reader.error("reset_end_limits",
                 "give at least one of reset_end_limits, reset_joint_limits, feedback_48x, payload (queries are the "
                 "end_limits, crash_protection and gripper_params ops)");
  }
  if (auto error = arguments.finish()) return *error;
  const auto frame = checked_encode("param_config", enquiry, driver_.codec_);
  if (!frame) return frame.error();
  auto acked = driver_.set_and_await_ack(frame.value(), kAckParams);
  if (!acked) return acked.error();
  return nlohmann::json{{"acknowledged", "ArmParamEnquiryAndConfig"}};
}

Result<nlohmann::json> PiperOps::set_end_limits(const nlohmann::json& args) {
  OpArguments arguments("set_end_limits", args);
  JsonReader& reader = arguments.reader();
  const NumberRange range{.min = 0, .max = 32.766};  // uint16 × 0.001, below the 0x7FFF "unchanged"
  EndVelAccSet set;
  set.values.max_linear_velocity_m_s = reader.number("max_linear_velocity_m_s", range);
  set.values.max_angular_velocity_rad_s = reader.number("max_angular_velocity_rad_s", range);
  set.values.max_linear_acceleration_m_s2 = reader.number("max_linear_acceleration_m_s2", range);
  set.values.max_angular_acceleration_rad_s2 = reader.number("max_angular_acceleration_rad_s2", range);
  const EndVelAcc& values = set.values;
  if (!values.max_linear_velocity_m_s && !values.max_angular_velocity_rad_s && !values.max_linear_acceleration_m_s2 &&
      !values.max_angular_acceleration_rad_s2) {
    reader.error("max_linear_velocity_m_s", "give at least one limit");
  }
  if (auto error = arguments.finish()) return *error;
  const auto frame = checked_encode("set_end_limits", set, driver_.codec_);
  if (!frame) return frame.error();
  auto acked = driver_.set_and_await_ack(frame.value(), kAckEndLimits);
  if (!acked) return acked.error();
  return nlohmann::json{{"acknowledged", "EndSpdAndAccParamSet"}, {"set", to_json(set.values)}};
}

Result<nlohmann::json> PiperOps::set_crash_protection(const nlohmann::json& args) {
  OpArguments arguments("set_crash_protection", args);
  JsonReader& reader = arguments.reader();
  reader.require("levels", "6 integers 0..8, one per joint (0 = off)");
  const auto levels = reader.number_array("levels", NumberRange{.min = 0, .max = 8});
  CrashProtectionSet set;
  if (levels) {
    if (levels->size() != kArmJoints) {
      reader.error("levels", "expected 6 levels, got " + std::to_string(levels->size()));
    } else {
      for (std::size_t j = 0; j < kArmJoints; ++j) {
        if ((*levels)[j] != static_cast<double>(static_cast<int>((*levels)[j]))) {
          reader.error("levels", "expected integers, got " + std::to_string((*levels)[j]));
          break;
        }
        set.levels[j] = static_cast<std::uint8_t>((*levels)[j]);
      }
    }
  }
  if (auto error = arguments.finish()) return *error;
  auto acked = driver_.set_and_await_ack(encode(set, driver_.codec_), kAckCrash);
  if (!acked) return acked.error();
  return nlohmann::json{{"acknowledged", "CrashProtectionConfig"}, {"levels", set.levels}};
}

Result<nlohmann::json> PiperOps::set_gripper_params(const nlohmann::json& args) {
  OpArguments arguments("set_gripper_params", args);
  JsonReader& reader = arguments.reader();
  GripperParamSet set;
  set.params.teaching_range_percent =
      static_cast<std::uint8_t>(reader.integer_or("teaching_range_percent", 100, 100, 200));
  const auto range = reader.integer_or("max_range_mm", 70, 0, 100);
  if (range != 0 && range != 70 && range != 100) {
    reader.error("max_range_mm", "expected 0, 70 or 100, got " + std::to_string(range));
  }
  set.params.max_range_mm = static_cast<std::uint8_t>(range);
  set.params.teaching_friction = static_cast<std::uint8_t>(reader.integer_or("teaching_friction", 1, 1, 10));
  if (auto error = arguments.finish()) return *error;
  // The arm does not acknowledge 0x47D; read the parameters back as the SDK demo does.
  const auto frame = checked_encode("set_gripper_params", set, driver_.codec_);
  if (!frame) return frame.error();
  if (driver_.send(frame.value()) != transport::CanIo::kDone) {
    return make_error(ErrorCode::kTransport, "could not send 0x47D");
  }
  auto stored = query_param(4, can_id::kGripperParamReply);
  if (!stored) return stored.error();
  return nlohmann::json{{"sent", "GripperTeachingPendantParamConfig"}, {"stored", stored.value()}};
}

}  // namespace robotd::piper
