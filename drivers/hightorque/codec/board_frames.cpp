// The USB-CDC board's packet framing (§1.6.3, errata "USB-CDC board framing", the SDK's
// lively_serial.cc): F7, cmd, len LE16, CRC-8 over cmd + len, CRC-16 over the payload (LE16,
// before the payload), payload; the admin and timeout packets of canport.cc; and re-framing a
// tty byte stream into packets.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "hightorque_codec.hpp"
#include "wire_scaling.hpp"

namespace robotd::hightorque {
namespace {

constexpr std::size_t kCommandAt = 1;
constexpr std::size_t kLengthAt = 2;
constexpr std::size_t kCrc8At = 4;
constexpr std::size_t kCrc16At = 5;
constexpr std::size_t kCrc8Span = 3;  // cmd, len_lo, len_hi

}  // namespace

std::size_t encode_board_frame(BoardCommand command, std::span<const std::uint8_t> payload,
                               std::span<std::uint8_t> out) noexcept {
  if (payload.size() > kMaxBoardPayload || out.size() < kBoardHeaderSize + payload.size()) return 0;
  out[0] = kBoardHeader;
  out[kCommandAt] = static_cast<std::uint8_t>(command);
  wire::put_u16(out, kLengthAt, static_cast<std::uint16_t>(payload.size()));
  out[kCrc8At] = board_crc8(out.subspan(kCommandAt, kCrc8Span));
  wire::put_u16(out, kCrc16At, board_crc16(payload));
  std::copy(payload.begin(), payload.end(), out.subspan(kBoardHeaderSize).begin());
  return kBoardHeaderSize + payload.size();
}

std::size_t encode_board_admin(BoardCommand command, int motor, std::span<std::uint8_t> out) noexcept {
  if (motor < 0 || motor > 0xFF) return 0;
  const std::array<std::uint8_t, 1> payload{static_cast<std::uint8_t>(motor)};
  return encode_board_frame(command, payload, out);
}

std::size_t encode_board_timeout(std::uint16_t timeout_ms, int motor_count, std::span<std::uint8_t> out) noexcept {
  if (motor_count < kMinMotorId || motor_count > kMaxMotorId) return 0;
  std::array<std::uint16_t, kMaxMotorId> timeouts{};
  timeouts.fill(timeout_ms);
  return encode_board_timeouts(std::span(timeouts).first(static_cast<std::size_t>(motor_count)), out);
}

std::size_t encode_board_timeouts(std::span<const std::uint16_t> timeout_ms_by_motor,
                                  std::span<std::uint8_t> out) noexcept {
  if (timeout_ms_by_motor.empty() || timeout_ms_by_motor.size() > static_cast<std::size_t>(kMaxMotorId)) return 0;
  std::array<std::uint8_t, std::size_t{2} * kMaxMotorId> payload{};
  for (std::size_t i = 0; i < timeout_ms_by_motor.size(); ++i) wire::put_u16(payload, 2 * i, timeout_ms_by_motor[i]);
  return encode_board_frame(BoardCommand::kTimeout, std::span(payload).first(2 * timeout_ms_by_motor.size()), out);
}

std::size_t BoardFrameSplitter::feed(std::span<const std::uint8_t> bytes) noexcept {
  std::size_t used = 0;
  while (!ready_ && used < bytes.size()) {
    if (filled_ == 0) {
      const auto rest = bytes.subspan(used);
      const auto header = std::find(rest.begin(), rest.end(), kBoardHeader);
      const auto skipped = static_cast<std::size_t>(header - rest.begin());
      skipped_bytes_ += skipped;
      used += skipped;
      if (header == rest.end()) break;
    }
    const std::size_t taken = std::min(wanted(), bytes.size() - used);
    std::copy_n(bytes.subspan(used).begin(), taken, buffer_.begin() + static_cast<std::ptrdiff_t>(filled_));
    filled_ += taken;
    used += taken;
    settle();
  }
  return used;
}

bool BoardFrameSplitter::next(BoardFrame& out) noexcept {
  if (!ready_) return false;
  out = frame_;
  ready_ = false;
  settle();  // bytes buffered after the packet (re-scanned after a bad one) may hold another
  return true;
}

std::size_t BoardFrameSplitter::wanted() const noexcept {
  if (filled_ < kBoardHeaderSize) return kBoardHeaderSize - filled_;
  return kBoardHeaderSize + wire::get_u16(buffer_, kLengthAt) - filled_;
}

void BoardFrameSplitter::settle() noexcept {
  while (!ready_ && filled_ >= kBoardHeaderSize) {
    const std::size_t length = wire::get_u16(buffer_, kLengthAt);
    const bool header_ok = board_crc8(std::span(buffer_).subspan(kCommandAt, kCrc8Span)) == buffer_[kCrc8At];
    if (!header_ok || length > kMaxBoardPayload) {
      // Not a packet start after all: drop its 0xF7 and look again from the next byte.
      if (!header_ok) ++crc_errors_;
      ++skipped_bytes_;
      discard(1);
      continue;
    }
    if (filled_ < kBoardHeaderSize + length) return;
    const auto payload = std::span(buffer_).subspan(kBoardHeaderSize, length);
    if (board_crc16(payload) != wire::get_u16(buffer_, kCrc16At)) {
      ++crc_errors_;
      ++skipped_bytes_;
      discard(1);
      continue;
    }
    frame_.command = static_cast<BoardCommand>(buffer_[kCommandAt]);
    frame_.length = static_cast<std::uint16_t>(length);
    std::copy(payload.begin(), payload.end(), frame_.payload.begin());
    ready_ = true;
    discard(kBoardHeaderSize + length);
  }
}

void BoardFrameSplitter::discard(std::size_t count) noexcept {
  const auto end = buffer_.begin() + static_cast<std::ptrdiff_t>(filled_);
  const auto next_header = std::find(buffer_.begin() + static_cast<std::ptrdiff_t>(count), end, kBoardHeader);
  const auto kept_from = static_cast<std::size_t>(next_header - buffer_.begin());
  skipped_bytes_ += kept_from - count;
  std::copy(next_header, end, buffer_.begin());
  filled_ -= kept_from;
}

}  // namespace robotd::hightorque
