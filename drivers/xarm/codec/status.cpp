// The reply's status byte (§2.3), replies as the driver reads them and the simulator writes
// them, the SDK's execution-state codes (seed Appendix I, §6.4), and the words for motion states
// and modes (§3).
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "xarm_codec.hpp"

namespace robotd::xarm {
namespace {

constexpr std::uint8_t kInvalidBit = 0x08;
constexpr std::uint8_t kNotReadyBit = 0x10;
constexpr std::uint8_t kWarningBit = 0x20;
constexpr std::uint8_t kErrorBit = 0x40;
constexpr std::uint8_t kMotionFeedbackRegister = static_cast<std::uint8_t>(Register::kMotionFeedback);

constexpr auto kExecutionStateTexts = std::to_array<std::string_view>({
    "normal",
    "xArm has an error code",
    "xArm has a warning code",
    "communication timed out",
    "instruction parsing error (length)",
    "instruction parsing error (transaction id)",
    "instruction parsing error (protocol id)",
    "instruction parsing error (register)",
    "network problem (send failed)",
    "not ready to move (not enabled, stopped or reset)",
    "invalid result (execution failed)",
    "unknown error",
    "parameter error",
});
static_assert(kExecutionStateTexts.size() == kExecParameterError + 1);

// Standard Modbus exceptions arrive as 0x80 + exception code (§6.4).
constexpr int kModbusExceptionBase = 0x80;
constexpr auto kModbusExceptionTexts =
    std::to_array<std::string_view>({"illegal function", "illegal data address", "illegal data value"});

constexpr auto kMotionStateTexts = std::to_array<std::string_view>({
    "start (ready for motion commands)",
    "moving",
    "sleeping",
    "paused",
    "stopped",
    "system reset (set state 0 to continue)",
    "slow stop (decelerating to a stop)",
});

constexpr auto kModeTexts = std::to_array<std::string_view>({
    "position",
    "servo",
    "joint teaching",
    "Cartesian teaching",
    "joint velocity",
    "Cartesian velocity",
    "joint online planning",
    "Cartesian online planning",
});

/// The entry for `index`, or "" when the table has none.
template <std::size_t N>
std::string_view text_at(const std::array<std::string_view, N>& table, int index) {
  if (index < 0 || static_cast<std::size_t>(index) >= N) return {};
  return table[static_cast<std::size_t>(index)];
}

}  // namespace

StatusBits decode_status(std::uint8_t byte) {
  return StatusBits{.invalid = (byte & kInvalidBit) != 0,
                    .not_ready = (byte & kNotReadyBit) != 0,
                    .warning = (byte & kWarningBit) != 0,
                    .error = (byte & kErrorBit) != 0};
}

std::uint8_t encode_status(const StatusBits& bits) {
  return static_cast<std::uint8_t>((bits.invalid ? kInvalidBit : 0) | (bits.not_ready ? kNotReadyBit : 0) |
                                   (bits.warning ? kWarningBit : 0) | (bits.error ? kErrorBit : 0));
}

Result<Reply> parse_reply(const Frame& frame) {
  if (frame.reg == kMotionFeedbackRegister) {
    return make_error(ErrorCode::kInvalidArgument,
                      "frame with register 0xFF is a motion feedback frame, not a reply (use parse_motion_feedback)");
  }
  if (frame.body.empty()) {
    return make_error(ErrorCode::kInvalidArgument,
                      register_name(frame.reg) + " reply has no status byte: length field 1, expected at least 2");
  }
  Reply reply;
  reply.transaction_id = frame.transaction_id;
  reply.protocol = frame.protocol;
  reply.reg = frame.reg;
  reply.status_byte = frame.body.front();
  reply.status = decode_status(reply.status_byte);
  reply.data.assign(frame.body.begin() + 1, frame.body.end());
  return reply;
}

Frame reply_frame(std::uint16_t transaction_id, std::uint16_t protocol, std::uint8_t reg, std::uint8_t status_byte,
                  ByteView data) {
  Frame frame{.transaction_id = transaction_id, .protocol = protocol, .reg = reg, .body = {}};
  frame.body.reserve(1 + data.size());
  frame.body.push_back(status_byte);
  frame.body.insert(frame.body.end(), data.begin(), data.end());
  return frame;
}

int execution_state(const Reply& reply) {
  if (reply.status.invalid) return kExecInvalidResult;
  if (reply.status.error) return kExecErrorActive;
  if (reply.status.warning) return kExecWarningActive;
  if (is_motion_register(reply.reg) && reply.status.not_ready) return kExecNotReady;
  return kExecOk;
}

std::string execution_state_text(int code) {
  if (const auto text = text_at(kExecutionStateTexts, code); !text.empty()) return std::string(text);
  if (const auto text = text_at(kModbusExceptionTexts, code - kModbusExceptionBase - 1); !text.empty()) {
    return "Modbus exception " + std::to_string(code - kModbusExceptionBase) + " (" + std::string(text) + ")";
  }
  return "unknown execution state " + std::to_string(code);
}

bool execution_succeeded(std::uint8_t reg, int code) {
  if (is_motion_register(reg)) return code == kExecOk || code == kExecWarningActive;
  return code == kExecOk || code == kExecErrorActive || code == kExecWarningActive || code == kExecNotReady;
}

std::string motion_state_text(int state) {
  if (const auto text = text_at(kMotionStateTexts, state); !text.empty()) return std::string(text);
  return "unknown state " + std::to_string(state);
}

std::string mode_text(int mode) {
  if (const auto text = text_at(kModeTexts, mode); !text.empty()) return std::string(text);
  return "unknown mode " + std::to_string(mode);
}

}  // namespace robotd::xarm
