// Requests as the controller reads them (the simulator's side of §4.1): parameters back into
// robotd's units. Bodies longer than the layout (newer firmware's trailing flags) are accepted.
#include <cstddef>
#include <cstdint>
#include <string>

#include "wire_fields.hpp"
#include "xarm_codec.hpp"

namespace robotd::xarm {
namespace {

constexpr std::size_t kLegacyLineFloats = 9;
constexpr std::size_t kLineFloatsWithRadius = 10;

/// Refuses a body shorter than `expected` bytes.
Result<void> check_params(std::uint8_t reg, ByteView params, std::size_t expected) {
  if (params.size() >= expected) return {};
  return size_error(register_name(reg) + " request", "parameter byte", params.size(), expected, true);
}

Result<JointSwitch> parse_joint_switch(Register reg, ByteView params) {
  if (auto checked = check_params(number(reg), params, 2); !checked) return checked.error();
  const std::uint8_t value = params[1];
  if (value > 1) {
    return make_error(ErrorCode::kInvalidArgument,
                      register_name(number(reg)) + " request value " + std::to_string(value) + " is neither 0 nor 1");
  }
  return JointSwitch{.joint = params[0], .on = value == 1};
}

}  // namespace

Result<JointSwitch> parse_motion_enable(ByteView params) { return parse_joint_switch(Register::kMotionEnable, params); }

Result<JointSwitch> parse_set_brake(ByteView params) { return parse_joint_switch(Register::kSetBrake, params); }

Result<int> parse_u8_param(std::uint8_t reg, ByteView params) {
  if (auto checked = check_params(reg, params, 1); !checked) return checked.error();
  return static_cast<int>(params[0]);
}

Result<LineMove> parse_line_move(std::uint8_t reg, ByteView params) {
  std::size_t floats = 0;
  if (reg == number(Register::kMoveLine)) {
    // The legacy form has nothing after its 9 floats; anything longer is the common form.
    floats = params.size() > kLegacyLineFloats * kF32Bytes ? kLineFloatsWithRadius : kLegacyLineFloats;
  } else if (reg == number(Register::kMoveLineB)) {
    floats = kLineFloatsWithRadius;
  } else {
    return make_error(ErrorCode::kInvalidArgument,
                      register_name(reg) + " is not a line move (move_line 21 or move_lineb 22)");
  }
  if (auto checked = check_params(reg, params, floats * kF32Bytes); !checked) return checked.error();
  ByteReader reader(params);
  LineMove move;
  move.pose = read_pose(reader);
  move.speed_m_s = read_f32(reader) / kMmPerM;
  move.acc_m_s2 = read_f32(reader) / kMmPerM;
  move.mvtime_s = read_f32(reader);
  move.blend_radius_m = floats == kLineFloatsWithRadius ? read_f32(reader) / kMmPerM : 0.0;
  return move;
}

Result<JointMove> parse_joint_move(ByteView params) {
  if (auto checked = check_params(number(Register::kMoveJoint), params, kJointBytes + 3 * kF32Bytes); !checked) {
    return checked.error();
  }
  ByteReader reader(params);
  JointMove move;
  move.joints_rad = read_joints(reader);
  move.speed_rad_s = read_f32(reader);
  move.acc_rad_s2 = read_f32(reader);
  move.mvtime_s = read_f32(reader);
  return move;
}

Result<JointMove> parse_gohome(ByteView params) {
  if (auto checked = check_params(number(Register::kMoveGohome), params, 3 * kF32Bytes); !checked) {
    return checked.error();
  }
  ByteReader reader(params);
  JointMove move;
  move.speed_rad_s = read_f32(reader);
  move.acc_rad_s2 = read_f32(reader);
  move.mvtime_s = read_f32(reader);
  return move;
}

Result<JointValues> parse_joint_params(std::uint8_t reg, ByteView params) {
  if (auto checked = check_params(reg, params, kJointBytes); !checked) return checked.error();
  ByteReader reader(params);
  return read_joints(reader);
}

Result<Pose> parse_pose_params(std::uint8_t reg, ByteView params) {
  if (auto checked = check_params(reg, params, kPoseBytes); !checked) return checked.error();
  ByteReader reader(params);
  return read_pose(reader);
}

Result<double> parse_scalar_param(std::uint8_t reg, ByteView params) {
  double wire_units_per_unit = 1.0;
  switch (static_cast<Register>(reg)) {
    case Register::kSleepInstruction:
    case Register::kSetJointJerk:
    case Register::kSetJointMaxAcc:
      break;
    case Register::kSetTcpJerk:
    case Register::kSetTcpMaxAcc:
      wire_units_per_unit = kMmPerM;
      break;
    default:
      return make_error(ErrorCode::kInvalidArgument,
                        register_name(reg) +
                            " does not take one float (sleep_instruction, set_tcp_jerk, set_tcp_maxacc, "
                            "set_joint_jerk, set_joint_maxacc do)");
  }
  if (auto checked = check_params(reg, params, kF32Bytes); !checked) return checked.error();
  ByteReader reader(params);
  return read_f32(reader) / wire_units_per_unit;
}

}  // namespace robotd::xarm
