// The UDP real-time push (§6.2): one "realtime_arm_joint_state" object per datagram, arrays
// sized to the arm's DOF, converted from the wire's 0.001 units to robotd's.
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "field_reader.hpp"
#include "realman_codec.hpp"

namespace robotd::realman {
namespace {

constexpr std::string_view kPushState = "realtime_arm_joint_state";
constexpr double kMilli = 1e-3;
constexpr double kMicro = 1e-6;
constexpr double kQuaternionScale = 1e6;

double rad_s_per_unit(SpeedUnit unit) {
  constexpr double kRadPerDegree = std::numbers::pi / 180.0;
  switch (unit) {
    case SpeedUnit::kCentiDegreesPerSecond:
      return 0.01 * kRadPerDegree;
    case SpeedUnit::kCentiRpm:
      return 0.01 * 360.0 / 60.0 * kRadPerDegree;  // 0.01 rev/min = 0.06 °/s
    case SpeedUnit::kFiftiethDegreesPerSecond:
      return 0.02 * kRadPerDegree;  // ROS1 divides the raw value by 50
  }
  return 0.01 * kRadPerDegree;
}

/// The fields of joint_status, read before any is used.
struct JointStatus {
  std::vector<std::int64_t> position;
  std::vector<std::int64_t> current;
  std::vector<std::int64_t> voltage;
  std::vector<std::int64_t> temperature;
  std::vector<bool> enabled;
  std::vector<std::int64_t> errors;
  std::vector<std::int64_t> speed;  // empty unless custom.joint_speed
};

JointStatus read_joint_status(FieldReader& joint_status) {
  JointStatus status;
  status.position = joint_status.integers("joint_position", 1, kMaxDof);
  // The other arrays must cover every joint; the joint positions say how many there are.
  const std::size_t dof = status.position.size();
  status.current = joint_status.integers("joint_current", dof, FieldReader::kAnyCount);
  status.voltage = joint_status.integers("joint_voltage", dof, FieldReader::kAnyCount);
  status.temperature = joint_status.integers("joint_temperature", dof, FieldReader::kAnyCount);
  status.enabled = joint_status.flags("joint_en_flag", dof, FieldReader::kAnyCount);
  status.errors = joint_status.integers("joint_err_code", dof, FieldReader::kAnyCount, 0, 0xFFFF);
  if (joint_status.has("joint_speed")) status.speed = joint_status.integers("joint_speed", dof, FieldReader::kAnyCount);
  return status;
}

}  // namespace

Result<RealtimePush> parse_realtime_push(std::string_view datagram, SpeedUnit speed_unit) {
  if (datagram.ends_with(kMessageTerminator)) datagram.remove_suffix(kMessageTerminator.size());
  auto parsed = parse_object(datagram);
  if (!parsed) return make_error(ErrorCode::kInvalidArgument, "realtime push: " + parsed.error().message);
  const nlohmann::json& body = parsed.value();

  std::string problem;
  FieldReader push(body, "", problem);
  const std::string state = push.text("state");
  if (problem.empty() && state != kPushState) {
    return make_error(ErrorCode::kInvalidArgument,
                      "realtime push: \"state\" is \"" + state + "\", expected \"" + std::string(kPushState) + "\"");
  }
  FieldReader joint_status = push.object("joint_status");
  const JointStatus joints = read_joint_status(joint_status);
  const bool has_pose = push.has("waypoint");
  std::vector<std::int64_t> position;
  std::vector<std::int64_t> euler;
  std::vector<std::int64_t> quaternion;
  if (has_pose) {
    FieldReader waypoint = push.object("waypoint");
    position = waypoint.integers("position", 3, 3);
    euler = waypoint.integers("euler", 3, 3);
    quaternion = waypoint.integers("quat", 4, 4);
  }
  auto errors = push.error_codes();
  const std::string arm_status = push.has("arm_current_status") ? push.text("arm_current_status") : "";
  if (!problem.empty()) return make_error(ErrorCode::kInvalidArgument, "realtime push: " + problem);

  RealtimePush out;
  out.dof = joints.position.size();
  const double speed_scale = rad_s_per_unit(speed_unit);
  for (std::size_t j = 0; j < out.dof; ++j) {
    out.position_rad[j] = rad_from_millidegrees(joints.position[j]);
    out.current_a[j] = static_cast<double>(joints.current[j]) * kMicro;  // 0.001 mA
    out.voltage_v[j] = static_cast<double>(joints.voltage[j]) * kMilli;
    out.temperature_c[j] = static_cast<double>(joints.temperature[j]) * kMilli;
    out.enabled[j] = joints.enabled[j];
    out.joint_errors[j] = static_cast<std::uint16_t>(joints.errors[j]);
  }
  out.has_speed = !joints.speed.empty();
  if (out.has_speed) {
    for (std::size_t j = 0; j < out.dof; ++j) out.speed_rad_s[j] = static_cast<double>(joints.speed[j]) * speed_scale;
  }
  out.errors = std::move(errors);
  out.has_pose = has_pose;
  if (has_pose) {
    for (std::size_t i = 0; i < 3; ++i) {
      out.position_m[i] = m_from_micrometres(position[i]);
      out.euler_rad[i] = rad_from_milliradians(euler[i]);
    }
    for (std::size_t i = 0; i < 4; ++i) out.quaternion_wxyz[i] = static_cast<double>(quaternion[i]) / kQuaternionScale;
  }
  out.arm_status = arm_status;
  return out;
}

}  // namespace robotd::realman
