// Motor replies (§1.6.1 query table, errata "replies (CAN-FD)", the vendor's motor.c parser):
// state replies 0x0A / 0x0B / 0x0C / 0x0E with fields at the id's width, version / model /
// command-result replies; decoded for the driver, encoded for the simulator.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>

#include "hightorque_codec.hpp"
#include "motor_units.hpp"
#include "wire_scaling.hpp"

namespace robotd::hightorque {
namespace {

constexpr std::uint8_t kFirmwareVersionReply = 0x04;
constexpr std::uint8_t kHardwareVersionReply = 0x05;
constexpr std::uint8_t kModelReply = 0x07;
constexpr std::uint8_t kResultReply = 0x03;
constexpr std::size_t kVersionBytes = 4;      // code, patch, minor, major
constexpr std::size_t kModelHeaderBytes = 2;  // code, length
constexpr std::size_t kMaxModelChars = std::tuple_size_v<decltype(ModelName::text)> - 1;

/// Which fields a state reply carries after its query byte, in wire order.
struct StateLayout {
  bool mode = false;  // mode, fault (else fault alone)
  bool counter = false;
  bool temperature = false;
  bool motion = false;  // position, velocity, torque

  std::size_t length(Width width) const {
    const std::size_t fields = (counter ? 1U : 0U) + (temperature ? 1U : 0U) + (motion ? 3U : 0U);
    return (mode ? 3U : 2U) + fields * wire::width_bytes(width);
  }
};

std::optional<StateLayout> state_layout(Query query) {
  switch (query) {
    case Query::kCounter:
      return StateLayout{.mode = true, .counter = true, .temperature = false, .motion = false};
    case Query::kState:
      return StateLayout{.mode = true, .counter = false, .temperature = false, .motion = true};
    case Query::kStateTemperature:
      return StateLayout{.mode = true, .counter = false, .temperature = true, .motion = true};
    case Query::kCompact:
      return StateLayout{.mode = false, .counter = false, .temperature = false, .motion = true};
    case Query::kNone:
      break;
  }
  return std::nullopt;
}

void put_counter(wire::Bytes bytes, std::size_t at, Width width, std::uint16_t counter) {
  switch (width) {
    case Width::kInt16:
      wire::put_u16(bytes, at, counter);
      return;
    case Width::kInt32:
      wire::put_u32(bytes, at, counter);
      return;
    case Width::kFloat:
      wire::put_u32(bytes, at, std::bit_cast<std::uint32_t>(static_cast<float>(counter)));
      return;
  }
}

std::uint16_t get_counter(wire::ConstBytes bytes, std::size_t at, Width width) {
  switch (width) {
    case Width::kInt16:
      return wire::get_u16(bytes, at);
    case Width::kInt32:
      return static_cast<std::uint16_t>(wire::get_u32(bytes, at) & 0xFFFFU);
    case Width::kFloat: {
      const float value = std::bit_cast<float>(wire::get_u32(bytes, at));
      return std::isnan(value) ? std::uint16_t{0} : static_cast<std::uint16_t>(std::clamp(value, 0.0F, 65535.0F));
    }
  }
  return 0;
}

bool decode_state(wire::ConstBytes bytes, Width width, const MotorScaling& scaling, MotorState& state) {
  state.query = static_cast<Query>(bytes[0]);
  const std::optional<StateLayout> layout = state_layout(state.query);
  if (!layout || bytes.size() < layout->length(width)) return false;
  std::size_t at = 1;
  if (layout->mode) state.mode = bytes[at++];
  state.fault = bytes[at++];
  const std::size_t step = wire::width_bytes(width);
  const auto next = [&](units::Quantity quantity) {
    const double value = units::from_counts(quantity, wire::get_counts(bytes, at, width), width, scaling);
    at += step;
    return value;
  };
  if (layout->counter) {
    state.counter = get_counter(bytes, at, width);
    at += step;
  }
  if (layout->temperature) state.temperature_c = next(units::Quantity::kTemperature);
  if (layout->motion) {
    state.position_rad = next(units::Quantity::kPosition);
    state.velocity_rad_s = next(units::Quantity::kVelocity);
    state.torque_nm = next(units::Quantity::kTorque);
  }
  return true;
}

bool decode_model(wire::ConstBytes bytes, ModelName& model) {
  if (bytes.size() < kModelHeaderBytes) return false;
  const std::size_t length = bytes[1];
  if (length == 0 || bytes.size() < kModelHeaderBytes + length) return false;
  const auto text = bytes.subspan(kModelHeaderBytes, std::min(length, kMaxModelChars));
  // The name ends up in JSON and logs: bytes that are not printable ASCII read as '?'.
  std::transform(text.begin(), text.end(), model.text.begin(), [](std::uint8_t byte) {
    return byte == 0 || (byte >= 0x20 && byte < 0x7F) ? static_cast<char>(byte) : '?';
  });
  model.text[text.size()] = '\0';
  return true;
}

bool decode_body(wire::ConstBytes bytes, Width width, const MotorScaling& scaling, Reply& reply) {
  switch (bytes[0]) {
    case kFirmwareVersionReply:
    case kHardwareVersionReply:
      if (bytes.size() < kVersionBytes) return false;
      reply.kind = bytes[0] == kFirmwareVersionReply ? Reply::Kind::kFirmwareVersion : Reply::Kind::kHardwareVersion;
      reply.version.patch = bytes[1];
      reply.version.minor = bytes[2];
      reply.version.major = bytes[3];
      return true;
    case kModelReply:
      reply.kind = Reply::Kind::kModel;
      return decode_model(bytes, reply.model);
    case kResultReply:
      if (bytes.size() < 2) return false;
      reply.kind = Reply::Kind::kResult;
      reply.result.code = bytes[1];
      reply.result.success = bytes[1] == 0;
      return true;
    default:
      reply.kind = Reply::Kind::kState;
      return decode_state(bytes, width, scaling, reply.state);
  }
}

}  // namespace

std::optional<Reply> decode_reply(const transport::CanMessage& message, int max_motor_id,
                                  const MotorScaling& scaling) noexcept {
  const wire::ConstBytes bytes = wire::payload(message);
  const std::uint32_t id = message.id;
  const std::uint32_t type = (id >> 16) & 0x3U;
  const auto motor = static_cast<int>((id >> 8) & 0x7FU);
  // Bits 28…18 reserved, bit 15 clear (bit 15 set is a command), type 00 is the classic reply.
  if (bytes.empty() || !message.extended || (id >> 18) != 0 || (id & 0x8000U) != 0 || type == 0 ||
      motor < kMinMotorId || motor > std::min(max_motor_id, kMaxMotorId)) {
    return std::nullopt;
  }
  Reply reply;
  if (!decode_body(bytes, static_cast<Width>(type), scaling, reply)) return std::nullopt;
  reply.state.motor = motor;
  reply.version.motor = motor;
  reply.model.motor = motor;
  reply.result.motor = motor;
  return reply;
}

transport::CanMessage encode_reply(const MotorState& state, Width width, const MotorScaling& scaling) noexcept {
  const std::optional<StateLayout> layout = state_layout(state.query);
  if (!layout) return wire::fd_frame(reply_id(width, state.motor), 0);
  transport::CanMessage message = wire::fd_frame(reply_id(width, state.motor), layout->length(width));
  message.data[0] = static_cast<std::uint8_t>(state.query);
  std::size_t at = 1;
  if (layout->mode) message.data[at++] = state.mode;
  message.data[at++] = state.fault;
  const std::size_t step = wire::width_bytes(width);
  const auto put = [&](units::Quantity quantity, double value) {
    wire::put_counts(message.data, at, width, units::to_counts(quantity, value, width, scaling));
    at += step;
  };
  if (layout->counter) {
    put_counter(message.data, at, width, state.counter.value_or(0));
    at += step;
  }
  if (layout->temperature) {
    put(units::Quantity::kTemperature, state.temperature_c.value_or(std::numeric_limits<double>::quiet_NaN()));
  }
  if (layout->motion) {
    put(units::Quantity::kPosition, state.position_rad);
    put(units::Quantity::kVelocity, state.velocity_rad_s);
    put(units::Quantity::kTorque, state.torque_nm);
  }
  return message;
}

transport::CanMessage encode_firmware_version(const FirmwareVersion& version, InfoKind kind) noexcept {
  transport::CanMessage message = wire::fd_frame(reply_id(Width::kInt16, version.motor), kVersionBytes);
  message.data[0] = static_cast<std::uint8_t>(kind);
  message.data[1] = static_cast<std::uint8_t>(version.patch);
  message.data[2] = static_cast<std::uint8_t>(version.minor);
  message.data[3] = static_cast<std::uint8_t>(version.major);
  return message;
}

transport::CanMessage encode_model_name(int motor, std::string_view name) noexcept {
  const std::size_t length = std::min(name.size(), kMaxModelChars);
  transport::CanMessage message = wire::fd_frame(reply_id(Width::kInt16, motor), kModelHeaderBytes + length);
  message.data[0] = kModelReply;
  message.data[1] = static_cast<std::uint8_t>(length);
  std::copy_n(name.begin(), length, message.data.data() + kModelHeaderBytes);
  return message;
}

transport::CanMessage encode_command_result(int motor, std::uint8_t code) noexcept {
  transport::CanMessage message = wire::fd_frame(reply_id(Width::kInt16, motor), 2);
  message.data[0] = kResultReply;
  message.data[1] = code;
  return message;
}

}  // namespace robotd::hightorque
