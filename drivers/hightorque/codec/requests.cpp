// The motor's side of the CAN-FD protocol, for the simulator: command frames (single-motor
// modes, queries, system commands, one-to-many blocks) back into per-motor requests.
#include <cstddef>
#include <cstdint>
#include <span>

#include "command_layouts.hpp"
#include "hightorque_codec.hpp"
#include "motor_units.hpp"
#include "wire_scaling.hpp"

namespace robotd::hightorque {
namespace {

constexpr std::uint32_t kBlockBit = 0x80;

/// Fills the mode's parameters from `bytes` at `width`, starting at `at`.
void decode_fields(std::span<const layouts::Field> fields, wire::ConstBytes bytes, std::size_t at, Width width,
                   const MotorScaling& scaling, MotorRequest& request) {
  for (const layouts::Field field : fields) {
    const units::Quantity quantity = layouts::quantity(field);
    layouts::assign(request, field,
                    units::from_counts(quantity, wire::get_command_counts(bytes, at, width), width, scaling));
    at += wire::width_bytes(width);
  }
}

/// 03 … : the configuration operations and the status push.
bool decode_system(wire::ConstBytes bytes, MotorRequest& request) {
  if (bytes.size() < 3) return false;
  if (bytes[1] == 0x03) {
    switch (bytes[2]) {
      case 0x01:
        request.kind = MotorRequest::Kind::kSoftReboot;
        return true;
      case 0x02:
        request.kind = MotorRequest::Kind::kSaveToFlash;
        return true;
      case 0x03:
        request.kind = MotorRequest::Kind::kSetZero;
        return true;
      case 0x04:
        if (bytes.size() < 4) return false;
        request.kind = MotorRequest::Kind::kChangeId;
        request.new_id = bytes[3];
        return true;
      default:
        return false;
    }
  }
  if (bytes[1] != 0x00 || bytes[2] != 0x05 || bytes.size() < 8 || !layouts::is_query(bytes[3])) return false;
  request.kind = MotorRequest::Kind::kStatusPush;
  request.query = static_cast<Query>(bytes[3]);
  request.period_us = wire::get_u32(bytes, 4);
  return true;
}

/// 00 <code>: a query or an info request, no mode change.
bool decode_query(wire::ConstBytes bytes, MotorRequest& request) {
  if (bytes.size() < layouts::kHeaderBytes) return false;
  const std::uint8_t code = bytes[1];
  switch (static_cast<InfoKind>(code)) {
    case InfoKind::kFirmwareVersion:
    case InfoKind::kHardwareVersion:
    case InfoKind::kModel:
      request.kind = MotorRequest::Kind::kInfo;
      request.info = static_cast<InfoKind>(code);
      return true;
  }
  if (!layouts::is_query(code)) return false;
  request.kind = MotorRequest::Kind::kQuery;
  request.query = static_cast<Query>(code);
  return true;
}

bool decode_single(wire::ConstBytes bytes, Width width, const MotorScaling& scaling, MotorRequest& request) {
  const std::uint8_t code = bytes[0];
  if (code == 0x00) return decode_query(bytes, request);
  if (code == 0x03) return decode_system(bytes, request);
  if (code == 0x05) {
    if (bytes.size() < 3) return false;
    request.kind = MotorRequest::Kind::kCommandTimeout;
    request.timeout_ms = wire::get_u16(bytes, 1);
    return true;
  }
  if (!layouts::is_mode(code) || bytes.size() < layouts::kHeaderBytes || !layouts::is_query(bytes[1])) return false;
  const auto fields = layouts::mode_fields(static_cast<Mode>(code));
  if (bytes.size() < layouts::kHeaderBytes + fields.size() * wire::width_bytes(width)) return false;
  request.kind = MotorRequest::Kind::kCommand;
  request.command.mode = static_cast<Mode>(code);
  request.query = static_cast<Query>(bytes[1]);
  decode_fields(fields, bytes, layouts::kHeaderBytes, width, scaling, request);
  return true;
}

/// A slot addresses its motor when a flag is non-zero or any field is not the sentinel.
bool slot_addressed(const layouts::BlockForm& form, wire::ConstBytes slot) {
  if (form.fields.empty()) return slot[0] != 0;
  for (std::size_t at = 0; at < slot.size(); at += 2) {
    if (wire::get_u16(slot, at) != wire::kUnset16) return true;
  }
  return false;
}

std::size_t decode_block(std::uint8_t code, Width width, wire::ConstBytes bytes, const MotorScaling& scaling,
                         std::span<MotorRequest> out) {
  const layouts::BlockForm* form = layouts::block_form_for_code(code);
  if (width != Width::kInt16 || form == nullptr || !layouts::is_query(bytes.back())) return 0;
  const std::size_t first_motor = static_cast<std::size_t>(code - form->first_code) * form->motors_per_frame + 1;
  const std::size_t slots = form->slots_in(bytes.size());
  std::size_t written = 0;
  for (std::size_t slot = 0; slot < slots && written < out.size(); ++slot) {
    const auto slot_bytes = bytes.subspan(slot * form->slot_bytes(), form->slot_bytes());
    if (!slot_addressed(*form, slot_bytes)) continue;
    MotorRequest& request = out[written++];
    request = MotorRequest{};
    request.kind = form->kind;
    request.motor = static_cast<int>(first_motor + slot);
    request.query = static_cast<Query>(bytes.back());
    request.command.mode = form->mode;
    decode_fields(form->fields, slot_bytes, 0, Width::kInt16, scaling, request);
  }
  return written;
}

}  // namespace

std::size_t decode_request(const transport::CanMessage& message, const MotorScaling& scaling,
                           std::span<MotorRequest> out) noexcept {
  const wire::ConstBytes bytes = wire::payload(message);
  const std::uint32_t id = message.id;
  const std::uint32_t type = (id >> 16) & 0x3U;
  // Bits 28…18 (reserved, and the classic-CAN MIT flag) must be clear, bit 15 set.
  if (out.empty() || bytes.empty() || !message.extended || (id >> 18) != 0 || (id & layouts::kCommandBit) == 0 ||
      type == 0) {
    return 0;
  }
  const auto width = static_cast<Width>(type);
  const auto target = static_cast<std::uint8_t>(id & 0xFFU);
  if ((target & kBlockBit) != 0) return decode_block(target, width, bytes, scaling, out);
  if (target == 0) return 0;
  MotorRequest request;
  request.motor = target;
  request.width = width;
  if (!decode_single(bytes, width, scaling, request)) return 0;
  out[0] = request;
  return 1;
}

}  // namespace robotd::hightorque
