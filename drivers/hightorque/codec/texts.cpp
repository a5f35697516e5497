// Fault and mode names (§1.6.1 fault byte, the vendor's FDCan_Protocol.md table 2) for logs and
// status topics. Every text has static storage, the unknown-fault ones included: the RT thread
// may call these.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "hightorque_codec.hpp"

namespace robotd::hightorque {
namespace {

constexpr std::size_t kUnknownFaultChars = sizeof("unknown fault 0x42");

/// "unknown fault 0xHH" for every byte, built at compile time.
constexpr auto kUnknownFaults = [] {
  constexpr std::array<char, 16> kHex{'0', '1', '2', '3', '4', '5', '6', '7', '8', '9', 'A', 'B', 'C', 'D', 'E', 'F'};
  constexpr std::string_view kPrefix = "unknown fault 0x";
  std::array<std::array<char, kUnknownFaultChars>, 256> texts{};
  for (std::size_t code = 0; code < texts.size(); ++code) {
    auto& text = texts[code];
    std::size_t at = 0;
    for (const char c : kPrefix) text[at++] = c;
    text[at++] = kHex[code >> 4];
    text[at++] = kHex[code & 0xFU];
    text[at] = '\0';
  }
  return texts;
}();

}  // namespace

const char* fault_text(std::uint8_t fault) noexcept {
  switch (fault) {
    case 0x00:
      return "ok";
    case 0x0A:
      return "not calibrated";
    case 0x0B:
      return "current calibration error";
    case 0x0C:
      return "driver calibration error";
    case 0x0D:
      return "driver error";
    case 0x0E:
      return "PWM cycle overrun";
    case 0x0F:
      return "main loop overran 4 ms";
    case 0x10:
      return "ADC timeout";
    case 0x11:
      return "over-voltage";
    case 0x12:
      return "under-voltage";
    case 0x13:
      return "MOSFET over-temperature";
    case 0x14:
      return "motor over-temperature";
    case 0x15:
      return "communication timeout";
    case 0x16:
      return "position over limit";
    default:
      return kUnknownFaults[fault].data();
  }
}

const char* mode_text(std::uint8_t mode) noexcept {
  switch (static_cast<Mode>(mode)) {
    case Mode::kStop:
      return "stop";
    case Mode::kBrake:
      return "brake";
    case Mode::kVoltage:
      return "voltage";
    case Mode::kCurrent:
      return "current";
    case Mode::kTorque:
      return "torque";
    case Mode::kVelocity:
      return "velocity";
    case Mode::kPosition:
      return "position";
    case Mode::kVelocityAcceleration:
      return "velocity-acceleration";
    case Mode::kPositionVelocityTorque:
      return "position-velocity-torque";
    case Mode::kPositionVelocityAcceleration:
      return "position-velocity-acceleration";
    case Mode::kMit:
      return "mit";
  }
  return "unknown";
}

}  // namespace robotd::hightorque
