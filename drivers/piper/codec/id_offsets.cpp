// The one home of MasterSlaveConfig's id offsets (0x470 bytes 1–3, piper_sdk
// piper_interface_v2.py MasterSlaveConfig): feedback offset 0x10 / 0x20 moves the arm's feedback
// base id 0x2Ax to 0x2Bx / 0x2Cx, control (and a leader's linkage) offset moves the control base
// id 0x15x to 0x16x / 0x17x. Only those two ranges move; queries, replies and 0x25x / 0x26x stay.
#include <array>
#include <optional>
#include <utility>

#include "piper_frames.hpp"

namespace robotd::piper {
namespace {

struct MovedRange {
  std::uint32_t first;
  std::uint32_t last;
};

constexpr MovedRange kControlIds{can_id::kMotionControl, can_id::kMitControl + kArmJoints - 1};  // 0x150–0x15F
constexpr MovedRange kFeedbackIds{can_id::kArmStatus, can_id::kGripperFeedback};                 // 0x2A1–0x2A8
constexpr std::array<std::uint8_t, 3> kOffsets{0x00, 0x10, 0x20};

bool within(std::uint32_t id, const MovedRange& range, std::uint8_t offset) {
  return id >= range.first + offset && id <= range.last + offset;
}

std::optional<std::uint8_t> offset_of(std::uint32_t wire_id, const MovedRange& range) {
  for (const std::uint8_t offset : kOffsets) {
    if (within(wire_id, range, offset)) return offset;
  }
  return std::nullopt;
}

}  // namespace

bool id_offset_valid(std::uint8_t offset) noexcept {
  return offset == kOffsets[0] || offset == kOffsets[1] || offset == kOffsets[2];
}

CanMessage to_wire(CanMessage message, const CodecOptions& options) noexcept {
  if (message.extended) return message;
  if (within(message.id, kControlIds, 0)) {
    message.id += options.control_id_offset;
  } else if (within(message.id, kFeedbackIds, 0)) {
    message.id += options.feedback_id_offset;
  }
  return message;
}

std::optional<std::uint32_t> from_wire_id(std::uint32_t wire_id, const CodecOptions& options) noexcept {
  for (const auto& [range, offset] :
       {std::pair{kControlIds, options.control_id_offset}, std::pair{kFeedbackIds, options.feedback_id_offset}}) {
    const std::optional<std::uint8_t> moved_by = offset_of(wire_id, range);
    if (!moved_by) continue;
    if (*moved_by != offset) return std::nullopt;
    return wire_id - offset;
  }
  return wire_id;
}

std::optional<std::uint8_t> feedback_offset_of(std::uint32_t wire_id) noexcept {
  return offset_of(wire_id, kFeedbackIds);
}

std::optional<std::uint8_t> control_offset_of(std::uint32_t wire_id) noexcept {
  return offset_of(wire_id, kControlIds);
}

}  // namespace robotd::piper
