// The USB-CDC board's checksums (errata "USB-CDC board framing"): CRC-8/MAXIM (reflected 0x31)
// started at 0xFF over cmd and length, and CRC-16/MCRF4XX (reflected 0x1021, init 0xFFFF, no
// final XOR) over the payload. Tables are built at compile time from the polynomials.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "hightorque_codec.hpp"

namespace robotd::hightorque {
namespace {

/// The byte-at-a-time table of a reflected CRC with polynomial `reflected_poly`.
template <typename Crc>
constexpr std::array<Crc, 256> reflected_table(Crc reflected_poly) {
  std::array<Crc, 256> table{};
  for (std::size_t byte = 0; byte < table.size(); ++byte) {
    auto crc = static_cast<Crc>(byte);
    for (int bit = 0; bit < 8; ++bit) {
      crc = (crc & 1U) != 0 ? static_cast<Crc>((crc >> 1) ^ reflected_poly) : static_cast<Crc>(crc >> 1);
    }
    table[byte] = crc;
  }
  return table;
}

constexpr auto kCrc8Table = reflected_table<std::uint8_t>(0x8C);
constexpr auto kCrc16Table = reflected_table<std::uint16_t>(0x8408);

}  // namespace

std::uint8_t board_crc8(std::span<const std::uint8_t> bytes) noexcept {
  std::uint8_t crc = 0xFF;
  for (const std::uint8_t byte : bytes) crc = kCrc8Table[static_cast<std::uint8_t>(crc ^ byte)];
  return crc;
}

std::uint16_t board_crc16(std::span<const std::uint8_t> bytes) noexcept {
  std::uint16_t crc = 0xFFFF;
  for (const std::uint8_t byte : bytes) {
    crc = static_cast<std::uint16_t>((crc >> 8) ^ kCrc16Table[(crc ^ byte) & 0xFFU]);
  }
  return crc;
}

}  // namespace robotd::hightorque
