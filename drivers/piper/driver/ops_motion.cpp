// Ops that move the arm or change its mode outside a session: end_pose, move_c, mode, gripper,
// enable / disable, master_slave, master_home.
#include <chrono>
#include <thread>

#include "driver/piper_ops.hpp"

namespace robotd::piper {
namespace {

using namespace std::chrono_literals;

/// How long an op waits for the loop to end a session robotd released just before it.
constexpr auto kSessionEndWait = 100ms;

std::optional<ControlMode> control_mode_named(const std::string& name) {
  if (name == "standby") return ControlMode::kStandby;
  if (name == "can") return ControlMode::kCanCommand;
  if (name == "ethernet") return ControlMode::kEthernet;
  if (name == "wifi") return ControlMode::kWifi;
  if (name == "offline") return ControlMode::kOfflineTrajectory;
  return std::nullopt;
}

std::optional<MoveMode> move_mode_named(const std::string& name) {
  if (name == "p") return MoveMode::kP;
  if (name == "j") return MoveMode::kJ;
  if (name == "l") return MoveMode::kL;
  if (name == "c") return MoveMode::kC;
  if (name == "mit") return MoveMode::kMit;
  if (name == "cpv") return MoveMode::kCpv;
  return std::nullopt;
}

std::uint8_t installation_code(const std::string& name) {
  if (name == "horizontal") return 1;
  if (name == "side_left") return 2;
  if (name == "side_right") return 3;
  return 0;
}

std::uint8_t id_offset(JsonReader& reader, std::string_view key) {
  const auto value = reader.integer(key, 0, 0x20);
  if (!value) return 0;
  if (!id_offset_valid(static_cast<std::uint8_t>(*value))) {
    reader.error(key, "expected 0, 16 or 32, got " + std::to_string(*value));
    return 0;
  }
  return static_cast<std::uint8_t>(*value);
}

}  // namespace

std::optional<Error> PiperOps::check_no_session_streams(std::string_view op) {
  ArmSnapshot snapshot = driver_.snapshot();
  if (!snapshot.link_up) {
    return make_error(ErrorCode::kNotAvailable, std::string(op) + ": the arm is not connected");
  }
  // robotd runs these ops with no session on the device and grants none meanwhile; one released a
  // moment ago may still own joints in the loop for a tick or two.
  const auto deadline = std::chrono::steady_clock::now() + kSessionEndWait;
  while (snapshot.any_owned && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(1ms);
    snapshot = driver_.snapshot();
  }
  if (snapshot.any_owned) {
    return make_error(ErrorCode::kRefused, std::string(op) +
                                               ": a session owns joints of this arm; release it first (the session "
                                               "streams joint targets and would fight the op)");
  }
  return std::nullopt;
}

std::optional<Error> PiperOps::take_arm_for(std::string_view op) {
  if (auto refused = check_no_session_streams(op)) return refused;
  if (driver_.snapshot().estop) {
    return make_error(ErrorCode::kRefused, std::string(op) + ": robotd's e-stop is engaged; reset it first");
  }
  driver_.hold_for_ops_.store(true, std::memory_order_release);
  return std::nullopt;
}

std::optional<Error> PiperOps::send_all(std::span<const CanMessage> frames) {
  for (const CanMessage& frame : frames) {
    if (driver_.send(frame) != transport::CanIo::kDone) {
      return make_error(ErrorCode::kTransport, "could not send on " + std::string(driver_.link_name_.data()));
    }
  }
  return std::nullopt;
}

Result<nlohmann::json> PiperOps::end_pose(const nlohmann::json& args) {
  OpArguments arguments("end_pose", args);
  JsonReader& reader = arguments.reader();
  const auto pose = OpArguments::pose(reader);
  const std::string motion = reader.string_or("motion", "p", {"p", "l"});
  const auto speed = reader.integer_or("speed_percent", driver_.params_.speed_percent, 1, 100);
  if (auto error = arguments.finish()) return *error;
  if (auto refused = take_arm_for("end_pose")) return *refused;
  const ModeControl mode{.move_mode = motion == "l" ? MoveMode::kL : MoveMode::kP,
                         .speed_percent = static_cast<std::uint8_t>(speed)};
  const auto targets = encode_end_pose_target(*pose);
  const std::array<CanMessage, 4> frames{encode(mode, driver_.codec_), targets[0], targets[1], targets[2]};
  if (auto failed = send_all(frames)) return *failed;
  return nlohmann::json{{"sent", "EndPoseCtrl"}, {"motion", motion}, {"pose", to_json(*pose)}};
}

Result<nlohmann::json> PiperOps::move_c(const nlohmann::json& args) {
  OpArguments arguments("move_c", args);
  JsonReader& reader = arguments.reader();
  std::array<std::optional<CartesianPose>, 3> poses;
  const std::array<const char*, 3> keys{"start", "middle", "end"};
  for (std::size_t i = 0; i < keys.size(); ++i) {
    reader.require(keys[i], "a pose {x_m, y_m, z_m, roll_rad, pitch_rad, yaw_rad}");
    if (auto pose_reader = reader.object(keys[i])) {
      poses[i] = OpArguments::pose(*pose_reader);
      pose_reader->finish();
    }
  }
  const auto speed = reader.integer_or("speed_percent", driver_.params_.speed_percent, 1, 100);
  if (auto error = arguments.finish()) return *error;
  if (auto refused = take_arm_for("move_c")) return *refused;
  const ModeControl mode{.move_mode = MoveMode::kC, .speed_percent = static_cast<std::uint8_t>(speed)};
  if (auto failed = send_all(std::array{encode(mode, driver_.codec_)})) return *failed;
  // Each point: its pose, then its index (spec §4.5); the SDK demo leaves ~1 ms between groups.
  for (std::size_t i = 0; i < poses.size(); ++i) {
    std::this_thread::sleep_for(1ms);
    if (auto failed = send_all(encode_end_pose_target(*poses[i]))) return *failed;
    const MoveCPoint point{.index = static_cast<std::uint8_t>(i + 1)};
    if (auto failed = send_all(std::array{encode(point, driver_.codec_)})) return *failed;
  }
  return nlohmann::json{{"sent", "MoveCAxisUpdateCtrl"},
                        {"start", to_json(*poses[0])},
                        {"middle", to_json(*poses[1])},
                        {"end", to_json(*poses[2])}};
}

Result<nlohmann::json> PiperOps::mode(const nlohmann::json& args) {
  OpArguments arguments("mode", args);
  JsonReader& reader = arguments.reader();
  const std::string ctrl = reader.string_or("ctrl_mode", "can", {"standby", "can", "ethernet", "wifi", "offline"});
  const std::string move = reader.string_or("move_mode", "j", {"p", "j", "l", "c", "mit", "cpv"});
  const auto speed = reader.integer_or("speed_percent", driver_.params_.speed_percent, 0, 100);
  const bool mit = reader.boolean_or("mit", move == "mit");
  const std::string installation =
      reader.string_or("installation", "unchanged", {"unchanged", "horizontal", "side_left", "side_right"});
  if (auto error = arguments.finish()) return *error;
  const ModeControl control{.ctrl_mode = *control_mode_named(ctrl),
                            .move_mode = *move_mode_named(move),
                            .speed_percent = static_cast<std::uint8_t>(speed),
                            .mit = mit,
                            .installation = installation_code(installation)};
  const auto frame = checked_encode("mode", control, driver_.codec_);
  if (!frame) return frame.error();
  if (auto refused = take_arm_for("mode")) return *refused;
  if (auto failed = send_all(std::array{frame.value()})) return *failed;
  return nlohmann::json{{"sent", "ModeCtrl"},     {"ctrl_mode", ctrl}, {"move_mode", move},
                        {"speed_percent", speed}, {"mit", mit},        {"installation", installation}};
}

Result<nlohmann::json> PiperOps::gripper(const nlohmann::json& args) {
  OpArguments arguments("gripper", args);
  JsonReader& reader = arguments.reader();
  const driver::JointLimits limits = [&] {  // narrowed at run time by sdk_gripper_range
    const std::lock_guard lock(driver_.limits_mutex_);
    return driver_.params_.gripper_joint.limits;
  }();
  const ArmSnapshot snapshot = driver_.snapshot();
  const double stroke = reader.number_or("stroke_m", snapshot.arm.gripper.stroke_m,
                                         NumberRange{.min = limits.position_min_rad, .max = limits.position_max_rad});
  const double effort =
      reader.number_or("effort_nm", driver_.params_.gripper_effort_nm, NumberRange{.min = 0, .max = 5});
  const bool enable = reader.boolean_or("enable", true);
  const bool clear_error = reader.boolean_or("clear_error", false);
  const bool set_zero = reader.boolean_or("set_zero", false);
  if (auto error = arguments.finish()) return *error;
  GripperEnable code = enable ? GripperEnable::kEnable : GripperEnable::kDisable;
  if (clear_error) code = enable ? GripperEnable::kEnableClearError : GripperEnable::kDisableClearError;
  const GripperControl control{.stroke_m = stroke, .effort_nm = effort, .enable = code, .set_zero = set_zero};
  const auto frame = checked_encode("gripper", control, driver_.codec_);
  if (!frame) return frame.error();
  if (auto refused = take_arm_for("gripper")) return *refused;
  if (auto failed = send_all(std::array{frame.value()})) return *failed;
  return nlohmann::json{{"sent", "GripperCtrl"}, {"stroke_m", stroke},         {"effort_nm", effort},
                        {"enable", enable},      {"clear_error", clear_error}, {"set_zero", set_zero}};
}

Result<nlohmann::json> PiperOps::enable(const nlohmann::json& args, bool on) {
  const char* op = on ? "enable" : "disable";
  OpArguments arguments(op, args);
  const auto joint = arguments.joint(/*allow_all=*/true);
  if (auto error = arguments.finish()) return *error;
  if (on) {
    // Streaming held off, a motor that powers up holds where it is instead of running to a
    // target robotd kept streaming while it was off.
    if (auto refused = take_arm_for(op)) return *refused;
    if (auto failed = send_all(std::array{encode(MotorEnable{.motor = *joint, .enable = true}, driver_.codec_)})) {
      return *failed;
    }
  } else if (auto refused = disable_now(*joint)) {
    return *refused;
  }
  // The enable bits come with the 40 Hz low-speed frames: report what they say a moment later.
  std::this_thread::sleep_for(100ms);
  const ArmSnapshot snapshot = driver_.snapshot();
  nlohmann::json enabled = nlohmann::json::array();
  for (const JointReport& report : snapshot.arm.joints) enabled.push_back(report.enabled());
  return nlohmann::json{{"sent", on ? "EnableArm" : "DisableArm"},
                        {"joint", *joint == kAllJoints ? nlohmann::json("all") : nlohmann::json(*joint)},
                        {"enabled", enabled}};
}

std::optional<Error> PiperOps::disable_now(std::uint8_t motor) {
  using Verdict = DisableOutcome::Verdict;
  if (auto refused = check_no_session_streams("disable")) return refused;
  if (!driver_.disable_.offer(DisableRequest{.motor = motor})) {
    return make_error(ErrorCode::kRefused, "disable: another disable is being decided; try again");
  }
  const auto outcome = driver_.disable_.await(std::chrono::milliseconds(driver_.params_.reply_timeout_ms));
  if (!outcome) {
    return make_error(ErrorCode::kNotAvailable, "disable: the control loop did not take the request within " +
                                                    std::to_string(driver_.params_.reply_timeout_ms) +
                                                    " ms (robotd pauses it during recover and reset_zero); nothing "
                                                    "was sent");
  }
  const std::string joint = "joint " + std::to_string(outcome->joint + 1);
  switch (outcome->verdict) {
    case Verdict::kSent:
      return std::nullopt;
    case Verdict::kEstop:
      return make_error(ErrorCode::kRefused, "disable: robotd's e-stop is engaged; reset it first");
    case Verdict::kOwned:
      return make_error(ErrorCode::kRefused, "disable: " + joint + " is held by a session; release it first");
    case Verdict::kHeld:
      return make_error(ErrorCode::kRefused,
                        "disable: robotd still holds " + joint +
                            " (the KEEP or DAMPING a session left it in), and disabled motors drop the arm; take the "
                            "arm with a session and release it with ZERO_TORQUE first");
    case Verdict::kNotSent:
      break;
  }
  return make_error(ErrorCode::kTransport, "disable: could not send on " + std::string(driver_.link_name_.data()));
}

Result<nlohmann::json> PiperOps::master_slave(const nlohmann::json& args) {
  OpArguments arguments("master_slave", args);
  JsonReader& reader = arguments.reader();
  reader.require("role", R"("master" (teach input) or "slave" (motion output))");
  const std::string role = reader.string_or("role", "slave", {"master", "slave"});
  MasterSlaveConfig config{.linkage = static_cast<std::uint8_t>(role == "master" ? 0xFA : 0xFC)};
  config.feedback_offset = id_offset(reader, "feedback_offset");
  config.control_offset = id_offset(reader, "control_offset");
  config.linkage_offset = id_offset(reader, "linkage_offset");
  if (auto error = arguments.finish()) return *error;
  const auto frame = checked_encode("master_slave", config, driver_.codec_);
  if (!frame) return frame.error();
  if (auto refused = take_arm_for("master_slave")) return *refused;
  if (auto failed = send_all(std::array{frame.value()})) return *failed;
  return nlohmann::json{
      {"sent", "MasterSlaveConfig"},
      {"role", role},
      {"feedback_offset", config.feedback_offset},
      {"control_offset", config.control_offset},
      {"linkage_offset", config.linkage_offset},
      {"note", role == "master" ? "the arm becomes a leader once restarted; a leader sends only its commands, "
                                  "which a device with params.role \"leader\" reads"
                                : "a leader becomes a follower only once restarted (piper_sdk "
                                  "demo/V2/README.MD); a follower sends feedback"}};
}

Result<nlohmann::json> PiperOps::master_home(const nlohmann::json& args) {
  OpArguments arguments("master_home", args);
  JsonReader& reader = arguments.reader();
  reader.require("mode", R"("restore_linkage", "leader_to_zero" or "both_to_zero")");
  const std::string mode =
      reader.string_or("mode", "restore_linkage", {"restore_linkage", "leader_to_zero", "both_to_zero"});
  if (auto error = arguments.finish()) return *error;
  const MasterArmHome request = mode == "leader_to_zero" ? MasterArmHome::kLeaderToZero
                                : mode == "both_to_zero" ? MasterArmHome::kBothToZero
                                                         : MasterArmHome::kRestoreLinkage;
  if (auto refused = take_arm_for("master_home")) return *refused;
  if (auto failed = send_all(std::array{encode(MasterArmHomeRequest{.mode = request}, driver_.codec_)})) return *failed;
  return nlohmann::json{{"sent", "ReqMasterArmMoveToHome"}, {"mode", mode}};
}

}  // namespace robotd::piper
