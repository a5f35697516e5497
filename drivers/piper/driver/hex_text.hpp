// Hex text for the driver's messages: CAN ids as 0x2A1, bytes and offsets as 0x10.
#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <string>

namespace robotd::piper {

/// `value` as "0x" and at least `digits` upper-case hex digits.
inline std::string hex_text(std::uint32_t value, int digits) {
  std::array<char, 16> text{};
  std::snprintf(text.data(), text.size(), "0x%0*X", digits, value);
  return text.data();
}

inline std::string can_id_text(std::uint32_t id) { return hex_text(id, 3); }

}  // namespace robotd::piper
