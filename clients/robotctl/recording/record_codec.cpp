#include "recording/record_codec.hpp"

#include <array>
#include <charconv>
#include <cstdio>

#include "recording/little_endian.hpp"

namespace robotctl::recording {
namespace {

constexpr std::size_t kSessionTagDigits = 8;

}  // namespace

std::optional<std::string> encode(const JointStateRecord& record) {
  std::string payload;
  LittleEndianWriter out(payload);
  out.u16(record.device);
  out.i64(record.stamp_ns);
  if (!out.f64_array(record.position) || !out.f64_array(record.velocity) || !out.f64_array(record.effort)) {
    return std::nullopt;
  }
  return payload;
}

std::optional<std::string> encode(const ControlCommandRecord& record) {
  std::string payload;
  LittleEndianWriter out(payload);
  out.u16(record.device);
  out.i64(record.stamp_ns);
  out.u32(record.session);
  const robotd::Command& values = record.values;
  if (!out.i32_array(values.motor_ids) || !out.f32_array(values.positions) || !out.f32_array(values.velocities) ||
      !out.f32_array(values.kp) || !out.f32_array(values.kd) || !out.f32_array(values.torques)) {
    return std::nullopt;
  }
  return payload;
}

std::optional<JointStateRecord> decode_joint_state(std::string_view payload) {
  LittleEndianReader in(payload);
  JointStateRecord record;
  record.device = in.u16();
  record.stamp_ns = in.i64();
  record.position = in.f64_array();
  record.velocity = in.f64_array();
  record.effort = in.f64_array();
  if (!in.consumed_exactly()) return std::nullopt;
  return record;
}

std::optional<ControlCommandRecord> decode_control_command(std::string_view payload) {
  LittleEndianReader in(payload);
  ControlCommandRecord record;
  record.device = in.u16();
  record.stamp_ns = in.i64();
  record.session = in.u32();
  record.values.motor_ids = in.i32_array();
  record.values.positions = in.f32_array();
  record.values.velocities = in.f32_array();
  record.values.kp = in.f32_array();
  record.values.kd = in.f32_array();
  record.values.torques = in.f32_array();
  if (!in.consumed_exactly()) return std::nullopt;
  return record;
}

std::uint32_t session_tag(std::string_view uuid) {
  std::uint32_t tag = 0;
  const std::string_view digits = uuid.substr(0, kSessionTagDigits);
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), tag, 16);
  const bool whole = error == std::errc() && end == digits.data() + digits.size() && digits.size() == kSessionTagDigits;
  return whole ? tag : 0;
}

std::string session_tag_text(std::uint32_t tag) {
  std::array<char, kSessionTagDigits + 1> text{};
  std::snprintf(text.data(), text.size(), "%08x", static_cast<unsigned>(tag));
  return text.data();
}

}  // namespace robotctl::recording
