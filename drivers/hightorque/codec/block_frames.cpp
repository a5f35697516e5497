// One-to-many block frames (§1.6.1 "One-to-many", errata "one-to-many capacity", the vendor's
// motor_many.c): int16 slots of motors in id order under id 0x18000 | block code, the query
// code in the last byte of the padded frame.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "command_layouts.hpp"
#include "hightorque_codec.hpp"
#include "wire_scaling.hpp"

namespace robotd::hightorque {
namespace {

constexpr std::size_t kMaxBlockFrames = 5;  // MIT: 0x98…0x9C
constexpr std::uint8_t kFlagSet = 1;        // 1-byte slots: non-zero = apply

/// Marks every slot unset, padding included (the vendor pads with stale bytes; unset slots keep a
/// motor beyond the last commanded one from reading the padding as a command).
void fill_unset(const layouts::BlockForm& form, transport::CanMessage& message) {
  if (form.fields.empty()) return;  // flag slots: 0 is already "not this motor"
  const std::size_t fields = form.slots_in(message.length) * form.fields.size();
  for (std::size_t field = 0; field < fields; ++field) wire::put_u16(message.data, 2 * field, wire::kUnset16);
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
                         std::span<const MotorScaling> scaling_by_motor_id,
                         std::span<transport::CanMessage> out) noexcept {
  if (slots.empty()) return 0;
  const Mode mode = slots.front().command.mode;
  const layouts::BlockForm* form = layouts::block_form_for_mode(mode);
  if (form == nullptr) return 0;

  // Per frame of the form: how many slots it needs (its highest commanded motor), 0 = not sent.
  std::array<std::size_t, kMaxBlockFrames> slots_in_frame{};
  for (const BlockSlot& slot : slots) {
    if (slot.command.mode != mode || slot.motor < kMinMotorId || slot.motor > kMaxBlockMotorId ||
        static_cast<std::size_t>(slot.motor) >= scaling_by_motor_id.size()) {
      return 0;
    }
    const auto index = static_cast<std::size_t>(slot.motor - 1);
    std::size_t& needed = slots_in_frame[index / form->motors_per_frame];
    needed = std::max(needed, index % form->motors_per_frame + 1);
  }
  const auto frames = static_cast<std::size_t>(
      std::count_if(slots_in_frame.begin(), slots_in_frame.end(), [](std::size_t needed) { return needed > 0; }));
  if (frames > out.size()) return 0;

  // Where each frame of the form lands in `out`.
  std::array<std::size_t, kMaxBlockFrames> position{};
  std::size_t written = 0;
  for (std::size_t frame = 0; frame < form->frames; ++frame) {
    if (slots_in_frame[frame] == 0) continue;
    transport::CanMessage& message = out[written];
    message = wire::fd_frame(command_id(Width::kInt16, form->first_code + static_cast<int>(frame)),
                             slots_in_frame[frame] * form->slot_bytes() + 1);
    fill_unset(*form, message);
    message.data[message.length - 1U] = static_cast<std::uint8_t>(query);
    position[frame] = written++;
  }
  for (const BlockSlot& slot : slots) {
    const auto frame = static_cast<std::size_t>(slot.motor - 1) / form->motors_per_frame;
    write_slot(*form, slot, scaling_by_motor_id[static_cast<std::size_t>(slot.motor)], out[position[frame]]);
  }
  return written;
}

}  // namespace robotd::hightorque
