// The USB-CDC board's payloads (§1.6.3, errata "board units", the SDK's motor.cc and
// serial_struct.h): one port's int16 command slots in motor-id order, and the state records the
// board sends back (kMotorState: id, pos, vel, τ; kMotorState2: id, mode, fault, pos, vel, τ).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>

#include "command_layouts.hpp"
#include "hightorque_codec.hpp"
#include "motor_units.hpp"
#include "wire_scaling.hpp"

namespace robotd::hightorque {
namespace {

using layouts::Field;

struct SlotForm {
  BoardCommand command = BoardCommand::kPosition;
  Mode mode = Mode::kPosition;
  std::span<const Field> fields;
};

constexpr std::array<SlotForm, 9> kSlotForms{{
    {BoardCommand::kPosition, Mode::kPosition, layouts::kPositionFields},
    {BoardCommand::kVelocity, Mode::kVelocity, layouts::kVelocityFields},
    {BoardCommand::kTorque, Mode::kTorque, layouts::kTorqueFields},
    {BoardCommand::kVoltage, Mode::kVoltage, layouts::kVoltageQFields},
    {BoardCommand::kCurrent, Mode::kCurrent, layouts::kCurrentQFields},
    {BoardCommand::kPositionVelocityTorqueMax, Mode::kPositionVelocityTorque, layouts::kPositionVelocityTorqueFields},
    // kp / kd without a torque: the motor holds the impedance, no feed-forward.
    {BoardCommand::kPositionVelocityKpKd, Mode::kMit, layouts::kPositionVelocityGainFields},
    {BoardCommand::kPositionVelocityTorqueKpKdV1, Mode::kMit, layouts::kMitFields},
    {BoardCommand::kPositionVelocityTorqueKpKd, Mode::kMit, layouts::kMitFields},
}};

const SlotForm* slot_form(BoardCommand command) {
  for (const SlotForm& form : kSlotForms) {
    if (form.command == command) return &form;
  }
  return nullptr;
}

constexpr std::int16_t kBoardLimit = std::numeric_limits<std::int16_t>::max();
constexpr std::int16_t kBoardGainLimit = 32700;  // the SDK's int16_limit() on kp / kd

std::uint16_t raw16(double counts, std::int16_t limit = kBoardLimit) {
  return static_cast<std::uint16_t>(wire::truncate<std::int16_t>(counts, limit));
}

/// A field's board count as the SDK's motor.cc computes it: position (float)rad / 2π_f × 1e4 and
/// velocity × 4e3 (the quotient in float, the product in double), torque (τ − d) / k in double,
/// gains (float)(kp / k_pid) × 10 × 2π_f in float and saturated at ±32700, volts and amps
/// (float) × 10 in float; then truncated
/// (saturated at ±32767 where the SDK's cast wraps). NaN reads as the board's "unset" (0x8000
/// for a position, 0 for the rest).
std::uint16_t board_raw(Field field, double value, const MotorScaling& scaling) {
  if (std::isnan(value)) return field == Field::kPosition ? wire::kUnset16 : std::uint16_t{0};
  const auto given = static_cast<float>(value);
  switch (layouts::quantity(field)) {
    case units::Quantity::kPosition:
      return raw16(static_cast<double>(given / units::kTwoPiF) * 1e4);
    case units::Quantity::kVelocity:
      return raw16(static_cast<double>(given / units::kTwoPiF) * 4e3);
    case units::Quantity::kTorque:
      return raw16((static_cast<double>(given) - scaling.torque_offset_nm) / scaling.torque_per_unit);
    case units::Quantity::kGain: {
      const auto per_unit = static_cast<float>(static_cast<double>(given) / scaling.gain_factor);
      return raw16(static_cast<double>(per_unit * 10.0F * units::kTwoPiF), kBoardGainLimit);
    }
    case units::Quantity::kElectrical:
      return raw16(static_cast<double>(given * 10.0F));
    default:
      return raw16(static_cast<double>(given));
  }
}

/// A board count back in robotd's units, as the SDK's fresh_data() reads a state record:
/// position (float)(raw × 2π_f / 1e4), velocity / 4e3, torque (float)(raw × k + d).
double board_value(Field field, std::uint16_t raw, const MotorScaling& scaling) {
  const auto counts = static_cast<std::int16_t>(raw);
  switch (layouts::quantity(field)) {
    case units::Quantity::kPosition:
      return static_cast<float>(static_cast<double>(static_cast<float>(counts) * units::kTwoPiF) / 1e4);
    case units::Quantity::kVelocity:
      return static_cast<float>(static_cast<double>(static_cast<float>(counts) * units::kTwoPiF) / 4e3);
    case units::Quantity::kTorque:
      return static_cast<float>(counts * scaling.torque_per_unit + scaling.torque_offset_nm);
    case units::Quantity::kGain:
      return counts / 10.0 / units::kTwoPiF * scaling.gain_factor;
    case units::Quantity::kElectrical:
      return counts / 10.0;
    default:
      return counts;
  }
}

bool has_scaling(int motor, std::span<const MotorScaling> scaling_by_motor_id) {
  return motor >= kMinMotorId && static_cast<std::size_t>(motor) < scaling_by_motor_id.size();
}

/// The record size of a state command; 0 if `command` is not one.
std::size_t state_record_size(BoardCommand command) {
  if (command == BoardCommand::kMotorState) return kBoardShortStateRecordSize;
  if (command == BoardCommand::kMotorState2) return kBoardStateRecordSize;
  return 0;
}

}  // namespace

BoardSlotBuffer::BoardSlotBuffer(int motor_count) noexcept : motor_count_(motor_count) {}

std::span<const std::uint8_t> BoardSlotBuffer::update(BoardCommand command, std::span<const BlockSlot> slots,
                                                      std::span<const MotorScaling> scaling_by_motor_id) noexcept {
  const SlotForm* form = slot_form(command);
  if (form == nullptr || motor_count_ < kMinMotorId || motor_count_ > kMaxMotorId) return {};
  for (const BlockSlot& slot : slots) {
    if (!has_scaling(slot.motor, scaling_by_motor_id) || slot.motor > motor_count_) return {};
  }
  const std::size_t slot_bytes = 2 * form->fields.size();
  const std::size_t size = static_cast<std::size_t>(motor_count_) * slot_bytes;
  if (!has_command_ || command != command_) {
    // A mode change resets every slot: position unset, the rest 0.
    for (std::size_t at = 0; at < size; at += 2) {
      const bool position = form->fields[(at % slot_bytes) / 2] == Field::kPosition;
      wire::put_u16(payload_, at, position ? wire::kUnset16 : std::uint16_t{0});
    }
    has_command_ = true;
    command_ = command;
  }
  for (const BlockSlot& slot : slots) {
    const MotorScaling& scaling = scaling_by_motor_id[static_cast<std::size_t>(slot.motor)];
    std::size_t at = static_cast<std::size_t>(slot.motor - 1) * slot_bytes;
    for (const Field field : form->fields) {
      wire::put_u16(payload_, at, board_raw(field, layouts::value(slot.command, field), scaling));
      at += 2;
    }
  }
  return std::span(payload_).first(size);
}

std::size_t decode_board_slots(BoardCommand command, std::span<const std::uint8_t> payload,
                               std::span<const MotorScaling> scaling_by_motor_id,
                               std::span<MotorRequest> out) noexcept {
  const SlotForm* form = slot_form(command);
  if (form == nullptr) return 0;
  const std::size_t slot_bytes = 2 * form->fields.size();
  std::size_t written = 0;
  for (std::size_t slot = 0; (slot + 1) * slot_bytes <= payload.size() && written < out.size(); ++slot) {
    const int motor = static_cast<int>(slot) + 1;
    if (!has_scaling(motor, scaling_by_motor_id)) continue;
    const MotorScaling& scaling = scaling_by_motor_id[slot + 1];
    MotorRequest& request = out[written++];
    request = MotorRequest{};
    request.motor = motor;
    request.command.mode = form->mode;
    std::size_t at = slot * slot_bytes;
    for (const Field field : form->fields) {
      const std::uint16_t raw = wire::get_u16(payload, at);
      const bool unset = field == Field::kPosition && raw == wire::kUnset16;
      layouts::assign(request, field,
                      unset ? std::numeric_limits<double>::quiet_NaN() : board_value(field, raw, scaling));
      at += 2;
    }
  }
  return written;
}

std::size_t decode_board_states(BoardCommand command, std::span<const std::uint8_t> payload,
                                std::span<const MotorScaling> scaling_by_motor_id,
                                std::span<BoardMotorState> out) noexcept {
  const std::size_t record_size = state_record_size(command);
  if (record_size == 0) return 0;
  std::size_t written = 0;
  for (std::size_t at = 0; at + record_size <= payload.size() && written < out.size(); at += record_size) {
    const auto record = payload.subspan(at, record_size);
    const int motor = record[0];
    if (!has_scaling(motor, scaling_by_motor_id)) continue;
    const MotorScaling& scaling = scaling_by_motor_id[record[0]];
    BoardMotorState& state = out[written++];
    state = BoardMotorState{};
    state.motor = motor;
    std::size_t field_at = 1;
    if (record_size == kBoardStateRecordSize) {
      state.mode = record[1];
      state.fault = record[2];
      field_at = 3;
    }
    state.position_rad = board_value(Field::kPosition, wire::get_u16(record, field_at), scaling);
    state.velocity_rad_s = board_value(Field::kVelocity, wire::get_u16(record, field_at + 2), scaling);
    state.torque_nm = board_value(Field::kTorque, wire::get_u16(record, field_at + 4), scaling);
  }
  return written;
}

std::size_t encode_board_states(BoardCommand command, std::span<const BoardMotorState> states,
                                std::span<const MotorScaling> scaling_by_motor_id,
                                std::span<std::uint8_t> out) noexcept {
  const std::size_t record_size = state_record_size(command);
  const std::size_t size = states.size() * record_size;
  if (record_size == 0 || size > out.size() || size > kMaxBoardPayload) return 0;
  std::size_t at = 0;
  for (const BoardMotorState& state : states) {
    if (!has_scaling(state.motor, scaling_by_motor_id)) return 0;
    const MotorScaling& scaling = scaling_by_motor_id[static_cast<std::size_t>(state.motor)];
    out[at++] = static_cast<std::uint8_t>(state.motor);
    if (record_size == kBoardStateRecordSize) {
      out[at++] = state.mode;
      out[at++] = state.fault;
    }
    wire::put_u16(out, at, board_raw(Field::kPosition, state.position_rad, scaling));
    wire::put_u16(out, at + 2, board_raw(Field::kVelocity, state.velocity_rad_s, scaling));
    wire::put_u16(out, at + 4, board_raw(Field::kTorque, state.torque_nm, scaling));
    at += 6;
  }
  return size;
}

}  // namespace robotd::hightorque
