// What each command frame carries (§1.6.1 mode table, errata "one-to-many capacity", the
// vendor's motor_many.h): the MotorCommand fields of each mode in wire order, and the block
// (one-to-many) forms with their codes, capacities and slot layouts. Shared by the encoders and
// the motor-side decoder. Internal to the codec.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>

#include "hightorque_codec.hpp"
#include "motor_units.hpp"
#include "wire_scaling.hpp"

namespace robotd::hightorque::layouts {

/// The CAN id bit that marks a command frame, and the bytes before a command's fields.
inline constexpr std::uint32_t kCommandBit = 0x8000;
inline constexpr std::size_t kHeaderBytes = 2;  // mode, query

/// One parameter of a command. kZeroD is the d axis of the voltage / current modes, always 0.
enum class Field : std::uint8_t {
  kPosition,
  kVelocity,
  kAcceleration,
  kTorque,
  kKp,
  kKd,
  kZeroD,
  kVoltageQ,
  kCurrentQ
};

constexpr units::Quantity quantity(Field field) noexcept {
  switch (field) {
    case Field::kPosition:
      return units::Quantity::kPosition;
    case Field::kVelocity:
      return units::Quantity::kVelocity;
    case Field::kAcceleration:
      return units::Quantity::kAcceleration;
    case Field::kTorque:
      return units::Quantity::kTorque;
    case Field::kKp:
    case Field::kKd:
      return units::Quantity::kGain;
    case Field::kZeroD:
    case Field::kVoltageQ:
    case Field::kCurrentQ:
      return units::Quantity::kElectrical;
  }
  return units::Quantity::kElectrical;
}

inline double value(const MotorCommand& command, Field field) noexcept {
  switch (field) {
    case Field::kPosition:
      return command.position_rad;
    case Field::kVelocity:
      return command.velocity_rad_s;
    case Field::kAcceleration:
      return command.acceleration_rad_s2;
    case Field::kTorque:
      return command.torque_nm;
    case Field::kKp:
      return command.kp;
    case Field::kKd:
      return command.kd;
    case Field::kZeroD:
      return 0.0;
    case Field::kVoltageQ:
      return command.voltage_q_v;
    case Field::kCurrentQ:
      return command.current_q_a;
  }
  return 0.0;
}

/// Stores a decoded field; NaN (the wire's "no value") leaves the has_* flag false.
inline void assign(MotorRequest& request, Field field, double decoded) noexcept {
  const bool present = !std::isnan(decoded);
  MotorCommand& command = request.command;
  switch (field) {
    case Field::kPosition:
      command.position_rad = decoded;
      request.has_position = present;
      return;
    case Field::kVelocity:
      command.velocity_rad_s = decoded;
      request.has_velocity = present;
      return;
    case Field::kAcceleration:
      command.acceleration_rad_s2 = decoded;
      return;
    case Field::kTorque:
      command.torque_nm = decoded;
      request.has_torque = present;
      return;
    case Field::kKp:
      command.kp = decoded;
      request.has_kp = present;
      return;
    case Field::kKd:
      command.kd = decoded;
      request.has_kd = present;
      return;
    case Field::kZeroD:
      return;
    case Field::kVoltageQ:
      command.voltage_q_v = decoded;
      return;
    case Field::kCurrentQ:
      command.current_q_a = decoded;
      return;
  }
}

/// Writes `fields` of `command` from byte `at` on, each `width` wide.
inline void put_fields(wire::Bytes bytes, std::size_t at, Width width, std::span<const Field> fields,
                       const MotorCommand& command, const MotorScaling& scaling) noexcept {
  for (const Field field : fields) {
    const units::Quantity q = quantity(field);
    wire::put_counts(bytes, at, width, units::to_counts(q, value(command, field), width, scaling));
    at += wire::width_bytes(width);
  }
}

inline constexpr std::array<Field, 1> kPositionFields{Field::kPosition};
inline constexpr std::array<Field, 1> kVelocityFields{Field::kVelocity};
inline constexpr std::array<Field, 1> kTorqueFields{Field::kTorque};
inline constexpr std::array<Field, 1> kVoltageQFields{Field::kVoltageQ};
inline constexpr std::array<Field, 1> kCurrentQFields{Field::kCurrentQ};
inline constexpr std::array<Field, 2> kVoltageFields{Field::kZeroD, Field::kVoltageQ};
inline constexpr std::array<Field, 2> kCurrentFields{Field::kZeroD, Field::kCurrentQ};
inline constexpr std::array<Field, 2> kVelocityAccelerationFields{Field::kVelocity, Field::kAcceleration};
inline constexpr std::array<Field, 3> kPositionVelocityTorqueFields{Field::kPosition, Field::kVelocity, Field::kTorque};
inline constexpr std::array<Field, 3> kPositionVelocityAccelerationFields{Field::kPosition, Field::kVelocity,
                                                                          Field::kAcceleration};
inline constexpr std::array<Field, 4> kPositionVelocityGainFields{Field::kPosition, Field::kVelocity, Field::kKp,
                                                                  Field::kKd};
inline constexpr std::array<Field, 5> kMitFields{Field::kPosition, Field::kVelocity, Field::kTorque, Field::kKp,
                                                 Field::kKd};

/// The parameters after [mode, query] in a single-motor frame.
constexpr std::span<const Field> mode_fields(Mode mode) noexcept {
  switch (mode) {
    case Mode::kStop:
    case Mode::kBrake:
      return {};
    case Mode::kVoltage:
      return kVoltageFields;
    case Mode::kCurrent:
      return kCurrentFields;
    case Mode::kTorque:
      return kTorqueFields;
    case Mode::kVelocity:
      return kVelocityFields;
    case Mode::kPosition:
      return kPositionFields;
    case Mode::kVelocityAcceleration:
      return kVelocityAccelerationFields;
    case Mode::kPositionVelocityTorque:
      return kPositionVelocityTorqueFields;
    case Mode::kPositionVelocityAcceleration:
      return kPositionVelocityAccelerationFields;
    case Mode::kMit:
      return kMitFields;
  }
  return {};
}

constexpr bool is_mode(std::uint8_t code) noexcept {
  return code == static_cast<std::uint8_t>(Mode::kStop) ||
         (code >= static_cast<std::uint8_t>(Mode::kBrake) && code <= static_cast<std::uint8_t>(Mode::kMit));
}

constexpr bool is_query(std::uint8_t code) noexcept {
  switch (static_cast<Query>(code)) {
    case Query::kNone:
    case Query::kCounter:
    case Query::kState:
    case Query::kStateTemperature:
    case Query::kCompact:
      return true;
  }
  return false;
}

/// A one-to-many form: block codes first_code … first_code + frames − 1, each frame carrying
/// `motors_per_frame` slots of motors in id order (frame k starts at motor k·motors_per_frame + 1).
/// Flag forms (no fields) have 1-byte slots: non-zero = apply.
struct BlockForm {
  std::uint8_t first_code = 0;
  std::uint8_t frames = 1;
  std::uint8_t motors_per_frame = 0;
  MotorRequest::Kind kind = MotorRequest::Kind::kCommand;
  Mode mode = Mode::kStop;
  std::span<const Field> fields;

  constexpr std::size_t slot_bytes() const noexcept { return fields.empty() ? 1 : 2 * fields.size(); }
  /// How many whole slots a frame of `length` bytes holds before its query byte.
  constexpr std::size_t slots_in(std::size_t length) const noexcept {
    return length == 0 ? 0 : std::min<std::size_t>((length - 1) / slot_bytes(), motors_per_frame);
  }
};

// Every form covers motors 1…30 (kMaxBlockMotorId) in at most 60 data bytes per frame.
inline constexpr std::array<BlockForm, 13> kBlockForms{{
    {0x80, 1, 30, MotorRequest::Kind::kCommand, Mode::kPosition, kPositionFields},
    {0x81, 1, 30, MotorRequest::Kind::kCommand, Mode::kVelocity, kVelocityFields},
    {0x82, 1, 30, MotorRequest::Kind::kCommand, Mode::kTorque, kTorqueFields},
    {0x83, 1, 30, MotorRequest::Kind::kCommand, Mode::kVoltage, kVoltageQFields},
    {0x84, 1, 30, MotorRequest::Kind::kCommand, Mode::kCurrent, kCurrentQFields},
    {0x85, 1, 30, MotorRequest::Kind::kCommand, Mode::kStop, {}},
    {0x86, 1, 30, MotorRequest::Kind::kCommand, Mode::kBrake, {}},
    {0x87, 1, 30, MotorRequest::Kind::kSoftReboot, Mode::kStop, {}},
    {0x88, 1, 30, MotorRequest::Kind::kSetZero, Mode::kStop, {}},
    {0x90, 2, 15, MotorRequest::Kind::kCommand, Mode::kVelocityAcceleration, kVelocityAccelerationFields},
    {0x92, 3, 10, MotorRequest::Kind::kCommand, Mode::kPositionVelocityTorque, kPositionVelocityTorqueFields},
    {0x95, 3, 10, MotorRequest::Kind::kCommand, Mode::kPositionVelocityAcceleration,
     kPositionVelocityAccelerationFields},
    {0x98, 5, 6, MotorRequest::Kind::kCommand, Mode::kMit, kMitFields},
}};

/// The form robotd sends a mode's slots in; nullptr if it has none.
inline const BlockForm* block_form_for_mode(Mode mode) noexcept {
  for (const BlockForm& form : kBlockForms) {
    if (form.kind == MotorRequest::Kind::kCommand && form.mode == mode) return &form;
  }
  return nullptr;
}

/// The flag form of a system request (kSoftReboot, kSetZero); nullptr if it has none.
inline const BlockForm* block_form_for_request(MotorRequest::Kind kind) noexcept {
  for (const BlockForm& form : kBlockForms) {
    if (form.kind == kind && kind != MotorRequest::Kind::kCommand) return &form;
  }
  return nullptr;
}

/// The form a block code belongs to; nullptr if none.
inline const BlockForm* block_form_for_code(std::uint8_t code) noexcept {
  for (const BlockForm& form : kBlockForms) {
    if (code >= form.first_code && code < form.first_code + form.frames) return &form;
  }
  return nullptr;
}

}  // namespace robotd::hightorque::layouts
