// The HighTorque CAN-FD codec (drivers/hightorque/codec) on any frame a CAN-FD link can
// deliver: read as a motor's reply (what the driver decodes) and as a command frame (what the
// simulator decodes, single-motor and one-to-many block frames). A decoded state reply must
// re-encode at its width into a reply that decodes to the same values, up to the one wire count
// that truncation toward zero may cost (the vendor's conversion), with "no value" kept as NaN.
//
// Input: u8 options (bit 0: the USB board's torque scaling instead of CAN-FD's 1.0), u8 highest
// motor id, then a CAN message (can_message_input.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "can_message_input.hpp"
#include "codec/hightorque_codec.hpp"
#include "fuzz_check.hpp"
#include "fuzz_input.hpp"

namespace {

using namespace robotd::hightorque;
using robotd::fuzz::FuzzInput;
using robotd::transport::CanMessage;

constexpr MotorScaling kCanFdScaling{};
constexpr MotorScaling kBoardScaling{.torque_per_unit = 0.004938, .torque_offset_nm = 0.0, .gain_factor = 1.0};

/// Equal, both NaN, or apart by at most one wire count of any quantity at these scalings.
bool same_value(double a, double b) {
  if (a == b || (std::isnan(a) && std::isnan(b))) return true;
  return std::abs(a - b) <= 0.1 + 1e-6 * std::abs(a);
}

void check_state_round_trip(const MotorState& state, Width width, int max_motor_id, const MotorScaling& scaling) {
  const CanMessage encoded = encode_reply(state, width, scaling);
  const auto again = decode_reply(encoded, max_motor_id, scaling);
  FUZZ_CHECK(again.has_value() && again->kind == Reply::Kind::kState);
  const MotorState& decoded = again->state;
  FUZZ_CHECK(decoded.motor == state.motor && decoded.query == state.query);
  FUZZ_CHECK(decoded.mode == state.mode && decoded.fault == state.fault);
  FUZZ_CHECK(same_value(decoded.position_rad, state.position_rad));
  FUZZ_CHECK(same_value(decoded.velocity_rad_s, state.velocity_rad_s));
  FUZZ_CHECK(same_value(decoded.torque_nm, state.torque_nm));
  FUZZ_CHECK(decoded.temperature_c.has_value() == state.temperature_c.has_value());
  if (state.temperature_c) FUZZ_CHECK(same_value(*decoded.temperature_c, *state.temperature_c));
  FUZZ_CHECK(decoded.counter.has_value() == state.counter.has_value());
}

void read_reply(const CanMessage& message, int max_motor_id, const MotorScaling& scaling) {
  const auto reply = decode_reply(message, max_motor_id, scaling);
  if (!reply) return;
  switch (reply->kind) {
    case Reply::Kind::kState: {
      FUZZ_CHECK(reply->state.motor >= kMinMotorId && reply->state.motor <= max_motor_id);
      FUZZ_CHECK(fault_text(reply->state.fault) != nullptr && mode_text(reply->state.mode) != nullptr);
      const auto width = static_cast<Width>((message.id >> 16) & 0x3U);
      check_state_round_trip(reply->state, width, max_motor_id, scaling);
      break;
    }
    case Reply::Kind::kModel: {
      const auto& text = reply->model.text;
      FUZZ_CHECK(std::find(text.begin(), text.end(), '\0') != text.end());
      FUZZ_CHECK(robotd::fuzz::is_printable_ascii(text.data()));
      break;
    }
    case Reply::Kind::kFirmwareVersion:
    case Reply::Kind::kHardwareVersion:
    case Reply::Kind::kResult:
      break;
  }
}

void read_request(const CanMessage& message, const MotorScaling& scaling) {
  std::array<MotorRequest, 64> requests{};
  const std::size_t count = decode_request(message, scaling, requests);
  FUZZ_CHECK(count <= requests.size());
  for (std::size_t i = 0; i < count; ++i) {
    FUZZ_CHECK(mode_text(static_cast<std::uint8_t>(requests[i].command.mode)) != nullptr);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzInput input(data, size);
  const MotorScaling& scaling = (input.u8() & 1U) != 0 ? kBoardScaling : kCanFdScaling;
  const int max_motor_id = input.u8();
  const CanMessage message = robotd::fuzz::read_can_message(input);
  read_reply(message, max_motor_id, scaling);
  read_request(message, scaling);
  return 0;
}
