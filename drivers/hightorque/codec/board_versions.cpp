// The board's per-motor answers: kVersion (each motor's firmware version, one 4-byte record per
// motor) and the acknowledgements of kResetZero / kSave / kReloadConfig (one id byte per motor).
#include <cstddef>
#include <cstdint>
#include <span>

#include "hightorque_codec.hpp"

namespace robotd::hightorque {
namespace {

bool fits_a_byte(int value) { return value >= 0 && value <= 0xFF; }

}  // namespace

std::size_t decode_board_acknowledgements(BoardCommand command, std::span<const std::uint8_t> payload,
                                          std::span<CommandResult> out) noexcept {
  if (command != BoardCommand::kResetZero && command != BoardCommand::kSave && command != BoardCommand::kReloadConfig) {
    return 0;
  }
  std::size_t written = 0;
  for (const std::uint8_t motor : payload) {
    if (motor == 0 || written == out.size()) continue;
    out[written++] = CommandResult{.motor = motor, .success = true, .code = 0};
  }
  return written;
}

std::size_t decode_board_versions(std::span<const std::uint8_t> payload, std::span<FirmwareVersion> out) noexcept {
  std::size_t written = 0;
  for (std::size_t at = 0; at + kBoardVersionRecordSize <= payload.size() && written < out.size();
       at += kBoardVersionRecordSize) {
    if (payload[at] == 0) continue;
    out[written++] = FirmwareVersion{
        .motor = payload[at], .major = payload[at + 1], .minor = payload[at + 2], .patch = payload[at + 3]};
  }
  return written;
}

std::size_t encode_board_versions(std::span<const FirmwareVersion> versions, std::span<std::uint8_t> out) noexcept {
  const std::size_t size = versions.size() * kBoardVersionRecordSize;
  if (size > out.size() || size > kMaxBoardPayload) return 0;
  std::size_t at = 0;
  for (const FirmwareVersion& version : versions) {
    if (!fits_a_byte(version.motor) || !fits_a_byte(version.major) || !fits_a_byte(version.minor) ||
        !fits_a_byte(version.patch)) {
      return 0;
    }
    for (const int field : {version.motor, version.major, version.minor, version.patch}) {
      out[at++] = static_cast<std::uint8_t>(field);
    }
  }
  return size;
}

}  // namespace robotd::hightorque
