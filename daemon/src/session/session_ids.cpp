#include "session/session_ids.hpp"

#include <array>
#include <cctype>
#include <cstdint>
#include <stdexcept>
#include <sys/random.h>

namespace robotd::session {
namespace {

constexpr std::size_t kShownCharacters = 8;
constexpr char kHex[] = "0123456789abcdef";

template <std::size_t N>
std::array<std::uint8_t, N> random_bytes() {
  std::array<std::uint8_t, N> bytes{};
  std::size_t filled = 0;
  while (filled < bytes.size()) {
    const ssize_t n = getrandom(bytes.data() + filled, bytes.size() - filled, 0);
    if (n < 0) throw std::runtime_error("getrandom failed: cannot create a session identifier");
    filled += static_cast<std::size_t>(n);
  }
  return bytes;
}

void append_hex(std::string& text, std::uint8_t byte) {
  text += kHex[byte >> 4U];
  text += kHex[byte & 0x0FU];
}

}  // namespace

std::string random_session_uuid() {
  auto bytes = random_bytes<16>();
  // RFC 4122 section 4.4: version 4 in the high nibble of byte 6, variant 10 in the top bits of byte 8.
  bytes[6] = static_cast<std::uint8_t>((bytes[6] & 0x0FU) | 0x40U);
  bytes[8] = static_cast<std::uint8_t>((bytes[8] & 0x3FU) | 0x80U);
  std::string text;
  text.reserve(36);
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    if (i == 4 || i == 6 || i == 8 || i == 10) text += '-';
    append_hex(text, bytes[i]);
  }
  return text;
}

std::string random_session_id() {
  std::string text;
  text.reserve(8);
  for (const std::uint8_t byte : random_bytes<4>()) append_hex(text, byte);
  return text;
}

std::string redacted_uuid(std::string_view uuid) {
  if (uuid.empty()) return "(empty)";
  std::string shown;
  for (const char c : uuid.substr(0, kShownCharacters)) {
    shown += std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '-' ? c : '?';
  }
  return uuid.size() > kShownCharacters ? shown + "…" : shown;
}

}  // namespace robotd::session
