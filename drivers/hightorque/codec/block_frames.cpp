// One-to-many block frames (§1.6.1 "One-to-many", errata "one-to-many capacity", the vendor's
// motor_many.c): int16 slots of motors in id order under id 0x18000 | block code, the query
// code in the last byte of the padded frame.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>

#include "command_layouts.hpp"
#include "hightorque_codec.hpp"
#include "wire_scaling.hpp"

namespace robotd::hightorque {
namespace {

constexpr std::uint8_t kFlagSet = 1;  // 1-byte slots: non-zero = apply

/// A frame carrying the slots of `count` motors, every one unset (2-byte fields 0x8000, flags 0)
/// and the query code last. The padding before the query code holds unset slots where whole
/// ones fit, 0 after them: a motor that reads a slot from the padding sees no command (the
/// vendor leaves whatever its buffer held there).
transport::CanMessage unset_frame(const layouts::BlockForm& form, std::size_t frame, std::size_t count, Query query) {
  transport::CanMessage message = wire::fd_frame(command_id(Width::kInt16, form.first_code + static_cast<int>(frame)),
                                                 count * form.slot_bytes() + 1);
  if (!form.fields.empty()) {
    for (std::size_t field = 0; field < form.slots_in(message.length) * form.fields.size(); ++field) {
      wire::put_u16(message.data, 2 * field, wire::kUnset16);
    }
  }
  message.data[message.length - 1U] = static_cast<std::uint8_t>(query);
  return message;
}

void write_slot(const layouts::BlockForm& form, const BlockSlot& slot, const MotorScaling& scaling,
                transport::CanMessage& message) {
  const auto index = static_cast<std::size_t>(slot.motor - 1) % form.motors_per_frame;
  const std::size_t at = index * form.slot_bytes();
  if (form.fields.empty()) {
    message.data[at] = kFlagSet;
    return;
  }
  layouts::put_fields(message.data, at, Width::kInt16, form.fields, slot.command, scaling);
}

}  // namespace

std::size_t encode_block(std::span<const BlockSlot> slots, Query query,
                         std::span<const MotorScaling> scaling_by_motor_id, int motor_count,
                         std::span<transport::CanMessage> out) noexcept {
  if (slots.empty() || motor_count < kMinMotorId || motor_count > kMaxBlockMotorId) return 0;
  const Mode mode = slots.front().command.mode;
  const layouts::BlockForm* form = layouts::block_form_for_mode(mode);
  if (form == nullptr) return 0;
  for (const BlockSlot& slot : slots) {
    if (slot.command.mode != mode || slot.motor < kMinMotorId || slot.motor > motor_count ||
        static_cast<std::size_t>(slot.motor) >= scaling_by_motor_id.size()) {
      return 0;
    }
  }
  // Every motor of the port has its slot, as the vendor sends them: ⌈motor_count / per frame⌉ frames.
  const auto motors = static_cast<std::size_t>(motor_count);
  const std::size_t frames = (motors + form->motors_per_frame - 1) / form->motors_per_frame;
  if (frames > out.size()) return 0;
  for (std::size_t frame = 0; frame < frames; ++frame) {
    const std::size_t first = frame * form->motors_per_frame;
    out[frame] = unset_frame(*form, frame, std::min<std::size_t>(form->motors_per_frame, motors - first), query);
  }
  for (const BlockSlot& slot : slots) {
    const auto frame = static_cast<std::size_t>(slot.motor - 1) / form->motors_per_frame;
    write_slot(*form, slot, scaling_by_motor_id[static_cast<std::size_t>(slot.motor)], out[frame]);
  }
  return frames;
}

std::size_t encode_block_system(BlockSystem what, std::span<const int> motors, Query query, int motor_count,
                                std::span<transport::CanMessage> out) noexcept {
  const layouts::BlockForm* form = layouts::block_form_for_request(
      what == BlockSystem::kSoftReboot ? MotorRequest::Kind::kSoftReboot : MotorRequest::Kind::kSetZero);
  if (form == nullptr || motors.empty() || out.empty() || motor_count < kMinMotorId || motor_count > kMaxBlockMotorId) {
    return 0;
  }
  for (const int motor : motors) {
    if (motor < kMinMotorId || motor > motor_count) return 0;
  }
  out[0] = unset_frame(*form, 0, static_cast<std::size_t>(motor_count), query);
  for (const int motor : motors) out[0].data[static_cast<std::size_t>(motor - 1)] = kFlagSet;
  return 1;
}

}  // namespace robotd::hightorque
