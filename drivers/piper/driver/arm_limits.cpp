// The arm's own joint limits, read at connect as the SDK's PiperInit does (0x472 → 0x473 for
// each joint): robotd's limits are the configured ones narrowed by what the arm holds, never
// widened, so a joint the arm was told to keep within ±1 rad is not commanded to 2 rad.
#include <algorithm>
#include <cstdio>

#include "codec/wire_scaling.hpp"
#include "driver/piper_driver.hpp"
#include "robotd/driver/monotonic_clock.hpp"

namespace robotd::piper {
namespace {

using namespace std::chrono_literals;

/// `config` narrowed by `arm`; appends what changed to `note` ("joint1 max 2.618→1.000 rad"). A
/// value tighter by less than one count of its field is the wire's rounding of the same limit
/// (3.14 rad is stored as 1799 × 0.1° = 3.13985 rad), not a narrower one.
driver::JointLimits narrowed(const driver::JointLimits& config, const JointLimitReply& arm, double speed_unit_rad_s,
                             std::string& note) {
  constexpr double kAngleCountRad = 1.0 / wire::kDeciDegPerRad;
  driver::JointLimits limits = config;
  std::array<char, 96> text{};
  const auto tell = [&](const char* what, double from, double to, const char* unit) {
    std::snprintf(text.data(), text.size(), "%sjoint%d %s %.3f→%.3f %s", note.empty() ? "" : ", ", arm.joint, what,
                  from, to, unit);
    note += text.data();
  };
  if (arm.min_angle_rad > limits.position_min_rad + kAngleCountRad) {
    tell("min", limits.position_min_rad, arm.min_angle_rad, "rad");
    limits.position_min_rad = arm.min_angle_rad;
  }
  if (arm.max_angle_rad < limits.position_max_rad - kAngleCountRad) {
    tell("max", limits.position_max_rad, arm.max_angle_rad, "rad");
    limits.position_max_rad = arm.max_angle_rad;
  }
  // A speed of 0 is "not set" on arms that never stored one; it would stop the joint.
  if (arm.max_speed_rad_s > 0 && arm.max_speed_rad_s < limits.velocity_max_rad_s - speed_unit_rad_s) {
    tell("speed", limits.velocity_max_rad_s, arm.max_speed_rad_s, "rad/s");
    limits.velocity_max_rad_s = arm.max_speed_rad_s;
  }
  return limits;
}

}  // namespace

void PiperDriver::read_arm_limits() {
  {
    const std::lock_guard lock(limits_mutex_);
    for (std::size_t j = 0; j < kArmJoints; ++j) params_.joints[j].limits = configured_limits_[j];
  }
  arm_limits_note_.clear();
  replies_.clear();
  for (int j = 1; j <= kArmJoints; ++j) {
    if (send(encode(JointLimitQuery{.joint = static_cast<std::uint8_t>(j)}, codec_)) != transport::CanIo::kDone) {
      arm_limits_note_ = "could not send the joint limit query (0x472): the configured limits apply";
      return;
    }
  }
  std::array<bool, kArmJoints> answered{};
  std::string narrowing;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(params_.reply_timeout_ms);
  while (std::count(answered.begin(), answered.end(), true) < kArmJoints) {
    drain_link_blocking_free(driver::monotonic_now_ns());
    while (const auto message = replies_.pop()) {
      const auto frame = message->id == can_id::kJointLimitReply ? decode(*message, codec_) : std::nullopt;
      const auto* reply = frame ? std::get_if<JointLimitReply>(&*frame) : nullptr;
      if (reply == nullptr || reply->joint < 1 || reply->joint > kArmJoints || answered[reply->joint - 1U]) continue;
      answered[reply->joint - 1U] = true;
      const std::lock_guard lock(limits_mutex_);
      PiperJointParams& joint = params_.joints[reply->joint - 1U];
      joint.limits = narrowed(configured_limits_[reply->joint - 1U], *reply, codec_.max_speed_unit_rad_s, narrowing);
      if (joint.limits.position_min_rad >= joint.limits.position_max_rad) {
        joint.limits = configured_limits_[reply->joint - 1U];  // disjoint ranges: the arm's answer is unusable
        narrowing += (narrowing.empty() ? "" : ", ") + joint.name + " ignored (no overlap with the config)";
      }
    }
    if (std::chrono::steady_clock::now() >= deadline) {
      arm_limits_note_ = "no answer to the joint limit query (0x472) for every joint: the configured limits apply";
      return;
    }
    if (!abort_.sleep_for(1ms)) return;
  }
  if (!narrowing.empty()) arm_limits_note_ = "the arm's limits narrow the config: " + narrowing;
}

}  // namespace robotd::piper
