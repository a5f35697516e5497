// Range checks of the arguments §7 bounds (motion parameter ranges, joint limits), so a bad value
// is refused with a clear message instead of being sent. NaN fails every check.
#include <array>
#include <charconv>
#include <cstddef>
#include <string>
#include <string_view>

#include "xarm_codec.hpp"

namespace robotd::xarm {
namespace {

constexpr double kMaxTcpAcc = 50.0;      // m/s²
constexpr double kMaxTcpJerk = 100.0;    // m/s³
constexpr double kMaxJointAcc = 20.0;    // rad/s², §7's 1145 °/s²
constexpr double kMaxJointJerk = 500.0;  // rad/s³, §7's 28647 °/s³
constexpr double kMaxSleepSeconds = 3600.0;
constexpr int kAllJoints = 8;
constexpr int kBoundDigits = 5;  // π shows as 3.1416
/// fp32 moves an angle of up to 2π by at most 2.4e-7 rad; no joint notices 1e-6 rad.
constexpr double kLimitRoundingRad = 1e-6;

/// The shortest text that reads back as `value` ("0.1", "nan", "-inf"), or `digits` significant
/// digits when given.
std::string number_text(double value, int digits = 0) {
  std::array<char, 32> text{};
  const auto result =
      digits > 0 ? std::to_chars(text.data(), text.data() + text.size(), value, std::chars_format::general, digits)
                 : std::to_chars(text.data(), text.data() + text.size(), value);
  return std::string(text.data(), result.ptr);
}

/// "joint speed 4 rad/s is outside (0, 3.1416] rad/s": accepts lower < value <= upper (lower <=
/// value when `closed_below`).
Result<void> check_range(std::string_view argument, double value, double lower, double upper, bool closed_below,
                         std::string_view unit, std::string_view subject = {}) {
  const bool above_lower = closed_below ? value >= lower : value > lower;
  if (above_lower && value <= upper) return {};
  const std::string unit_text = " " + std::string(unit);
  return make_error(ErrorCode::kInvalidArgument, std::string(argument) + " " + number_text(value) + unit_text +
                                                     " is outside " + (closed_below ? "[" : "(") +
                                                     number_text(lower, kBoundDigits) + ", " +
                                                     number_text(upper, kBoundDigits) + "]" + unit_text +
                                                     (subject.empty() ? "" : " for the " + std::string(subject)));
}

}  // namespace

Result<void> check_joint_selector(int joint, std::size_t dof) {
  if (joint == kAllJoints || (joint >= 1 && static_cast<std::size_t>(joint) <= dof)) return {};
  return make_error(ErrorCode::kInvalidArgument, "joint " + std::to_string(joint) + " is outside 1.." +
                                                     std::to_string(dof) + " (or 8 for all joints)");
}

Result<void> check_tcp_speed(double speed_m_s, const ArmModel& model) {
  return check_range("TCP speed", speed_m_s, 0, model.max_tcp_speed_m_s, false, "m/s", model.display);
}

Result<void> check_tcp_acc(double acc_m_s2) {
  return check_range("TCP acceleration", acc_m_s2, 0, kMaxTcpAcc, false, "m/s²");
}

Result<void> check_tcp_jerk(double jerk_m_s3) {
  return check_range("TCP jerk", jerk_m_s3, 0, kMaxTcpJerk, false, "m/s³");
}

Result<void> check_joint_speed(double speed_rad_s) {
  return check_range("joint speed", speed_rad_s, 0, kMaxJointSpeedRadS, false, "rad/s");
}

Result<void> check_joint_acc(double acc_rad_s2) {
  return check_range("joint acceleration", acc_rad_s2, 0, kMaxJointAcc, false, "rad/s²");
}

Result<void> check_joint_jerk(double jerk_rad_s3) {
  return check_range("joint jerk", jerk_rad_s3, 0, kMaxJointJerk, false, "rad/s³");
}

Result<void> check_sleep(double seconds) { return check_range("sleep time", seconds, 0, kMaxSleepSeconds, true, "s"); }

Result<void> check_joints_within(const JointValues& joints_rad, const ArmModel& model) {
  for (std::size_t j = 0; j < model.dof && j < kMaxDof; ++j) {
    const double angle = joints_rad[j];
    if (angle >= model.min_rad[j] - kLimitRoundingRad && angle <= model.max_rad[j] + kLimitRoundingRad) continue;
    // The message names the limits themselves, not the forgiven ones.
    return check_range("joint " + std::to_string(j + 1) + " angle", angle, model.min_rad[j], model.max_rad[j], true,
                       "rad", model.display);
  }
  return {};
}

}  // namespace robotd::xarm
