// Kinematics registers (spec §4.1, seed Part III, IV): the TCP offset and payload, the pose and
// joints now, forward and inverse kinematics, the joint-limit check.
#include <cmath>
#include <string>

#include "controller.hpp"
#include "joint_limits.hpp"

namespace robotd::xarm::sim {
namespace {

constexpr std::size_t kLoadFloats = 4;  // mass kg, centre of mass x, y, z mm
constexpr double kMmPerM = 1000.0;
constexpr unsigned kJointGroupMask = 0x0F;  // get_joint_pos's u8: how many 7-float groups
constexpr unsigned kMaxJointGroups = 3;     // positions, velocities, efforts

bool finite(const Pose& pose) {
  for (std::size_t i = 0; i < 3; ++i) {
    if (!std::isfinite(pose.position_m[i]) || !std::isfinite(pose.rpy_rad[i])) return false;
  }
  return true;
}

}  // namespace

Controller::Outcome Controller::set_tcp_offset(const Request& request) {
  const auto parsed = parse_pose_params(request.frame.reg, request.frame.body);
  if (!parsed) return parameter_error(request, parsed.error().message);
  if (!finite(parsed.value())) return parameter_error(request, "the offset has a value that is not a number");
  config_.tcp_offset = parsed.value();
  reset_system();
  return Outcome{};
}

Controller::Outcome Controller::set_load_param(const Request& request) {
  ByteReader reader(request.frame.body);
  std::array<double, kLoadFloats> values{};
  for (double& value : values) {
    const auto read = reader.f32_le();
    if (!read || !std::isfinite(*read)) {
      return parameter_error(request, "expected 4 floats (mass kg, centre of mass x, y, z mm), got " +
                                          std::to_string(request.frame.body.size()) + " bytes");
    }
    value = *read;
  }
  config_.payload_kg = values[0];
  config_.payload_centre_m = {values[1] / kMmPerM, values[2] / kMmPerM, values[3] / kMmPerM};
  return Outcome{};
}

Controller::Outcome Controller::get_tcp_pose(const Request& /*request*/) {
  return answer(encode_pose(tcp_pose(joints_)));
}

Controller::Outcome Controller::get_joint_pos(const Request& request) {
  if (request.frame.body.empty()) return answer(encode_joints(joints_));
  const unsigned groups = request.frame.body[0] & kJointGroupMask;
  if (groups == 0 || groups > kMaxJointGroups) {
    return parameter_error(request, "asks for " + std::to_string(groups) + " groups of 7 floats (1 … 3)");
  }
  Bytes data = encode_joints(joints_);
  if (groups >= 2) {
    const Bytes velocities = encode_joints(velocity_);
    data.insert(data.end(), velocities.begin(), velocities.end());
  }
  if (groups >= 3) {
    const Bytes efforts = encode_joints(joint_efforts());
    data.insert(data.end(), efforts.begin(), efforts.end());
  }
  return answer(std::move(data));
}

Controller::Outcome Controller::get_ik(const Request& request) {
  const auto parsed = parse_pose_params(request.frame.reg, request.frame.body);
  if (!parsed) return parameter_error(request, parsed.error().message);
  if (!finite(parsed.value())) return parameter_error(request, "the pose has a value that is not a number");
  if (!kinematics_.solves_poses()) {
    return no_solution(request, "a " + std::to_string(model_.dof) + "-joint arm has no general inverse kinematics");
  }
  const auto joints = kinematics_.solve(isometry_of(parsed.value()), tcp_offset(), joints_);
  if (!joints) return no_solution(request, "no joint solution within the limits");
  return answer(encode_joints(*joints));
}

Controller::Outcome Controller::get_fk(const Request& request) {
  const auto parsed = parse_joint_params(request.frame.reg, request.frame.body);
  if (!parsed) return parameter_error(request, parsed.error().message);
  return answer(encode_pose(tcp_pose(parsed.value())));
}

Controller::Outcome Controller::is_joint_limit(const Request& request) {
  const auto parsed = parse_joint_params(request.frame.reg, request.frame.body);
  if (!parsed) return parameter_error(request, parsed.error().message);
  return answer(encode_limit_flag(!within_limits(parsed.value(), model_)));
}

}  // namespace robotd::xarm::sim
