// Ops that read: the arm's stored parameters (request → reply), and what the driver has seen.
#include <chrono>
#include <cstdio>
#include <thread>

#include "driver/hex_text.hpp"
#include "driver/piper_ops.hpp"
#include "kinematics/piper_kinematics.hpp"

namespace robotd::piper {
namespace {

constexpr const char* kProtocolVersion = "V2";        // the SDK's GetCurrentProtocolVersion: ARM_PROTOCOL_V2
constexpr std::uint8_t kTrajectoryIndexQuery = 0x03;  // 0x477 byte 0

template <class T>
std::optional<T> decoded(const CanMessage& message, const CodecOptions& options) {
  const auto frame = decode(message, options);
  if (!frame) return std::nullopt;
  if (const auto* value = std::get_if<T>(&*frame)) return *value;
  return std::nullopt;
}

std::optional<Error> no_arguments(std::string_view op, const nlohmann::json& args) {
  OpArguments arguments(op, args);
  return arguments.finish();
}

nlohmann::json joint_json(const JointReport& joint, const PiperJointParams& params) {
  return {{"position_rad", joint.position_rad},
          {"speed_rad_s", joint.speed_rad_s},
          {"current_a", joint.current_a},
          {"effort_nm", joint.current_a * params.effort_nm_per_a},
          {"motor_position_rad", joint.motor_position_rad},
          {"voltage_v", joint.voltage_v},
          {"driver_temperature_c", joint.driver_temperature_c},
          {"motor_temperature_c", joint.motor_temperature_c},
          {"driver_status", hex_text(joint.driver_status, 2)},
          {"driver_faults", driver_status_text(joint.driver_status)},
          {"bus_current_a", joint.bus_current_a},
          {"enabled", joint.enabled()}};
}

nlohmann::json bit_list(std::uint8_t bits) {
  nlohmann::json joints = nlohmann::json::array();
  for (int j = 0; j < kArmJoints; ++j) {
    if ((bits & (1U << static_cast<unsigned>(j))) != 0) joints.push_back(j + 1);
  }
  return joints;
}

}  // namespace

Result<nlohmann::json> PiperOps::limits(const nlohmann::json& args) {
  if (auto error = no_arguments("limits", args)) return *error;
  std::vector<CanMessage> requests;
  requests.reserve(kArmJoints);
  for (int j = 1; j <= kArmJoints; ++j) {
    requests.push_back(encode(JointLimitQuery{.joint = static_cast<std::uint8_t>(j)}, driver_.codec_));
  }
  auto replies = driver_.exchange(requests, can_id::kJointLimitReply, kArmJoints);
  if (!replies) return replies.error();
  nlohmann::json joints = nlohmann::json::array();
  for (const CanMessage& message : replies.value()) {
    if (const auto reply = decoded<JointLimitReply>(message, driver_.codec_)) {
      joints.push_back({{"joint", reply->joint},
                        {"min_angle_rad", reply->min_angle_rad},
                        {"max_angle_rad", reply->max_angle_rad},
                        {"max_speed_rad_s", reply->max_speed_rad_s}});
    }
  }
  return nlohmann::json{{"joints", joints}};
}

Result<nlohmann::json> PiperOps::acc_limits(const nlohmann::json& args) {
  if (auto error = no_arguments("acc_limits", args)) return *error;
  std::vector<CanMessage> requests;
  requests.reserve(kArmJoints);
  for (int j = 1; j <= kArmJoints; ++j) {
    requests.push_back(
        encode(JointLimitQuery{.joint = static_cast<std::uint8_t>(j), .acceleration = true}, driver_.codec_));
  }
  auto replies = driver_.exchange(requests, can_id::kJointAccReply, kArmJoints);
  if (!replies) return replies.error();
  nlohmann::json joints = nlohmann::json::array();
  for (const CanMessage& message : replies.value()) {
    if (const auto reply = decoded<JointAccReply>(message, driver_.codec_)) {
      joints.push_back({{"joint", reply->joint}, {"max_acc_rad_s2", reply->max_acc_rad_s2}});
    }
  }
  return nlohmann::json{{"joints", joints}};
}

Result<nlohmann::json> PiperOps::firmware(const nlohmann::json& args) {
  if (auto error = no_arguments("firmware", args)) return *error;
  constexpr std::size_t kReplyFrames = 11;
  auto replies = driver_.exchange(std::array{firmware_request()}, can_id::kFirmware, kReplyFrames);
  if (!replies) return replies.error();
  std::string text;
  for (const CanMessage& message : replies.value()) {
    text.append(reinterpret_cast<const char*>(message.data.data()), message.length);  // NOLINT: bytes are ASCII
  }
  const auto version = software_version(text);
  std::string printable;
  for (const char c : text) printable += (c >= 0x20 && c < 0x7F) ? c : '.';
  return nlohmann::json{{"text", printable},
                        {"software_version", version ? nlohmann::json(*version) : nullptr},
                        {"mit_layout", driver_.codec_.mit_layout == MitLayout::kTorque12 ? "12-bit torque, no CRC"
                                                                                         : "8-bit torque + CRC"},
                        {"protocol", kProtocolVersion}};
}

Result<nlohmann::json> PiperOps::query_param(std::uint8_t query, std::uint32_t reply_id) {
  auto replies = driver_.exchange(std::array{encode(ParamEnquiry{.query = query}, driver_.codec_)}, reply_id, 1);
  if (!replies) return replies.error();
  const auto frame = decode(replies.value().front(), driver_.codec_);
  if (!frame) return make_error(ErrorCode::kTransport, "the arm's reply could not be decoded");
  if (const auto* reply = std::get_if<EndVelAccReply>(&*frame)) return to_json(reply->values);
  if (const auto* reply = std::get_if<CrashProtectionReply>(&*frame)) {
    return nlohmann::json{{"levels", reply->levels}};
  }
  if (const auto* reply = std::get_if<GripperParamReply>(&*frame)) return to_json(reply->params);
  return make_error(ErrorCode::kTransport, "unexpected reply to the parameter query");
}

Result<nlohmann::json> PiperOps::end_limits(const nlohmann::json& args) {
  if (auto error = no_arguments("end_limits", args)) return *error;
  return query_param(1, can_id::kEndVelAccReply);
}

Result<nlohmann::json> PiperOps::crash_protection(const nlohmann::json& args) {
  if (auto error = no_arguments("crash_protection", args)) return *error;
  return query_param(2, can_id::kCrashProtectionReply);
}

Result<nlohmann::json> PiperOps::gripper_params(const nlohmann::json& args) {
  if (auto error = no_arguments("gripper_params", args)) return *error;
  return query_param(4, can_id::kGripperParamReply);
}

Result<nlohmann::json> PiperOps::can_fps(const nlohmann::json& args) {
  if (auto error = no_arguments("can_fps", args)) return *error;
  const ArmSnapshot snapshot = driver_.snapshot();
  return nlohmann::json{{"rx_fps", snapshot.rx_fps},
                        {"tx_fps", snapshot.tx_fps},
                        {"rx_frames", snapshot.rx_frames},
                        {"tx_frames", snapshot.tx_frames},
                        {"tx_dropped", snapshot.tx_dropped},
                        {"unknown_frames", snapshot.arm.unknown_frames},
                        {"implausible_frames", snapshot.arm.implausible_frames},
                        {"link", driver_.link_name_.data()}};
}

Result<nlohmann::json> PiperOps::state(const nlohmann::json& args) {
  if (auto error = no_arguments("state", args)) return *error;
  const ArmSnapshot snapshot = driver_.snapshot();
  const ArmState& arm = snapshot.arm;
  nlohmann::json joints = nlohmann::json::array();
  for (std::size_t j = 0; j < kArmJoints; ++j) joints.push_back(joint_json(arm.joints[j], driver_.params_.joints[j]));
  const GripperFeedback& gripper = arm.gripper;
  return nlohmann::json{
      {"link", snapshot.link_up ? "up" : "down"},
      {"ctrl_mode", control_mode_text(arm.status.ctrl_mode)},
      {"arm_status", arm_status_text(arm.status.arm_status)},
      {"move_mode", move_mode_text(arm.status.mode_feed)},
      {"teach_status", teach_status_text(arm.status.teach_status)},
      {"motion", arm.status.motion_status == 0 ? "target reached" : "moving"},
      {"trajectory_index", arm.status.trajectory_index},
      {"angle_limit_joints", bit_list(arm.status.angle_limit_bits)},
      {"comm_error_joints", bit_list(arm.status.comm_error_bits)},
      {"joints", joints},
      {"gripper",
       {{"stroke_m", gripper.stroke_m},
        {"effort_nm", gripper.effort_nm},
        {"enabled", (gripper.status_bits & 0x40U) != 0},
        {"homed", (gripper.status_bits & 0x80U) != 0},
        {"faults", gripper_status_text(gripper.status_bits)}}},
      {"end_pose", to_json(arm.end_pose)},
  };
}

Result<nlohmann::json> PiperOps::fk(const nlohmann::json& args) {
  OpArguments arguments("fk", args);
  const auto given = arguments.reader().number_array("joints_rad");
  if (given && given->size() != kArmJoints) {
    arguments.reader().error("joints_rad", "expected 6 numbers, got " + std::to_string(given->size()));
  }
  if (auto error = arguments.finish()) return *error;
  std::array<double, kArmJoints> q{};
  const ArmSnapshot snapshot = driver_.snapshot();
  for (std::size_t j = 0; j < kArmJoints; ++j) q[j] = given ? (*given)[j] : snapshot.arm.joints[j].position_rad;
  nlohmann::json links = nlohmann::json::array();  // links 1 … 6, as the SDK's GetFK
  for (const CartesianPose& link : link_poses(q, driver_.params_.dh)) links.push_back(to_json(link));
  return nlohmann::json{{"joints_rad", q},
                        {"source", given ? "given" : "measured"},
                        {"dh", driver_.params_.dh == DhVariant::kOffset ? "offset" : "plain"},
                        {"flange", to_json(forward_kinematics(q, driver_.params_.dh))},
                        {"links", links}};
}

Result<nlohmann::json> PiperOps::fk_calculation(const nlohmann::json& args) {
  OpArguments arguments("fk_calculation", args);
  const bool enabled = arguments.reader().boolean_or("enabled", driver_.fk_enabled_.load(std::memory_order_relaxed));
  if (auto error = arguments.finish()) return *error;
  driver_.fk_enabled_.store(enabled, std::memory_order_relaxed);
  return nlohmann::json{{"enabled", driver_.fk_enabled_.load(std::memory_order_relaxed)}};
}

Result<nlohmann::json> PiperOps::trajectory_index(const nlohmann::json& args) {
  if (auto error = no_arguments("trajectory_index", args)) return *error;
  // The vendor publishes no reply frame for query 0x03; the arm carries the index in every
  // status frame, so the answer is the first status that arrives after the query.
  const std::int64_t asked_ns = driver_.snapshot().arm.last_status_ns;
  if (driver_.send(encode(ParamEnquiry{.query = kTrajectoryIndexQuery}, driver_.codec_)) != transport::CanIo::kDone) {
    return make_error(ErrorCode::kTransport, "could not send the trajectory-index query (0x477)");
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(driver_.params_.reply_timeout_ms);
  while (std::chrono::steady_clock::now() < deadline) {
    const ArmSnapshot snapshot = driver_.snapshot();
    if (snapshot.arm.last_status_ns > asked_ns) {
      return nlohmann::json{{"trajectory_index", snapshot.arm.status.trajectory_index}};
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return make_error(ErrorCode::kTimeout, "no status frame (0x2A1) within " +
                                             std::to_string(driver_.params_.reply_timeout_ms) + " ms of the query");
}

Result<nlohmann::json> PiperOps::master_commands(const nlohmann::json& args) {
  if (auto error = no_arguments("master_commands", args)) return *error;
  const ArmState& arm = driver_.snapshot().arm;
  if (!arm.master_seen) return nlohmann::json{{"seen", false}};
  return nlohmann::json{{"seen", true},
                        {"ctrl_mode", control_mode_text(arm.master_mode.ctrl_mode)},
                        {"move_mode", move_mode_text(arm.master_mode.move_mode)},
                        {"speed_percent", arm.master_mode.speed_percent},
                        {"joints_rad", arm.master_joints_rad},
                        {"gripper_stroke_m", arm.master_gripper.stroke_m},
                        {"gripper_effort_nm", arm.master_gripper.effort_nm}};
}

}  // namespace robotd::piper
