// The PiPER driver's "params" object, parsed and validated (docs/drivers/piper.md). Every error
// names its key path relative to params.
#pragma once

#include <array>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "codec/piper_frames.hpp"
#include "kinematics/piper_kinematics.hpp"
#include "robotd/driver/driver.hpp"
#include "robotd/result.hpp"
#include "robotd/transport/can_transport.hpp"

namespace robotd::piper {

enum class EnablePolicy : std::uint8_t {
  kOnSession,  // 0x471 enable when a session first owns a joint
  kOnConnect,  // enable as soon as the link is up
  kManual,     // only through the "enable" op
};

/// What the arm is on its CAN bus (MasterSlaveConfig 0x470 byte 0, set on the arm beforehand).
enum class ArmRole : std::uint8_t {
  kFollower,  // 0xFC, the arm's default: streams feedback, takes commands; robotd drives it
  kLeader,    // 0xFA, teach input: sends only its control frames; robotd reads them, sends nothing
};

struct PiperJointParams {
  std::string name;
  driver::JointLimits limits;
  double default_kp = 10.0;  // MIT gains for POSITION commands in MIT mode and for DAMPING
  double default_kd = 0.8;
  double mit_torque_scale = 1.0;  // wire torque per N·m (the arm executes 4× on J1–J3: 0.25)
  double effort_nm_per_a = 0.0;   // feedback effort = motor current × this
};

struct PiperParams {
  std::string model = "AgileX PiPER";
  ArmRole role = ArmRole::kFollower;
  transport::CanLinkConfig can;
  bool check_interface = true;   // the SDK's judge_flag: interface up at 1 Mbit/s (SocketCAN only)
  int connect_timeout_ms = 500;  // arm feedback must arrive this soon after opening the link
  // No 0x2A1 or 0x2A5–0x2A7 this long: the link is lost. Below robotd's feedback_timeout_ms
  // (100 ms), so that the driver names and reconnects a silent arm before the loop's generic
  // "no feedback" fault fires on the same tick.
  int feedback_timeout_ms = 50;
  int reply_timeout_ms = 500;     // queries and settings wait this long for the arm's answer
  double command_rate_hz = 200;   // joint command groups per second on the bus
  int speed_percent = 100;        // 0x151 byte 2 for MOVE J streaming
  bool high_follow = false;       // 0x151 byte 3 = 0xAD with MOVE J: track without the arm's planner
  std::string firmware = "auto";  // "auto" (ask with 0x4AF) or a version such as "S-V1.8-2"
  DhVariant dh = DhVariant::kOffset;
  EnablePolicy enable = EnablePolicy::kOnSession;
  bool disable_on_release = false;  // 0x471 disable when the last session ends (the arm drops!)
  bool gripper = true;              // the gripper is joint 7, "gripper", in metres
  double gripper_effort_nm = 1.0;   // gripping torque when a command carries none
  CodecOptions codec;               // mit_layout comes from `firmware`; the id offsets from their params
  std::array<PiperJointParams, kArmJoints> joints;
  PiperJointParams gripper_joint;

  bool leader() const { return role == ArmRole::kLeader; }
  std::size_t joint_count() const { return kArmJoints + (gripper ? 1 : 0); }
  const PiperJointParams& joint(std::size_t index) const { return index < kArmJoints ? joints[index] : gripper_joint; }
};

/// The SDK's limits (spec §8) as defaults, overridden by "joints": {"joint3": {...}, "gripper": {...}}.
Result<PiperParams> parse_piper_params(const nlohmann::json& params);

}  // namespace robotd::piper
