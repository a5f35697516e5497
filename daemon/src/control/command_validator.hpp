// The gate every ControlCommand passes before it may reach a motor: well-formed arrays, known
// and owned motors, finite values, values within the device's limits. Pure: the caller
// supplies the session and the device; the verdict names the reason and what was wrong.
#pragma once

#include <array>
#include <bitset>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "control/device_model.hpp"
#include "robotd/driver/types.hpp"
#include "robotd/messages.hpp"

namespace robotd::control {

using MotorSet = std::bitset<driver::kMaxJoints>;

enum class Rejection : std::uint8_t {
  kUnknownSession,
  kWrongDevice,
  kNotOwner,
  kUnknownMotor,
  kMalformed,
  kNonFinite,
  kOutOfRange,
  kEstop,
  kFault,
};
inline constexpr std::size_t kRejectionCount = 9;

const char* to_string(Rejection rejection);

/// Which fields of a JointTargetUpdate carry a value.
enum TargetField : std::uint8_t {
  kHasPosition = 1U << 0U,
  kHasVelocity = 1U << 1U,
  kHasKp = 1U << 2U,
  kHasKd = 1U << 3U,
  kHasTorque = 1U << 4U,
};

struct JointTargetUpdate {
  std::uint8_t joint = 0;
  std::uint8_t fields = 0;
  float position = 0;
  float velocity = 0;
  float kp = 0;
  float kd = 0;
  float torque = 0;
};

struct ValidatedCommand {
  bool keepalive = false;  // no motors named: renews the session, moves nothing
  bool clamped = false;    // some value was clamped into its limits (limit_policy clamp)
  std::size_t count = 0;
  std::array<JointTargetUpdate, driver::kMaxJoints> joints{};
};

struct SessionView {
  std::string_view device;
  ControlMode mode = ControlMode::kPosition;
  MotorSet motors;
};

struct Verdict {
  std::optional<Rejection> rejection;  // nullopt = accepted
  std::string detail;                  // why, for the log
};

/// Checks `command` for `session` on `model`, whose limits now are `limits` (one per joint:
/// the model's, narrowed at run time); on acceptance fills `out`.
Verdict validate_command(const ControlCommand& command, const SessionView& session, const DeviceModel& model,
                         std::span<const driver::JointLimits> limits, ValidatedCommand& out);

}  // namespace robotd::control
