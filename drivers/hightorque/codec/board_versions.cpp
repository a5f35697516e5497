// The board's per-motor answers: kVersion (each motor's firmware version, one 4-byte record per
// motor) and the acknowledgements of kResetZero / kSave / kReloadConfig (one id byte per motor);
// the board's own firmware (its kSetMotorCount answer) and the function version it is given
// (the SDK's lively_serial.cc and robot.cc).
#include <cstddef>
#include <cstdint>
#include <optional>
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

BoardFunction board_function_for(const FirmwareVersion& lowest) noexcept {
  const auto at_least = [&](int major, int minor, int patch) {
    return !lowest.older_than({.major = major, .minor = minor, .patch = patch});
  };
  if (at_least(4, 4, 6)) return BoardFunction::kV5;
  if (at_least(4, 2, 3)) return BoardFunction::kV4;
  if (at_least(4, 2, 2)) return BoardFunction::kV3;
  if (at_least(4, 2, 0)) return BoardFunction::kV2;
  return BoardFunction::kV1;
}

std::optional<BoardFirmware> decode_board_firmware(std::span<const std::uint8_t> payload) noexcept {
  constexpr std::size_t kMajorAt = 2;
  constexpr std::size_t kMinorAt = 3;
  if (payload.size() <= kMinorAt) return std::nullopt;
  return BoardFirmware{.major = payload[kMajorAt], .minor = payload[kMinorAt]};
}

std::size_t encode_board_firmware(BoardFirmware firmware, std::span<std::uint8_t> out) noexcept {
  if (out.size() < 4 || !fits_a_byte(firmware.major) || !fits_a_byte(firmware.minor)) return 0;
  out[0] = 0;
  out[1] = 0;
  out[2] = static_cast<std::uint8_t>(firmware.major);
  out[3] = static_cast<std::uint8_t>(firmware.minor);
  return 4;
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
