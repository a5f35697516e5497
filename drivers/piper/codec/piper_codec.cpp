// Encoding and decoding of the PiPER frames of piper_frames.hpp: byte layouts per
// piper_can.md §4–§6, through the primitives of wire_scaling.hpp.
#include <algorithm>
#include <array>
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>

#include "piper_frames.hpp"
#include "wire_scaling.hpp"

namespace robotd::piper {
namespace {

using wire::get_i16;
using wire::get_i32;
using wire::get_u16;
using wire::Payload;
using wire::put_i16;
using wire::put_i32;
using wire::put_u16;
using wire::saturate;

constexpr std::uint8_t kMitCode8 = 0x04;   // MIT move mode, firmware ≤ S-V1.8-7
constexpr std::uint8_t kMitCode12 = 0x06;  // MIT move mode, firmware ≥ S-V1.8-8
constexpr std::uint8_t kMotorOn = 0x02;    // 0x471 byte 1
constexpr std::uint8_t kMotorOff = 0x01;
constexpr std::uint8_t kQueryLimits = 0x01;  // 0x472 byte 1
constexpr std::uint8_t kQueryAcc = 0x02;
constexpr std::uint8_t kPayloadUnset = 0x03;  // 0x477 byte 4 when no payload is set (SDK default)
constexpr std::uint8_t kZeroSetDone = 0x01;   // 0x476 byte 1
constexpr std::size_t kFrameBytes = 8;
constexpr std::uint8_t kMasterHomeRequest = 0x01;  // 0x191 byte 0

/// 0x191 bytes 1 and 2 for each mode (SDK ReqMasterArmMoveToHome).
std::array<std::uint8_t, 2> master_home_bytes(MasterArmHome mode) {
  switch (mode) {
    case MasterArmHome::kRestoreLinkage:
      return {0x00, 0x00};
    case MasterArmHome::kLeaderToZero:
      return {0x01, 0x01};
    case MasterArmHome::kBothToZero:
      return {0x00, 0x01};
  }
  throw std::invalid_argument("0x191 master-arm home mode " + std::to_string(static_cast<int>(mode)) +
                              " is not one of 0 (restore linkage), 1 (leader to zero), 2 (both to zero)");
}

constexpr wire::MitRange kMitPosition{.min = -12.5, .max = 12.5, .bits = 16};
constexpr wire::MitRange kMitVelocity{.min = -45.0, .max = 45.0, .bits = 12};
constexpr wire::MitRange kMitKp{.min = 0.0, .max = 500.0, .bits = 12};
constexpr wire::MitRange kMitKd{.min = -5.0, .max = 5.0, .bits = 12};
constexpr wire::MitRange kMitTorque8{.min = -8.0, .max = 8.0, .bits = 8};
constexpr wire::MitRange kMitTorque12{.min = -16.0, .max = 16.0, .bits = 12};

constexpr std::uint8_t byte(std::uint32_t value) { return static_cast<std::uint8_t>(value & 0xFFU); }
constexpr std::uint8_t flag(bool set, std::uint8_t code) { return set ? code : std::uint8_t{0}; }

CanMessage message_for(std::uint32_t id) {
  CanMessage message;
  message.id = id;
  message.length = kFrameBytes;
  return message;
}

/// Id `base + index` with the index saturated into [0, count): a bad index still names a frame
/// of the right kind.
std::uint32_t indexed_id(std::uint32_t base, int index, int count) {
  return base + static_cast<std::uint32_t>(std::clamp(index, 0, count - 1));
}

std::int32_t milli_degrees(double rad) { return saturate<std::int32_t>(rad * wire::kMilliDegPerRad); }
double from_milli_degrees(std::int32_t counts) { return counts / wire::kMilliDegPerRad; }
std::int32_t micrometres(double m) { return saturate<std::int32_t>(m * wire::kMicrometresPerMetre); }
double from_micrometres(std::int32_t counts) { return counts / wire::kMicrometresPerMetre; }
std::int16_t deci_degrees(double rad) { return saturate<std::int16_t>(rad * wire::kDeciDegPerRad); }
double from_deci_degrees(std::int16_t counts) { return counts / wire::kDeciDegPerRad; }
std::uint16_t unsigned_counts(double value, double unit) { return saturate<std::uint16_t>(value / unit); }
std::int16_t signed_counts(double value, double unit) { return saturate<std::int16_t>(value / unit); }

// Fields with the 0x7FFF "leave unchanged" sentinel. A present value uses the whole field, as the
// SDK sends it (EndSpdAndAccParamSet 65535 goes out as FF FF).
constexpr auto kUnchangedSigned = static_cast<std::int16_t>(kUnchanged);

std::uint16_t unsigned_or_unchanged(const std::optional<double>& value, double unit) {
  if (!value) return kUnchanged;
  return unsigned_counts(*value, unit);
}
std::int16_t deci_degrees_or_unchanged(const std::optional<double>& rad) {
  if (!rad) return kUnchangedSigned;
  return deci_degrees(*rad);
}
std::optional<double> unless_unchanged(std::uint16_t counts, double unit) {
  if (counts == kUnchanged) return std::nullopt;
  return counts * unit;
}
std::optional<double> deci_degrees_unless_unchanged(std::int16_t counts) {
  if (counts == kUnchangedSigned) return std::nullopt;
  return from_deci_degrees(counts);
}

std::uint8_t move_mode_code(MoveMode mode, MitLayout layout) {
  if (mode != MoveMode::kMit) return static_cast<std::uint8_t>(mode);
  return layout == MitLayout::kTorque12 ? kMitCode12 : kMitCode8;
}
/// The SDK 0.6.1 reads 0x04 as MIT and 0x06 as unknown; firmware from S-V1.8-8 moved MIT to 0x06.
MoveMode move_mode_of(std::uint8_t code, MitLayout layout) {
  const std::uint8_t mit_code = layout == MitLayout::kTorque12 ? kMitCode12 : kMitCode8;
  if (code == mit_code) return MoveMode::kMit;
  if (code == kMitCode8 || code > static_cast<std::uint8_t>(MoveMode::kCpv)) return MoveMode::kUnknown;
  return static_cast<MoveMode>(code);
}

std::uint8_t mit_crc(const Payload& data) {
  std::uint8_t crc = 0;
  for (std::size_t i = 0; i < 7; ++i) crc ^= data[i];
  return crc & 0x0FU;
}

// 0x152–0x154 and 0x2A2–0x2A4 carry x, y | z, rx | ry, rz: slots 0–2 are lengths, 3–5 angles.
std::int32_t pose_counts(double value, int slot) { return slot < 3 ? micrometres(value) : milli_degrees(value); }
double pose_value(std::int32_t counts, int slot) {
  return slot < 3 ? from_micrometres(counts) : from_milli_degrees(counts);
}

template <typename Part>
CanMessage encode_pose_part(std::uint32_t base, const Part& part) {
  const int index = std::clamp(part.part, 0, 2);
  CanMessage message = message_for(base + static_cast<std::uint32_t>(index));
  put_i32(message.data, 0, pose_counts(part.first, 2 * index));
  put_i32(message.data, 4, pose_counts(part.second, 2 * index + 1));
  return message;
}

template <typename Part>
std::optional<Frame> decode_pose_part(const CanMessage& message, std::uint32_t base) {
  const int index = static_cast<int>(message.id - base);
  return Part{.part = index,
              .first = pose_value(get_i32(message.data, 0), 2 * index),
              .second = pose_value(get_i32(message.data, 4), 2 * index + 1)};
}

template <typename Pair>
CanMessage encode_joint_pair(std::uint32_t base, const Pair& pair) {
  CanMessage message = message_for(indexed_id(base, pair.pair, 3));
  put_i32(message.data, 0, milli_degrees(pair.first_rad));
  put_i32(message.data, 4, milli_degrees(pair.second_rad));
  return message;
}

template <typename Pair>
std::optional<Frame> decode_joint_pair(const CanMessage& message, std::uint32_t base) {
  return Pair{.pair = static_cast<int>(message.id - base),
              .first_rad = from_milli_degrees(get_i32(message.data, 0)),
              .second_rad = from_milli_degrees(get_i32(message.data, 4))};
}

// 0x478 and 0x479 share four uint16 fields in kEndLimitUnit, 0x7FFF meaning "none".

void put_end_vel_acc(Payload& data, const EndVelAcc& values) {
  put_u16(data, 0, unsigned_or_unchanged(values.max_linear_velocity_m_s, kEndLimitUnit));
  put_u16(data, 2, unsigned_or_unchanged(values.max_angular_velocity_rad_s, kEndLimitUnit));
  put_u16(data, 4, unsigned_or_unchanged(values.max_linear_acceleration_m_s2, kEndLimitUnit));
  put_u16(data, 6, unsigned_or_unchanged(values.max_angular_acceleration_rad_s2, kEndLimitUnit));
}

EndVelAcc get_end_vel_acc(const Payload& data) {
  return EndVelAcc{.max_linear_velocity_m_s = unless_unchanged(get_u16(data, 0), kEndLimitUnit),
                   .max_angular_velocity_rad_s = unless_unchanged(get_u16(data, 2), kEndLimitUnit),
                   .max_linear_acceleration_m_s2 = unless_unchanged(get_u16(data, 4), kEndLimitUnit),
                   .max_angular_acceleration_rad_s2 = unless_unchanged(get_u16(data, 6), kEndLimitUnit)};
}

template <typename Levels>
CanMessage encode_levels(std::uint32_t id, const Levels& frame_levels) {
  CanMessage message = message_for(id);
  std::ranges::copy(frame_levels.levels, message.data.begin());
  return message;
}

template <typename Levels>
std::optional<Frame> decode_levels(const CanMessage& message) {
  Levels levels;
  std::copy_n(message.data.begin(), kArmJoints, levels.levels.begin());
  return levels;
}

template <typename Params>
CanMessage encode_gripper_params(std::uint32_t id, const Params& params) {
  CanMessage message = message_for(id);
  message.data[0] = params.params.teaching_range_percent;
  message.data[1] = params.params.max_range_mm;
  message.data[2] = params.params.teaching_friction;
  return message;
}

template <typename Params>
std::optional<Frame> decode_gripper_params(const CanMessage& message) {
  return Params{.params = GripperParams{.teaching_range_percent = message.data[0],
                                        .max_range_mm = message.data[1],
                                        .teaching_friction = message.data[2]}};
}

// --- decoders: called only with a standard frame of the id and at least the length the table
// below gives them.

std::optional<Frame> decode_motion_control(const CanMessage& message, const CodecOptions& /*options*/) {
  const Payload& data = message.data;
  return MotionControl{.emergency_stop = static_cast<EmergencyStop>(data[0]),
                       .track_ctrl = data[1],
                       .drag_teach_ctrl = data[2],
                       .trajectory_index = data[3],
                       .name_index = get_u16(data, 4),
                       .crc16 = get_u16(data, 6)};
}

std::optional<Frame> decode_mode_control(const CanMessage& message, const CodecOptions& options) {
  const Payload& data = message.data;
  return ModeControl{.ctrl_mode = static_cast<ControlMode>(data[0]),
                     .move_mode = move_mode_of(data[1], options.mit_layout),
                     .speed_percent = data[2],
                     .mit = data[3] == kMitFlag,
                     .residence_time_s = data[4],
                     .installation = data[5]};
}

std::optional<Frame> decode_end_pose_target(const CanMessage& message, const CodecOptions& /*options*/) {
  return decode_pose_part<EndPoseTargetPart>(message, can_id::kEndPoseTarget);
}

std::optional<Frame> decode_joint_target(const CanMessage& message, const CodecOptions& /*options*/) {
  return decode_joint_pair<JointTargetPair>(message, can_id::kJointTarget);
}

std::optional<Frame> decode_move_c_point(const CanMessage& message, const CodecOptions& /*options*/) {
  return MoveCPoint{.index = message.data[0]};
}

std::optional<Frame> decode_gripper_control(const CanMessage& message, const CodecOptions& /*options*/) {
  const Payload& data = message.data;
  return GripperControl{.stroke_m = from_micrometres(get_i32(data, 0)),
                        .effort_nm = get_u16(data, 4) * 0.001,
                        .enable = static_cast<GripperEnable>(data[6]),
                        .set_zero = data[7] == kMagic};
}

std::optional<Frame> decode_mit_control(const CanMessage& message, const CodecOptions& options) {
  const bool wide = options.mit_layout == MitLayout::kTorque12;
  if (!wide && (message.data[7] & 0x0FU) != mit_crc(message.data)) return std::nullopt;
  const auto at = [&message](std::size_t i) { return std::uint32_t{message.data[i]}; };
  const std::uint32_t position = (at(0) << 8) | at(1);
  const std::uint32_t velocity = (at(2) << 4) | (at(3) >> 4);
  const std::uint32_t kp = ((at(3) & 0x0FU) << 8) | at(4);
  const std::uint32_t kd = (at(5) << 4) | (at(6) >> 4);
  const std::uint32_t torque = wide ? ((at(6) & 0x0FU) << 8) | at(7) : ((at(6) & 0x0FU) << 4) | (at(7) >> 4);
  return MitControl{.joint = static_cast<int>(message.id - can_id::kMitControl) + 1,
                    .position_rad = wire::mit_value(position, kMitPosition),
                    .velocity_rad_s = wire::mit_value(velocity, kMitVelocity),
                    .kp = wire::mit_value(kp, kMitKp),
                    .kd = wire::mit_value(kd, kMitKd),
                    .torque = wire::mit_value(torque, wide ? kMitTorque12 : kMitTorque8)};
}

std::optional<Frame> decode_master_slave(const CanMessage& message, const CodecOptions& /*options*/) {
  const Payload& data = message.data;
  return MasterSlaveConfig{
      .linkage = data[0], .feedback_offset = data[1], .control_offset = data[2], .linkage_offset = data[3]};
}

std::optional<Frame> decode_master_arm_home(const CanMessage& message, const CodecOptions& /*options*/) {
  const Payload& data = message.data;
  if (data[0] != kMasterHomeRequest) return std::nullopt;
  for (const MasterArmHome mode :
       {MasterArmHome::kRestoreLinkage, MasterArmHome::kLeaderToZero, MasterArmHome::kBothToZero}) {
    const auto bytes = master_home_bytes(mode);
    if (data[1] == bytes[0] && data[2] == bytes[1]) return MasterArmHomeRequest{.mode = mode};
  }
  return std::nullopt;
}

std::optional<Frame> decode_motor_enable(const CanMessage& message, const CodecOptions& /*options*/) {
  return MotorEnable{.motor = message.data[0], .enable = message.data[1] == kMotorOn};
}

std::optional<Frame> decode_joint_limit_query(const CanMessage& message, const CodecOptions& /*options*/) {
  return JointLimitQuery{.joint = message.data[0], .acceleration = message.data[1] == kQueryAcc};
}

std::optional<Frame> decode_joint_limit_reply(const CanMessage& message, const CodecOptions& options) {
  const Payload& data = message.data;
  return JointLimitReply{.joint = data[0],
                         .max_angle_rad = from_deci_degrees(get_i16(data, 1)),
                         .min_angle_rad = from_deci_degrees(get_i16(data, 3)),
                         .max_speed_rad_s = get_u16(data, 5) * options.max_speed_unit_rad_s};
}

std::optional<Frame> decode_joint_limit_set(const CanMessage& message, const CodecOptions& options) {
  const Payload& data = message.data;
  return JointLimitSet{.joint = data[0],
                       .max_angle_rad = deci_degrees_unless_unchanged(get_i16(data, 1)),
                       .min_angle_rad = deci_degrees_unless_unchanged(get_i16(data, 3)),
                       .max_speed_rad_s = unless_unchanged(get_u16(data, 5), options.max_speed_unit_rad_s)};
}

std::optional<Frame> decode_joint_config(const CanMessage& message, const CodecOptions& options) {
  const Payload& data = message.data;
  return JointConfig{.joint = data[0],
                     .set_zero = data[1] == kMagic,
                     .apply_max_acc = data[2] == kMagic,
                     .max_acc_rad_s2 = get_u16(data, 3) * options.max_acc_unit_rad_s2,
                     .clear_error = data[5] == kMagic};
}

std::optional<Frame> decode_set_ack(const CanMessage& message, const CodecOptions& /*options*/) {
  const Payload& data = message.data;
  return SetAck{.command = data[0], .zero_set = data[1] == kZeroSetDone, .trajectory_index = data[2]};
}

std::optional<Frame> decode_param_enquiry(const CanMessage& message, const CodecOptions& /*options*/) {
  const Payload& data = message.data;
  ParamEnquiry enquiry{.query = data[0], .setting = data[1], .feedback_48x = data[2]};
  if (data[3] == kMagic) enquiry.payload = data[4];
  return enquiry;
}

std::optional<Frame> decode_end_vel_acc_reply(const CanMessage& message, const CodecOptions& /*options*/) {
  return EndVelAccReply{.values = get_end_vel_acc(message.data)};
}

std::optional<Frame> decode_end_vel_acc_set(const CanMessage& message, const CodecOptions& /*options*/) {
  return EndVelAccSet{.values = get_end_vel_acc(message.data)};
}

std::optional<Frame> decode_crash_set(const CanMessage& message, const CodecOptions& /*options*/) {
  return decode_levels<CrashProtectionSet>(message);
}

std::optional<Frame> decode_crash_reply(const CanMessage& message, const CodecOptions& /*options*/) {
  return decode_levels<CrashProtectionReply>(message);
}

std::optional<Frame> decode_joint_acc_reply(const CanMessage& message, const CodecOptions& options) {
  return JointAccReply{.joint = message.data[0],
                       .max_acc_rad_s2 = get_u16(message.data, 1) * options.max_acc_unit_rad_s2};
}

std::optional<Frame> decode_gripper_param_set(const CanMessage& message, const CodecOptions& /*options*/) {
  return decode_gripper_params<GripperParamSet>(message);
}

std::optional<Frame> decode_gripper_param_reply(const CanMessage& message, const CodecOptions& /*options*/) {
  return decode_gripper_params<GripperParamReply>(message);
}

std::optional<Frame> decode_firmware(const CanMessage& message, const CodecOptions& /*options*/) {
  FirmwareChunk chunk;
  chunk.length = static_cast<std::uint8_t>(std::min<std::size_t>(message.length, kFrameBytes));
  std::copy_n(message.data.begin(), chunk.length, chunk.text.begin());
  return chunk;
}

std::optional<Frame> decode_arm_status(const CanMessage& message, const CodecOptions& options) {
  const Payload& data = message.data;
  return ArmStatus{.ctrl_mode = static_cast<ControlMode>(data[0]),
                   .arm_status = data[1],
                   .mode_feed = move_mode_of(data[2], options.mit_layout),
                   .teach_status = data[3],
                   .motion_status = data[4],
                   .trajectory_index = data[5],
                   .angle_limit_bits = data[6],
                   .comm_error_bits = data[7]};
}

std::optional<Frame> decode_end_pose_feedback(const CanMessage& message, const CodecOptions& /*options*/) {
  return decode_pose_part<EndPoseFeedbackPart>(message, can_id::kEndPoseFeedback);
}

std::optional<Frame> decode_joint_feedback(const CanMessage& message, const CodecOptions& /*options*/) {
  return decode_joint_pair<JointFeedbackPair>(message, can_id::kJointFeedback);
}

std::optional<Frame> decode_gripper_feedback(const CanMessage& message, const CodecOptions& /*options*/) {
  const Payload& data = message.data;
  return GripperFeedback{.stroke_m = from_micrometres(get_i32(data, 0)),
                         .effort_nm = get_i16(data, 4) * 0.001,
                         .status_bits = data[6],
                         .reserved = data[7]};
}

std::optional<Frame> decode_high_speed(const CanMessage& message, const CodecOptions& options) {
  const Payload& data = message.data;
  return HighSpeedInfo{.joint = static_cast<int>(message.id - can_id::kHighSpeedInfo) + 1,
                       .speed_rad_s = get_i16(data, 0) * 0.001,
                       .current_a = get_i16(data, 2) * 0.001,
                       .position_rad = get_i32(data, 4) * options.motor_position_unit_rad};
}

std::optional<Frame> decode_low_speed(const CanMessage& message, const CodecOptions& /*options*/) {
  const Payload& data = message.data;
  return LowSpeedInfo{.joint = static_cast<int>(message.id - can_id::kLowSpeedInfo) + 1,
                      .voltage_v = get_u16(data, 0) * 0.1,
                      .driver_temperature_c = get_i16(data, 2),
                      .motor_temperature_c = static_cast<std::int8_t>(data[4]),
                      .status_bits = data[5],
                      .bus_current_a = get_u16(data, 6) * 0.001};
}

struct FrameDecoder {
  std::uint32_t first_id;
  std::uint32_t last_id;
  std::uint8_t length;  // payload bytes up to the frame's last field (trailing reserved bytes may be cut)
  std::optional<Frame> (*decode)(const CanMessage&, const CodecOptions&);
};

constexpr std::uint32_t kJointIds = kArmJoints - 1;  // last id − first id of a per-joint frame

constexpr std::array kDecoders{
    FrameDecoder{can_id::kMotionControl, can_id::kMotionControl, 8, decode_motion_control},
    FrameDecoder{can_id::kModeControl, can_id::kModeControl, 6, decode_mode_control},
    FrameDecoder{can_id::kEndPoseTarget, can_id::kEndPoseTarget + 2, 8, decode_end_pose_target},
    FrameDecoder{can_id::kJointTarget, can_id::kJointTarget + 2, 8, decode_joint_target},
    FrameDecoder{can_id::kMoveCPoint, can_id::kMoveCPoint, 1, decode_move_c_point},
    FrameDecoder{can_id::kGripperControl, can_id::kGripperControl, 8, decode_gripper_control},
    FrameDecoder{can_id::kMitControl, can_id::kMitControl + kJointIds, 8, decode_mit_control},
    FrameDecoder{can_id::kMasterSlaveConfig, can_id::kMasterSlaveConfig, 4, decode_master_slave},
    FrameDecoder{can_id::kMasterArmHome, can_id::kMasterArmHome, 3, decode_master_arm_home},
    FrameDecoder{can_id::kMotorEnable, can_id::kMotorEnable, 2, decode_motor_enable},
    FrameDecoder{can_id::kJointLimitQuery, can_id::kJointLimitQuery, 2, decode_joint_limit_query},
    FrameDecoder{can_id::kJointLimitReply, can_id::kJointLimitReply, 7, decode_joint_limit_reply},
    FrameDecoder{can_id::kJointLimitSet, can_id::kJointLimitSet, 7, decode_joint_limit_set},
    FrameDecoder{can_id::kJointConfig, can_id::kJointConfig, 6, decode_joint_config},
    FrameDecoder{can_id::kSetAck, can_id::kSetAck, 3, decode_set_ack},
    FrameDecoder{can_id::kParamEnquiry, can_id::kParamEnquiry, 5, decode_param_enquiry},
    FrameDecoder{can_id::kEndVelAccReply, can_id::kEndVelAccReply, 8, decode_end_vel_acc_reply},
    FrameDecoder{can_id::kEndVelAccSet, can_id::kEndVelAccSet, 8, decode_end_vel_acc_set},
    FrameDecoder{can_id::kCrashProtectionSet, can_id::kCrashProtectionSet, kArmJoints, decode_crash_set},
    FrameDecoder{can_id::kCrashProtectionReply, can_id::kCrashProtectionReply, kArmJoints, decode_crash_reply},
    FrameDecoder{can_id::kJointAccReply, can_id::kJointAccReply, 3, decode_joint_acc_reply},
    FrameDecoder{can_id::kGripperParamSet, can_id::kGripperParamSet, 3, decode_gripper_param_set},
    FrameDecoder{can_id::kGripperParamReply, can_id::kGripperParamReply, 3, decode_gripper_param_reply},
    FrameDecoder{can_id::kFirmware, can_id::kFirmware, 1, decode_firmware},
    FrameDecoder{can_id::kArmStatus, can_id::kArmStatus, 8, decode_arm_status},
    FrameDecoder{can_id::kEndPoseFeedback, can_id::kEndPoseFeedback + 2, 8, decode_end_pose_feedback},
    FrameDecoder{can_id::kJointFeedback, can_id::kJointFeedback + 2, 8, decode_joint_feedback},
    FrameDecoder{can_id::kGripperFeedback, can_id::kGripperFeedback, 8, decode_gripper_feedback},
    FrameDecoder{can_id::kHighSpeedInfo, can_id::kHighSpeedInfo + kJointIds, 8, decode_high_speed},
    FrameDecoder{can_id::kLowSpeedInfo, can_id::kLowSpeedInfo + kJointIds, 8, decode_low_speed},
};

/// The decimal number at the front of `text`, which it consumes.
std::optional<unsigned> take_number(std::string_view& text) {
  unsigned value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc{}) return std::nullopt;
  text.remove_prefix(static_cast<std::size_t>(end - text.data()));
  return value;
}

bool take(std::string_view& text, std::string_view prefix) {
  if (!text.starts_with(prefix)) return false;
  text.remove_prefix(prefix.size());
  return true;
}

}  // namespace

CanMessage encode(const MotionControl& frame, const CodecOptions& /*options*/) {
  CanMessage message = message_for(can_id::kMotionControl);
  message.data[0] = static_cast<std::uint8_t>(frame.emergency_stop);
  message.data[1] = frame.track_ctrl;
  message.data[2] = frame.drag_teach_ctrl;
  message.data[3] = frame.trajectory_index;
  put_u16(message.data, 4, frame.name_index);
  put_u16(message.data, 6, frame.crc16);
  return message;
}

CanMessage encode(const ModeControl& frame, const CodecOptions& options) {
  CanMessage message = message_for(can_id::kModeControl);
  message.data[0] = static_cast<std::uint8_t>(frame.ctrl_mode);
  message.data[1] = move_mode_code(frame.move_mode, options.mit_layout);
  message.data[2] = frame.speed_percent;
  message.data[3] = flag(frame.mit, kMitFlag);
  message.data[4] = frame.residence_time_s;
  message.data[5] = frame.installation;
  return message;
}

CanMessage encode(const EndPoseTargetPart& frame, const CodecOptions& /*options*/) {
  return encode_pose_part(can_id::kEndPoseTarget, frame);
}

CanMessage encode(const JointTargetPair& frame, const CodecOptions& /*options*/) {
  return encode_joint_pair(can_id::kJointTarget, frame);
}

CanMessage encode(const MoveCPoint& frame, const CodecOptions& /*options*/) {
  CanMessage message = message_for(can_id::kMoveCPoint);
  message.data[0] = frame.index;
  return message;
}

CanMessage encode(const GripperControl& frame, const CodecOptions& /*options*/) {
  CanMessage message = message_for(can_id::kGripperControl);
  put_i32(message.data, 0, micrometres(frame.stroke_m));
  put_u16(message.data, 4, unsigned_counts(frame.effort_nm, 0.001));
  message.data[6] = static_cast<std::uint8_t>(frame.enable);
  message.data[7] = flag(frame.set_zero, kMagic);
  return message;
}

CanMessage encode(const MitControl& frame, const CodecOptions& options) {
  if (frame.joint < 1 || frame.joint > kArmJoints) {
    throw std::invalid_argument("MIT joint " + std::to_string(frame.joint) +
                                " does not exist: joints are 1 … 6 (frames 0x15A … 0x15F)");
  }
  CanMessage message = message_for(can_id::kMitControl + static_cast<std::uint32_t>(frame.joint - 1));
  const bool wide = options.mit_layout == MitLayout::kTorque12;
  const std::uint32_t position = wire::mit_quantise(frame.position_rad, kMitPosition);
  const std::uint32_t velocity = wire::mit_quantise(frame.velocity_rad_s, kMitVelocity);
  const std::uint32_t kp = wire::mit_quantise(frame.kp, kMitKp);
  const std::uint32_t kd = wire::mit_quantise(frame.kd, kMitKd);
  const std::uint32_t torque = wire::mit_quantise(frame.torque, wide ? kMitTorque12 : kMitTorque8);
  Payload& data = message.data;
  data[0] = byte(position >> 8);
  data[1] = byte(position);
  data[2] = byte(velocity >> 4);
  data[3] = byte(((velocity & 0x0FU) << 4) | (kp >> 8));
  data[4] = byte(kp);
  data[5] = byte(kd >> 4);
  if (wide) {
    data[6] = byte(((kd & 0x0FU) << 4) | (torque >> 8));
    data[7] = byte(torque);
  } else {
    data[6] = byte(((kd & 0x0FU) << 4) | (torque >> 4));
    data[7] = byte((torque & 0x0FU) << 4);
    data[7] |= mit_crc(data);
  }
  return message;
}

CanMessage encode(const MasterSlaveConfig& frame, const CodecOptions& /*options*/) {
  CanMessage message = message_for(can_id::kMasterSlaveConfig);
  message.data[0] = frame.linkage;
  message.data[1] = frame.feedback_offset;
  message.data[2] = frame.control_offset;
  message.data[3] = frame.linkage_offset;
  return message;
}

CanMessage encode(const MasterArmHomeRequest& frame, const CodecOptions& /*options*/) {
  const auto bytes = master_home_bytes(frame.mode);
  CanMessage message = message_for(can_id::kMasterArmHome);
  message.data[0] = kMasterHomeRequest;
  message.data[1] = bytes[0];
  message.data[2] = bytes[1];
  return message;
}

CanMessage encode(const MotorEnable& frame, const CodecOptions& /*options*/) {
  CanMessage message = message_for(can_id::kMotorEnable);
  message.data[0] = frame.motor;
  message.data[1] = frame.enable ? kMotorOn : kMotorOff;
  return message;
}

CanMessage encode(const JointLimitQuery& frame, const CodecOptions& /*options*/) {
  CanMessage message = message_for(can_id::kJointLimitQuery);
  message.data[0] = frame.joint;
  message.data[1] = frame.acceleration ? kQueryAcc : kQueryLimits;
  return message;
}

CanMessage encode(const JointLimitSet& frame, const CodecOptions& options) {
  CanMessage message = message_for(can_id::kJointLimitSet);
  message.data[0] = frame.joint;
  put_i16(message.data, 1, deci_degrees_or_unchanged(frame.max_angle_rad));
  put_i16(message.data, 3, deci_degrees_or_unchanged(frame.min_angle_rad));
  put_u16(message.data, 5, unsigned_or_unchanged(frame.max_speed_rad_s, options.max_speed_unit_rad_s));
  return message;
}

CanMessage encode(const JointConfig& frame, const CodecOptions& options) {
  CanMessage message = message_for(can_id::kJointConfig);
  message.data[0] = frame.joint;
  message.data[1] = flag(frame.set_zero, kMagic);
  message.data[2] = flag(frame.apply_max_acc, kMagic);
  put_u16(message.data, 3, unsigned_counts(frame.max_acc_rad_s2, options.max_acc_unit_rad_s2));
  message.data[5] = flag(frame.clear_error, kMagic);
  return message;
}

CanMessage encode(const ParamEnquiry& frame, const CodecOptions& /*options*/) {
  CanMessage message = message_for(can_id::kParamEnquiry);
  message.data[0] = frame.query;
  message.data[1] = frame.setting;
  message.data[2] = frame.feedback_48x;
  message.data[3] = flag(frame.payload.has_value(), kMagic);
  message.data[4] = frame.payload.value_or(kPayloadUnset);
  return message;
}

CanMessage encode(const EndVelAccSet& frame, const CodecOptions& /*options*/) {
  CanMessage message = message_for(can_id::kEndVelAccSet);
  put_end_vel_acc(message.data, frame.values);
  return message;
}

CanMessage encode(const CrashProtectionSet& frame, const CodecOptions& /*options*/) {
  return encode_levels(can_id::kCrashProtectionSet, frame);
}

CanMessage encode(const GripperParamSet& frame, const CodecOptions& /*options*/) {
  return encode_gripper_params(can_id::kGripperParamSet, frame);
}

CanMessage encode(const FirmwareChunk& frame, const CodecOptions& /*options*/) {
  CanMessage message = message_for(can_id::kFirmware);
  std::copy_n(frame.text.begin(), std::min<std::size_t>(frame.length, kFrameBytes), message.data.begin());
  return message;
}

CanMessage encode(const ArmStatus& frame, const CodecOptions& options) {
  CanMessage message = message_for(can_id::kArmStatus);
  message.data[0] = static_cast<std::uint8_t>(frame.ctrl_mode);
  message.data[1] = frame.arm_status;
  message.data[2] = move_mode_code(frame.mode_feed, options.mit_layout);
  message.data[3] = frame.teach_status;
  message.data[4] = frame.motion_status;
  message.data[5] = frame.trajectory_index;
  message.data[6] = frame.angle_limit_bits;
  message.data[7] = frame.comm_error_bits;
  return message;
}

CanMessage encode(const EndPoseFeedbackPart& frame, const CodecOptions& /*options*/) {
  return encode_pose_part(can_id::kEndPoseFeedback, frame);
}

CanMessage encode(const JointFeedbackPair& frame, const CodecOptions& /*options*/) {
  return encode_joint_pair(can_id::kJointFeedback, frame);
}

CanMessage encode(const GripperFeedback& frame, const CodecOptions& /*options*/) {
  CanMessage message = message_for(can_id::kGripperFeedback);
  put_i32(message.data, 0, micrometres(frame.stroke_m));
  put_i16(message.data, 4, signed_counts(frame.effort_nm, 0.001));
  message.data[6] = frame.status_bits;
  message.data[7] = frame.reserved;
  return message;
}

CanMessage encode(const HighSpeedInfo& frame, const CodecOptions& options) {
  CanMessage message = message_for(indexed_id(can_id::kHighSpeedInfo, frame.joint - 1, kArmJoints));
  put_i16(message.data, 0, signed_counts(frame.speed_rad_s, 0.001));
  put_i16(message.data, 2, signed_counts(frame.current_a, 0.001));
  put_i32(message.data, 4, saturate<std::int32_t>(frame.position_rad / options.motor_position_unit_rad));
  return message;
}

CanMessage encode(const LowSpeedInfo& frame, const CodecOptions& /*options*/) {
  CanMessage message = message_for(indexed_id(can_id::kLowSpeedInfo, frame.joint - 1, kArmJoints));
  put_u16(message.data, 0, unsigned_counts(frame.voltage_v, 0.1));
  put_i16(message.data, 2, saturate<std::int16_t>(frame.driver_temperature_c));
  message.data[4] = static_cast<std::uint8_t>(saturate<std::int8_t>(frame.motor_temperature_c));
  message.data[5] = frame.status_bits;
  put_u16(message.data, 6, unsigned_counts(frame.bus_current_a, 0.001));
  return message;
}

CanMessage encode(const JointLimitReply& frame, const CodecOptions& options) {
  CanMessage message = message_for(can_id::kJointLimitReply);
  message.data[0] = frame.joint;
  put_i16(message.data, 1, deci_degrees(frame.max_angle_rad));
  put_i16(message.data, 3, deci_degrees(frame.min_angle_rad));
  put_u16(message.data, 5, unsigned_counts(frame.max_speed_rad_s, options.max_speed_unit_rad_s));
  return message;
}

CanMessage encode(const SetAck& frame, const CodecOptions& /*options*/) {
  CanMessage message = message_for(can_id::kSetAck);
  message.data[0] = frame.command;
  message.data[1] = flag(frame.zero_set, kZeroSetDone);
  message.data[2] = frame.trajectory_index;
  return message;
}

CanMessage encode(const EndVelAccReply& frame, const CodecOptions& /*options*/) {
  CanMessage message = message_for(can_id::kEndVelAccReply);
  put_end_vel_acc(message.data, frame.values);
  return message;
}

CanMessage encode(const CrashProtectionReply& frame, const CodecOptions& /*options*/) {
  return encode_levels(can_id::kCrashProtectionReply, frame);
}

CanMessage encode(const JointAccReply& frame, const CodecOptions& options) {
  CanMessage message = message_for(can_id::kJointAccReply);
  message.data[0] = frame.joint;
  put_u16(message.data, 1, unsigned_counts(frame.max_acc_rad_s2, options.max_acc_unit_rad_s2));
  return message;
}

CanMessage encode(const GripperParamReply& frame, const CodecOptions& /*options*/) {
  return encode_gripper_params(can_id::kGripperParamReply, frame);
}

std::optional<Frame> decode(const CanMessage& wire_message, const CodecOptions& options) {
  if (wire_message.extended || wire_message.fd || wire_message.error_frame) return std::nullopt;
  const std::optional<std::uint32_t> id = from_wire_id(wire_message.id, options);
  if (!id) return std::nullopt;
  CanMessage message = wire_message;  // the decoders read frame indices off the protocol id
  message.id = *id;
  for (const FrameDecoder& decoder : kDecoders) {
    if (message.id < decoder.first_id || message.id > decoder.last_id) continue;
    if (message.length < decoder.length) return std::nullopt;
    return decoder.decode(message, options);
  }
  return std::nullopt;
}

CanMessage firmware_request() {
  CanMessage message = message_for(can_id::kFirmware);
  message.data[0] = 0x01;
  return message;
}

bool is_firmware_request(const CanMessage& message) {
  if (message.extended || message.fd || message.error_frame) return false;
  if (message.id != can_id::kFirmware || message.length < kFrameBytes) return false;
  const CanMessage request = firmware_request();
  return std::equal(request.data.begin(), request.data.begin() + kFrameBytes, message.data.begin());
}

std::array<CanMessage, 3> encode_end_pose_target(const CartesianPose& pose) {
  return {encode(EndPoseTargetPart{.part = 0, .first = pose.x_m, .second = pose.y_m}),
          encode(EndPoseTargetPart{.part = 1, .first = pose.z_m, .second = pose.rx_rad}),
          encode(EndPoseTargetPart{.part = 2, .first = pose.ry_rad, .second = pose.rz_rad})};
}

std::array<CanMessage, 3> encode_joint_targets(const std::array<double, kArmJoints>& positions_rad) {
  return {encode(JointTargetPair{.pair = 0, .first_rad = positions_rad[0], .second_rad = positions_rad[1]}),
          encode(JointTargetPair{.pair = 1, .first_rad = positions_rad[2], .second_rad = positions_rad[3]}),
          encode(JointTargetPair{.pair = 2, .first_rad = positions_rad[4], .second_rad = positions_rad[5]})};
}

std::array<CanMessage, 3> encode_end_pose_feedback(const CartesianPose& pose) {
  return {encode(EndPoseFeedbackPart{.part = 0, .first = pose.x_m, .second = pose.y_m}),
          encode(EndPoseFeedbackPart{.part = 1, .first = pose.z_m, .second = pose.rx_rad}),
          encode(EndPoseFeedbackPart{.part = 2, .first = pose.ry_rad, .second = pose.rz_rad})};
}

std::array<CanMessage, 3> encode_joint_feedback(const std::array<double, kArmJoints>& positions_rad) {
  return {encode(JointFeedbackPair{.pair = 0, .first_rad = positions_rad[0], .second_rad = positions_rad[1]}),
          encode(JointFeedbackPair{.pair = 1, .first_rad = positions_rad[2], .second_rad = positions_rad[3]}),
          encode(JointFeedbackPair{.pair = 2, .first_rad = positions_rad[4], .second_rad = positions_rad[5]})};
}

std::optional<std::string> software_version(const std::string& firmware_text) {
  constexpr std::size_t kVersionLength = 8;  // "S-V1.8-2"; the SDK takes 8 characters too
  const std::size_t at = firmware_text.find("S-V");
  if (at == std::string::npos) return std::nullopt;
  // The bytes come from the arm and end up in JSON and logs: keep the printable ones.
  const std::string_view version = std::string_view(firmware_text).substr(at, kVersionLength);
  const auto end = std::find_if(version.begin(), version.end(), [](char c) { return c < 0x20 || c > 0x7E; });
  return std::string(version.begin(), end);
}

MitLayout mit_layout_for(const std::string& software_version) {
  std::string_view text = software_version;
  if (!take(text, "S-V")) return MitLayout::kTorque8Crc;
  const auto major = take_number(text);
  if (!major || !take(text, ".")) return MitLayout::kTorque8Crc;
  const auto minor = take_number(text);
  if (!minor) return MitLayout::kTorque8Crc;
  // S-V1.8-8 is the first 12-bit firmware. The 8-character field cuts the patch of a two-digit
  // minor ("S-V1.10-"), so major.minor decide alone when they are not 1.8.
  const std::pair version{*major, *minor};
  constexpr std::pair kFirst{1U, 8U};
  if (version != kFirst) return version > kFirst ? MitLayout::kTorque12 : MitLayout::kTorque8Crc;
  const auto patch = take(text, "-") ? take_number(text) : std::nullopt;
  return patch && *patch >= 8 ? MitLayout::kTorque12 : MitLayout::kTorque8Crc;
}

}  // namespace robotd::piper
