// Words for the status codes and fault bits of piper_can.md §5.1, §5.4 and §5.6.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

#include "piper_frames.hpp"

namespace robotd::piper {
namespace {

constexpr const char* kUnknown = "unknown";

template <std::size_t N>
const char* lookup(const std::array<const char*, N>& texts, std::uint8_t code) {
  return code < N ? texts[code] : kUnknown;
}

/// The names of the set bits among those `names` has one for (nullptr: a bit without a fault).
std::string set_bits_text(std::uint8_t bits, const std::array<const char*, 8>& names) {
  std::string text;
  for (std::size_t bit = 0; bit < names.size(); ++bit) {
    if (names[bit] == nullptr || (bits & (1U << bit)) == 0) continue;
    if (!text.empty()) text += ", ";
    text += names[bit];
  }
  return text;
}

constexpr std::array<const char*, 8> kControlModes{"standby", "can command", "teach",         "ethernet",
                                                   "wifi",    "remote",      "linkage teach", "offline trajectory"};

constexpr std::array<const char*, 6> kMoveModes{"move p", "move j", "move l", "move c", "mit", "cpv"};

constexpr std::array<const char*, 16> kArmStatuses{
    "normal",
    "emergency stop",
    "no ik solution",
    "singularity",
    "target angle exceeds limit",
    "joint communication error",
    "joint brake not released",
    "collision",
    "over-speed during drag-teach",
    "joint status abnormal",
    "other",
    "teach recording",
    "teach executing",
    "teach paused",
    "main-controller ntc over-temperature",
    "brake-resistor ntc over-temperature",
};

constexpr std::array<const char*, 8> kTeachStatuses{"off",   "start recording", "end recording", "replay",
                                                    "pause", "continue",        "terminate",     "move to start"};

// Bit 6 of both status bytes is "enabled", and bit 7 of the gripper's is "homed": not faults.
constexpr std::array<const char*, 8> kDriverFaults{"under-voltage",
                                                   "motor over-temperature",
                                                   "over-current",
                                                   "driver over-temperature",
                                                   "collision protection triggered",
                                                   "driver error",
                                                   nullptr,
                                                   "stall protection triggered"};

constexpr std::array<const char*, 8> kGripperFaults{
    "under-voltage", "motor over-temperature", "over-current", "driver over-temperature",
    "sensor fault",  "driver error",           nullptr,        nullptr};

}  // namespace

const char* control_mode_text(ControlMode mode) { return lookup(kControlModes, static_cast<std::uint8_t>(mode)); }

const char* move_mode_text(MoveMode mode) { return lookup(kMoveModes, static_cast<std::uint8_t>(mode)); }

const char* arm_status_text(std::uint8_t arm_status) { return lookup(kArmStatuses, arm_status); }

const char* teach_status_text(std::uint8_t teach_status) { return lookup(kTeachStatuses, teach_status); }

std::string driver_status_text(std::uint8_t status_bits) { return set_bits_text(status_bits, kDriverFaults); }

std::string gripper_status_text(std::uint8_t status_bits) { return set_bits_text(status_bits, kGripperFaults); }

const char* driver_status_bit_text(int bit) {
  if (bit < 0 || bit >= 8) return kUnknown;
  const char* name = kDriverFaults[static_cast<std::size_t>(bit)];
  return name != nullptr ? name : "enabled";
}

const char* gripper_status_bit_text(int bit) {
  if (bit < 0 || bit >= 8) return kUnknown;
  const char* name = kGripperFaults[static_cast<std::size_t>(bit)];
  if (name != nullptr) return name;
  return bit == 6 ? "enabled" : "homed";
}

}  // namespace robotd::piper
