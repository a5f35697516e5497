// Words for the controller's error codes (§7.1), the joint error bits (§7.2) and the gripper's
// error bits and modes (§5.1).
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "realman_codec.hpp"

namespace robotd::realman {
namespace {

struct CodeText {
  std::uint16_t code;
  std::string_view text;
};

constexpr auto kSystemErrors = std::to_array<CodeText>({
    {0x0000, "OK"},
    {0x1001, "joint communication error"},
    {0x1002, "target angle beyond joint limit"},
    {0x1003, "unreachable / singularity (IK failure)"},
    {0x1004, "real-time kernel communication error"},
    {0x1005, "joint bus communication error"},
    {0x1006, "planning-layer kernel error"},
    {0x1007, "joint over-speed"},
    {0x1008, "end interface board unreachable"},
    {0x1009, "over speed limit"},
    {0x100A, "over acceleration limit"},
    {0x100B, "joint brake not released"},
    {0x100C, "over-speed during drag teaching"},
    {0x100D, "collision detected"},
    {0x100E, "work frame does not exist"},
    {0x100F, "tool frame does not exist"},
    {0x1010, "joint lost enable"},
    {0x1011, "arc planning error"},
    {0x1012, "self-collision"},
    {0x1013, "electronic fence violation"},
    {0x1014, "beyond joint soft limit"},
    {0x2001, "gripper fault"},
    {0x2002, "dexterous hand fault"},
    {0x2003, "six-axis F/T module fault"},
    {0x2004, "one-axis force module fault"},
    {0x2005, "output current abnormal"},
    {0x5001, "reserved (older ROS header: base tipped)"},
    {0x5002, "reserved (older ROS header: IMU data error)"},
    {0x5003, "controller over-temperature"},
    {0x5004, "reserved (older ROS header: temperature sensor data error)"},
    {0x5005, "controller over-current"},
    {0x5006, "controller under-current"},
    {0x5007, "controller over-voltage"},
    {0x5008, "controller under-voltage"},
    {0x5009, "real-time kernel communication error"},
});

// Severe per the web version of §7.1: the joint, bus, kernel and end-board communication faults.
// The 0x5xxx controller hardware faults are judged severe here (the spec gives no severity for
// them); every other code, known or not, counts as general.
constexpr auto kSevereBySpec = std::to_array<std::uint16_t>({0x1001, 0x1004, 0x1005, 0x1006, 0x1008});
constexpr std::uint16_t kControllerHardwareFamily = 0x5000;
constexpr std::uint16_t kFamilyMask = 0xF000;

// Bit i of a joint's error word (§7.2).
constexpr auto kJointErrorBits = std::to_array<std::string_view>(
    {"FOC error", "over-voltage", "under-voltage", "over-temperature", "start-up failure", "encoder error",
     "over-current", "software error", "temperature sensor error", "position over limit", "illegal joint ID",
     "position tracking error", "current detection error", "brake release failed", "position command step warning",
     "multi-turn count lost"});
static_assert(kJointErrorBits.size() == 16);
constexpr std::uint16_t kJointFrameLoss = 0xF000;  // a value of its own, not four bits

// Bit i of the gripper's "error" (§5.1); bits 5..7 are reserved.
constexpr auto kGripperErrorBits = std::to_array<std::string_view>(
    {"stall", "over-temperature", "over-current", "driver error", "internal communication error"});

// "mode" 1..6 (§5.1).
constexpr auto kGripperModes =
    std::to_array<std::string_view>({"fully open, idle", "fully closed, idle", "stopped, idle", "closing", "opening",
                                     "stopped by force while closing"});

/// "0x1002".
std::string hex_code(std::uint16_t code) {
  constexpr std::string_view kHexDigits = "0123456789ABCDEF";
  std::string text = "0x";
  for (int shift = 12; shift >= 0; shift -= 4) text += kHexDigits[(code >> shift) & 0xF];
  return text;
}

/// The texts of the set bits, joined by ", "; `unnamed` words a bit without a text.
template <std::size_t N>
std::string set_bits_text(std::uint16_t bits, const std::array<std::string_view, N>& names, std::string_view unnamed) {
  std::string text;
  for (std::size_t bit = 0; bit < 16; ++bit) {
    if ((bits & (1U << bit)) == 0) continue;
    if (!text.empty()) text += ", ";
    text += bit < N ? std::string(names[bit]) : std::string(unnamed) + " " + std::to_string(bit);
  }
  return text;
}

}  // namespace

std::string system_error_text(std::uint16_t code) {
  const auto found = std::find_if(kSystemErrors.begin(), kSystemErrors.end(),
                                  [code](const CodeText& entry) { return entry.code == code; });
  return hex_code(code) + " " + (found != kSystemErrors.end() ? std::string(found->text) : "unknown controller error");
}

bool system_error_is_severe(std::uint16_t code) {
  return std::find(kSevereBySpec.begin(), kSevereBySpec.end(), code) != kSevereBySpec.end() ||
         (code & kFamilyMask) == kControllerHardwareFamily;
}

std::string joint_error_text(std::uint16_t bits) {
  if (bits == kJointFrameLoss) return "communication frame loss";
  return set_bits_text(bits, kJointErrorBits, "bit");
}

std::string gripper_error_text(std::uint16_t bits) { return set_bits_text(bits, kGripperErrorBits, "reserved bit"); }

std::string gripper_mode_text(int mode) {
  if (mode >= 1 && mode <= static_cast<int>(kGripperModes.size())) {
    return std::string(kGripperModes[static_cast<std::size_t>(mode - 1)]);
  }
  return "unknown mode " + std::to_string(mode);
}

}  // namespace robotd::realman
