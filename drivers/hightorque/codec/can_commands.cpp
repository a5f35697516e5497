// CAN-FD identifiers and single-motor frames (§1.6.1, errata "command / reply IDs"): a mode
// command [mode, query, params…] at the chosen width, and a bare query [00, query].
#include <cstddef>
#include <cstdint>

#include "command_layouts.hpp"
#include "hightorque_codec.hpp"
#include "wire_scaling.hpp"

namespace robotd::hightorque {
namespace {

std::uint32_t type_bits(Width width) { return std::uint32_t{static_cast<std::uint8_t>(width)} << 16; }

}  // namespace

std::uint32_t command_id(Width width, int motor_or_block) noexcept {
  return type_bits(width) | layouts::kCommandBit | (static_cast<std::uint32_t>(motor_or_block) & 0xFFU);
}

std::uint32_t reply_id(Width width, int motor) noexcept {
  return type_bits(width) | ((static_cast<std::uint32_t>(motor) & 0x7FU) << 8);
}

transport::CanMessage encode_command(int motor, const MotorCommand& command, Width width, Query query,
                                     const MotorScaling& scaling) noexcept {
  const auto fields = layouts::mode_fields(command.mode);
  transport::CanMessage message =
      wire::motor_frame(width, motor, layouts::kHeaderBytes + fields.size() * wire::width_bytes(width));
  message.data[0] = static_cast<std::uint8_t>(command.mode);
  message.data[1] = static_cast<std::uint8_t>(query);
  layouts::put_fields(message.data, layouts::kHeaderBytes, width, fields, command, scaling);
  return message;
}

transport::CanMessage encode_query(int motor, Query query, Width width) noexcept {
  transport::CanMessage message = wire::motor_frame(width, motor, layouts::kHeaderBytes);
  message.data[1] = static_cast<std::uint8_t>(query);
  return message;
}

}  // namespace robotd::hightorque
