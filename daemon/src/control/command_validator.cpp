#include "control/command_validator.hpp"

#include <cmath>
#include <sstream>

#include "control/joint_limiter.hpp"

namespace robotd::control {
namespace {

Verdict reject(Rejection reason, std::string detail) { return Verdict{reason, std::move(detail)}; }

struct ArrayCheck {
  const char* name;
  const std::vector<float>* values;
  bool required;
};

std::string join_ids(const std::vector<std::int32_t>& ids) {
  std::string out;
  for (const auto id : ids) out += (out.empty() ? "" : ", ") + std::to_string(id);
  return out;
}

// The float nearest to `limit` that is not beyond it (a double limit rarely is a float, and
// rounding to the nearest float can land just outside it).
float float_within(double limit, bool upper) {
  const auto nearest = static_cast<float>(limit);
  if (upper && static_cast<double>(nearest) > limit) return std::nextafter(nearest, -HUGE_VALF);
  if (!upper && static_cast<double>(nearest) < limit) return std::nextafter(nearest, HUGE_VALF);
  return nearest;
}

// Checks one value against [low, high]: accepted, clamped (policy clamp) or rejected.
bool within_or_clamped(float& value, double low, double high, LimitPolicy policy, bool& clamped) {
  if (value >= low && value <= high) return true;
  if (policy == LimitPolicy::kReject) return false;
  value = value < low ? float_within(low, false) : float_within(high, true);
  clamped = true;
  return true;
}

}  // namespace

const char* to_string(Rejection rejection) {
  switch (rejection) {
    case Rejection::kUnknownSession:
      return "unknown_session";
    case Rejection::kWrongDevice:
      return "wrong_device";
    case Rejection::kNotOwner:
      return "not_owner";
    case Rejection::kUnknownMotor:
      return "unknown_motor";
    case Rejection::kMalformed:
      return "malformed";
    case Rejection::kNonFinite:
      return "non_finite";
    case Rejection::kOutOfRange:
      return "out_of_range";
    case Rejection::kEstop:
      return "estop";
    case Rejection::kFault:
      return "fault";
  }
  return "unknown";
}

Verdict validate_command(const ControlCommand& command, const SessionView& session, const DeviceModel& model,
                         std::span<const driver::JointLimits> joint_limits, ValidatedCommand& out) {
  out = ValidatedCommand{};
  if (!command.device.empty() && command.device != session.device) {
    return reject(Rejection::kWrongDevice, "command names device '" + command.device +
                                               "' but its session is on device '" + std::string(session.device) + "'");
  }

  const std::size_t count = command.motor_ids.size();
  const bool positions_required = session.mode != ControlMode::kTorque;
  const bool torques_required = session.mode != ControlMode::kPosition;
  const bool gains_required = session.mode == ControlMode::kMixed;
  const std::array<ArrayCheck, 5> arrays{{{"positions", &command.positions, positions_required},
                                          {"velocities", &command.velocities, false},
                                          {"kp", &command.kp, gains_required},
                                          {"kd", &command.kd, gains_required},
                                          {"torques", &command.torques, torques_required}}};

  if (count == 0) {
    for (const auto& array : arrays) {
      if (!array.values->empty()) {
        return reject(Rejection::kMalformed, std::string(array.name) + " has " + std::to_string(array.values->size()) +
                                                 " values but motor_ids is empty");
      }
    }
    out.keepalive = true;
    return {};
  }
  if (count > model.joint_count()) {
    return reject(Rejection::kMalformed, "motor_ids names " + std::to_string(count) + " motors; device '" + model.name +
                                             "' has " + std::to_string(model.joint_count()));
  }
  for (const auto& array : arrays) {
    if (array.values->empty() && array.required) {
      return reject(Rejection::kMalformed, std::string(array.name) + " is required in " +
                                               std::string(to_string(session.mode)) + " mode (one per motor id)");
    }
    if (!array.values->empty() && array.values->size() != count) {
      return reject(Rejection::kMalformed, std::string(array.name) + " has " + std::to_string(array.values->size()) +
                                               " values for " + std::to_string(count) + " motor ids");
    }
  }

  MotorSet seen;
  for (const auto id : command.motor_ids) {
    if (id < 0 || static_cast<std::size_t>(id) >= model.joint_count()) {
      return reject(Rejection::kUnknownMotor, "motor id " + std::to_string(id) + " does not exist on device '" +
                                                  model.name + "' (valid: 0.." +
                                                  std::to_string(model.joint_count() - 1) + ")");
    }
    const auto index = static_cast<std::size_t>(id);
    if (seen.test(index)) return reject(Rejection::kMalformed, "motor id " + std::to_string(id) + " appears twice");
    seen.set(index);
  }
  if ((seen & ~session.motors).any()) {
    std::vector<std::int32_t> foreign;
    for (const auto id : command.motor_ids) {
      if (!session.motors.test(static_cast<std::size_t>(id))) foreign.push_back(id);
    }
    return reject(Rejection::kNotOwner,
                  "the session does not own motor(s) " + join_ids(foreign) + " of '" + model.name + "'");
  }
  for (const auto& array : arrays) {
    for (std::size_t i = 0; i < array.values->size(); ++i) {
      if (!std::isfinite((*array.values)[i])) {
        return reject(Rejection::kNonFinite, std::string(array.name) + " for motor " +
                                                 std::to_string(command.motor_ids[i]) + " is not a finite number");
      }
    }
  }

  for (std::size_t i = 0; i < count; ++i) {
    const auto joint = static_cast<std::size_t>(command.motor_ids[i]);
    const driver::JointLimits& limits = joint_limits[joint];
    JointTargetUpdate& update = out.joints[i];
    update.joint = static_cast<std::uint8_t>(joint);
    const auto out_of_range = [&](const char* field, float value, double low, double high) {
      std::ostringstream text;
      text << field << " " << value << " for motor " << joint << " ('" << model.joint_names[joint] << "') is outside "
           << low << ".." << high;
      return reject(Rejection::kOutOfRange, text.str());
    };
    const auto take = [&](const std::vector<float>& values, TargetField field, float& slot, const char* name,
                          double low, double high) -> std::optional<Verdict> {
      if (values.empty()) return std::nullopt;
      slot = values[i];
      if (!within_or_clamped(slot, low, high, model.limit_policy, out.clamped)) {
        return out_of_range(name, values[i], low, high);
      }
      update.fields = static_cast<std::uint8_t>(update.fields | field);
      return std::nullopt;
    };
    if (auto v = take(command.positions, kHasPosition, update.position, "position", limits.position_min_rad,
                      limits.position_max_rad)) {
      return *v;
    }
    if (auto v = take(command.velocities, kHasVelocity, update.velocity, "velocity", -limits.velocity_max_rad_s,
                      limits.velocity_max_rad_s)) {
      return *v;
    }
    if (auto v =
            take(command.torques, kHasTorque, update.torque, "torque", -limits.effort_max_nm, limits.effort_max_nm)) {
      return *v;
    }
    // Negative gains are never clamped: they are a sign error, not an overshoot.
    for (const auto& [values, name] : {std::pair{&command.kp, "kp"}, std::pair{&command.kd, "kd"}}) {
      if (!values->empty() && (*values)[i] < 0) {
        return reject(Rejection::kOutOfRange,
                      std::string(name) + " for motor " + std::to_string(joint) + " is negative; gains must be >= 0");
      }
    }
    if (auto v = take(command.kp, kHasKp, update.kp, "kp", 0, limits.kp_max)) return *v;
    if (auto v = take(command.kd, kHasKd, update.kd, "kd", 0, limits.kd_max)) return *v;
  }
  out.count = count;
  return {};
}

}  // namespace robotd::control
