#include "controller.hpp"

#include <utility>
#include <variant>

#include "firmware_info.hpp"

namespace robotd::piper::sim {
namespace {

// 0x476 byte 0: the low byte of the acknowledged command's id.
constexpr std::uint8_t kAckJointLimitSet = 0x74;
constexpr std::uint8_t kAckJointConfig = 0x75;
constexpr std::uint8_t kAckParamSetting = 0x77;
constexpr std::uint8_t kAckEndVelAcc = 0x79;
constexpr std::uint8_t kAckCrashProtection = 0x7A;
constexpr std::uint8_t kAckTrajectoryPoint = 0x50;
constexpr std::uint8_t kTrajectoryTransfer = 0x07;  // 0x150 byte 1

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

}  // namespace

Controller::Controller(ArmModel& arm, const CodecOptions& codec, std::string software_version)
    : arm_(arm), codec_(codec), software_version_(std::move(software_version)) {}

void Controller::handle(const CanMessage& message, std::vector<CanMessage>& replies) {
  if (message.id == can_id::kFirmware && !message.extended) {
    // The request decodes as a FirmwareChunk like the reply does: tell them apart first.
    if (is_firmware_request(message)) {
      for (const CanMessage& frame : firmware_reply(software_version_, codec_)) replies.push_back(frame);
    }
    return;
  }
  const std::optional<Frame> frame = decode(message, codec_);
  if (!frame) return;  // unknown id, short payload, bad MIT CRC: the arm ignores it
  std::visit(
      Overloaded{
          [&](const MotionControl& f) {
            arm_.motion_control(f);
            if (f.track_ctrl == kTrajectoryTransfer) {  // trajectory point upload: ack with its index
              SetAck reply;
              reply.command = kAckTrajectoryPoint;
              reply.trajectory_index = f.trajectory_index;
              replies.push_back(encode(reply, codec_));
            }
          },
          [&](const ModeControl& f) { arm_.mode_control(f); },
          [&](const EndPoseTargetPart& f) { arm_.end_pose_target(f); },
          [&](const JointTargetPair& f) { arm_.joint_target(f); }, [&](const MoveCPoint& f) { arm_.move_c_point(f); },
          [&](const GripperControl& f) { arm_.gripper_control(f); }, [&](const MitControl& f) { arm_.mit_control(f); },
          // No ack (spec §7); the arm takes it at its next start (Simulator::restart).
          [&](const MasterSlaveConfig& f) { arm_.settings().master_slave = f; },
          [&](const MasterArmHomeRequest&) {},                  // for a leader arm; the simulated arm is a follower
          [&](const MotorEnable& f) { arm_.motor_enable(f); },  // no ack (spec §7)
          [&](const JointLimitQuery& f) { answer_joint_limit_query(f, replies); },
          [&](const JointLimitSet& f) {
            if (arm_.joint_limit_set(f)) ack(kAckJointLimitSet, false, replies);
          },
          [&](const JointConfig& f) {
            if (const auto zero_set = arm_.joint_config(f)) ack(kAckJointConfig, *zero_set, replies);
          },
          [&](const ParamEnquiry& f) { answer_param_enquiry(f, replies); },
          [&](const EndVelAccSet& f) {
            EndVelAcc& limits = arm_.settings().end_limits;
            const EndVelAcc& set = f.values;  // nullopt: 0x7FFF, leave the value as it is
            if (set.max_linear_velocity_m_s) limits.max_linear_velocity_m_s = set.max_linear_velocity_m_s;
            if (set.max_angular_velocity_rad_s) {
              limits.max_angular_velocity_rad_s = set.max_angular_velocity_rad_s;
            }
            if (set.max_linear_acceleration_m_s2) {
              limits.max_linear_acceleration_m_s2 = set.max_linear_acceleration_m_s2;
            }
            if (set.max_angular_acceleration_rad_s2) {
              limits.max_angular_acceleration_rad_s2 = set.max_angular_acceleration_rad_s2;
            }
            ack(kAckEndVelAcc, false, replies);
          },
          [&](const CrashProtectionSet& f) {
            arm_.settings().collision_levels = f.levels;
            ack(kAckCrashProtection, false, replies);
          },
          [&](const GripperParamSet& f) { arm_.settings().gripper = f.params; },  // no ack (spec §7)
          [](const auto&) {},  // the arm's own frames, seen from another node
      },
      *frame);
}

void Controller::answer_joint_limit_query(const JointLimitQuery& query, std::vector<CanMessage>& replies) const {
  if (query.joint < 1 || query.joint > kArmJoints) return;
  const JointSettings& settings = arm_.settings().joints.at(query.joint - 1U);
  if (query.acceleration) {
    JointAccReply reply;
    reply.joint = query.joint;
    reply.max_acc_rad_s2 = settings.max_acc_rad_s2;
    replies.push_back(encode(reply, codec_));
    return;
  }
  JointLimitReply reply;
  reply.joint = query.joint;
  reply.max_angle_rad = settings.max_rad;
  reply.min_angle_rad = settings.min_rad;
  reply.max_speed_rad_s = settings.max_speed_rad_s;
  replies.push_back(encode(reply, codec_));
}

void Controller::answer_param_enquiry(const ParamEnquiry& enquiry, std::vector<CanMessage>& replies) {
  ArmSettings& settings = arm_.settings();
  bool changed = false;
  if (enquiry.setting == 1 || enquiry.setting == 2) {
    arm_.reset_settings(enquiry.setting);
    changed = true;
  }
  if (enquiry.feedback_48x == 1 || enquiry.feedback_48x == 2) {
    settings.feedback_48x = enquiry.feedback_48x;
    changed = true;
  }
  if (enquiry.payload) {
    settings.payload = *enquiry.payload;
    changed = true;
  }
  if (changed) ack(kAckParamSetting, false, replies);
  switch (enquiry.query) {
    case 1: {
      EndVelAccReply reply;
      reply.values = settings.end_limits;
      replies.push_back(encode(reply, codec_));
      break;
    }
    case 2: {
      CrashProtectionReply reply;
      reply.levels = settings.collision_levels;
      replies.push_back(encode(reply, codec_));
      break;
    }
    case 4: {
      GripperParamReply reply;
      reply.params = settings.gripper;
      replies.push_back(encode(reply, codec_));
      break;
    }
    default:  // 3 (trajectory index) and 5 (0x488) have no published reply layout
      break;
  }
}

void Controller::ack(std::uint8_t command, bool zero_set, std::vector<CanMessage>& replies) const {
  SetAck reply;
  reply.command = command;
  reply.zero_set = zero_set;
  replies.push_back(encode(reply, codec_));
}

}  // namespace robotd::piper::sim
