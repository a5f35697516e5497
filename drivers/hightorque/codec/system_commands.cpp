// System commands to one motor (§1.6.1 "System commands", errata "motor command timeout"),
// always at int16 width: reboot / save / rezero / change id (03 03 xx), the command timeout
// (05 <ms>), the periodic status push (03 00 05 <query> <µs>) and the info queries (00 0x).
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <utility>

#include "hightorque_codec.hpp"
#include "wire_scaling.hpp"

namespace robotd::hightorque {
namespace {

constexpr std::uint8_t kSystem = 0x03;
constexpr std::uint8_t kConfigure = 0x03;  // 03 03 <operation>
constexpr std::uint8_t kTimeout = 0x05;
constexpr std::uint8_t kPushOperation = 0x05;  // 03 00 05

transport::CanMessage system_frame(int motor, std::initializer_list<std::uint8_t> bytes) {
  transport::CanMessage message = wire::motor_frame(Width::kInt16, motor, bytes.size());
  std::size_t at = 0;
  for (const std::uint8_t byte : bytes) message.data[at++] = byte;
  return message;
}

}  // namespace

transport::CanMessage encode_soft_reboot(int motor) noexcept {
  return system_frame(motor, {kSystem, kConfigure, 0x01});
}

transport::CanMessage encode_save_to_flash(int motor) noexcept {
  return system_frame(motor, {kSystem, kConfigure, 0x02});
}

transport::CanMessage encode_set_zero(int motor) noexcept { return system_frame(motor, {kSystem, kConfigure, 0x03}); }

Result<transport::CanMessage> encode_change_id(int motor, int new_id) {
  for (const auto& [what, id] : {std::pair{"motor", motor}, std::pair{"new id", new_id}}) {
    if (id < kMinMotorId || id > kMaxMotorId) {
      return make_error(ErrorCode::kInvalidArgument, std::string("change id: ") + what + " " + std::to_string(id) +
                                                         " is outside the motor ids " + std::to_string(kMinMotorId) +
                                                         "…" + std::to_string(kMaxMotorId));
    }
  }
  return system_frame(motor, {kSystem, kConfigure, 0x04, static_cast<std::uint8_t>(new_id)});
}

// Neither vendor SDK builds this frame; the layout is the protocol document's ("05 F4 01" for
// 500 ms; its example row "05 1F F4 01" has a stray byte that its own description contradicts).
transport::CanMessage encode_command_timeout(int motor, std::uint16_t timeout_ms) noexcept {
  transport::CanMessage message = system_frame(motor, {kTimeout, 0, 0});
  wire::put_u16(message.data, 1, timeout_ms);
  return message;
}

transport::CanMessage encode_status_push(int motor, Query query, std::uint32_t period_us) noexcept {
  transport::CanMessage message =
      system_frame(motor, {kSystem, 0x00, kPushOperation, static_cast<std::uint8_t>(query), 0, 0, 0, 0});
  wire::put_u32(message.data, 4, period_us);
  return message;
}

transport::CanMessage encode_info_request(int motor, InfoKind kind) noexcept {
  return system_frame(motor, {0x00, static_cast<std::uint8_t>(kind)});
}

}  // namespace robotd::hightorque
