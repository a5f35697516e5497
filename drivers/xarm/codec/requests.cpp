// The requests robotd sends (§4.1): each register's parameters in wire order and units (mm,
// mm/s, mm/s², mm/s³ for Cartesian values; rad and s as given).
#include <cstdint>
#include <initializer_list>

#include "wire_fields.hpp"
#include "xarm_codec.hpp"

namespace robotd::xarm {
namespace {

Request request(Register reg, ByteWriter& params) { return Request{.reg = number(reg), .params = params.take()}; }

Request u8_request(Register reg, std::initializer_list<std::uint8_t> values) {
  ByteWriter params;
  for (const std::uint8_t value : values) params.u8(value);
  return request(reg, params);
}

Request f32_request(Register reg, double value) {
  ByteWriter params;
  params.f32_le(value);
  return request(reg, params);
}

/// pose (mm, rad), speed mm/s, acc mm/s², mvtime s: the common head of both line moves.
ByteWriter line_move_params(const LineMove& move) {
  ByteWriter params;
  write_pose(params, move.pose);
  params.f32_le(move.speed_m_s * kMmPerM).f32_le(move.acc_m_s2 * kMmPerM).f32_le(move.mvtime_s);
  return params;
}

}  // namespace

Request plain_request(Register reg) { return Request{.reg = number(reg), .params = {}}; }

Request motion_enable_request(int joint, bool enable) {
  return u8_request(Register::kMotionEnable,
                    {static_cast<std::uint8_t>(joint), enable ? std::uint8_t{1} : std::uint8_t{0}});
}

Request set_state_request(int state) { return u8_request(Register::kSetState, {static_cast<std::uint8_t>(state)}); }

Request set_mode_request(int mode) { return u8_request(Register::kSetMode, {static_cast<std::uint8_t>(mode)}); }

Request set_reduced_mode_request(bool on) {
  return u8_request(Register::kSetReducedMode, {on ? std::uint8_t{1} : std::uint8_t{0}});
}

Request set_feedback_type_request(std::uint8_t types) { return u8_request(Register::kSetFeedbackType, {types}); }

Request set_brake_request(int joint, bool release) {
  return u8_request(Register::kSetBrake,
                    {static_cast<std::uint8_t>(joint), release ? std::uint8_t{1} : std::uint8_t{0}});
}

Request move_line_request(const LineMove& move) {
  ByteWriter params = line_move_params(move);
  return request(Register::kMoveLine, params);
}

Request move_lineb_request(const LineMove& move) {
  ByteWriter params = line_move_params(move);
  params.f32_le(move.blend_radius_m * kMmPerM);
  return request(Register::kMoveLineB, params);
}

Request move_joint_request(const JointMove& move) {
  ByteWriter params;
  write_joints(params, move.joints_rad);
  params.f32_le(move.speed_rad_s).f32_le(move.acc_rad_s2).f32_le(move.mvtime_s);
  return request(Register::kMoveJoint, params);
}

Request move_gohome_request(const JointMove& move) {
  ByteWriter params;
  params.f32_le(move.speed_rad_s).f32_le(move.acc_rad_s2).f32_le(move.mvtime_s);
  return request(Register::kMoveGohome, params);
}

Request sleep_instruction_request(double seconds) { return f32_request(Register::kSleepInstruction, seconds); }

Request servo_j_request(const JointValues& joints_rad) {
  ByteWriter params;
  write_joints(params, joints_rad);
  params.f32_le(0).f32_le(0).f32_le(0);  // speed, acc, time: reserved
  return request(Register::kServoJ, params);
}

Request set_tcp_jerk_request(double jerk_m_s3) { return f32_request(Register::kSetTcpJerk, jerk_m_s3 * kMmPerM); }

Request set_tcp_maxacc_request(double acc_m_s2) { return f32_request(Register::kSetTcpMaxAcc, acc_m_s2 * kMmPerM); }

Request set_joint_jerk_request(double jerk_rad_s3) { return f32_request(Register::kSetJointJerk, jerk_rad_s3); }

Request set_joint_maxacc_request(double acc_rad_s2) { return f32_request(Register::kSetJointMaxAcc, acc_rad_s2); }

Request set_tcp_offset_request(const Pose& offset) {
  ByteWriter params;
  write_pose(params, offset);
  return request(Register::kSetTcpOffset, params);
}

Request get_fk_request(const JointValues& joints_rad) {
  ByteWriter params;
  write_joints(params, joints_rad);
  return request(Register::kGetFk, params);
}

Request is_joint_limit_request(const JointValues& joints_rad) {
  ByteWriter params;
  write_joints(params, joints_rad);
  return request(Register::kIsJointLimit, params);
}

}  // namespace robotd::xarm
