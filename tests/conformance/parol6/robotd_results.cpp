#include "robotd_results.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <span>
#include <stdexcept>
#include <string>

#include "codec/joint_units.hpp"
#include "codec/parol6_frames.hpp"
#include "vector_file.hpp"

namespace robotd::parol6::conformance {
namespace {

using nlohmann::json;
using robotd::conformance::hex_text;

constexpr std::size_t kApiFrameBytes = 52;  // what the API's transport publishes of a body

std::uint8_t bit_list(const json& bits) {
  std::array<bool, 8> values{};
  for (std::size_t k = 0; k < values.size(); ++k) values[k] = bits.at(k).get<int>() != 0;
  return pack_bits(values);
}

json bit_values(std::uint8_t byte) {
  json bits = json::array();
  for (const bool bit : unpack_bits(byte)) bits.push_back(bit ? 1 : 0);
  return bits;
}

json common_fields(const RobotFrame& frame) {
  return {{"positions", frame.position_steps},
          {"speeds", frame.speed_steps_s},
          {"homed", bit_values(frame.homed)},
          {"io", bit_values(frame.io)},
          {"temperature_error", bit_values(frame.temperature_error)},
          {"position_error", bit_values(frame.position_error)},
          {"timing", frame.timing_ticks}};
}

json gripper_fields(const RobotFrame& frame, int object_detection) {
  return {{"id", frame.gripper_id},         {"position", frame.gripper_position},
          {"speed", frame.gripper_speed},   {"current", frame.gripper_current},
          {"status", frame.gripper_status}, {"object_detection", object_detection}};
}

RobotFrame decoded(const Bytes& body) {
  const auto frame = decode_robot_body(body);
  if (!frame) throw std::invalid_argument("a recorded reply body robotd cannot decode: " + hex_text(body));
  return *frame;
}

/// What the driver's parser (FrameParser::Style::kResync, then decode_robot_body) accepts from
/// `stream` fed in reads of `chunk` bytes, in the API transport's terms: after each read that
/// brought frames, how many and the last one's first 52 bytes.
json published_frames(const Bytes& stream, std::size_t chunk) {
  FrameParser parser(FrameParser::Style::kResync);
  json published = json::array();
  for (std::size_t at = 0; at < stream.size(); at += chunk) {
    int count = 0;
    std::string last;
    parser.feed(std::span(stream).subspan(at, std::min(chunk, stream.size() - at)),
                [&](std::span<const std::uint8_t> body) {
                  if (!decode_robot_body(body)) return;
                  ++count;
                  last = hex_text(body.data(), std::min(body.size(), kApiFrameBytes));
                });
    if (count > 0) published.push_back({{"count", count}, {"frame", last}});
  }
  return published;
}

}  // namespace

json tx_frame(const json& input) {
  HostFrame frame;
  for (std::size_t j = 0; j < kJoints; ++j) {
    frame.position_steps[j] = input.at("positions").at(j).get<std::int32_t>();
    frame.speed_steps_s[j] = input.at("speeds").at(j).get<std::int32_t>();
  }
  frame.command = input.at("command").get<std::uint8_t>();
  frame.affected_joints = bit_list(input.at("affected"));
  frame.io = bit_list(input.at("io"));
  frame.timeout_ms = input.at("timeout").get<std::uint8_t>();
  const json& gripper = input.at("gripper");
  frame.gripper_position = gripper.at(0).get<std::int16_t>();
  frame.gripper_speed = gripper.at(1).get<std::int16_t>();
  frame.gripper_current_ma = gripper.at(2).get<std::int16_t>();
  frame.gripper_command = gripper.at(3).get<std::uint8_t>();
  frame.gripper_mode = gripper.at(4).get<std::uint8_t>();
  frame.gripper_id = gripper.at(5).get<std::uint8_t>();
  const auto bytes = encode(frame);
  return hex_text(bytes.data(), bytes.size());
}

json rx_as_api(const Bytes& body) {
  const RobotFrame frame = decoded(body);
  json result = common_fields(frame);
  result["ok"] = true;
  result["gripper"] = gripper_fields(frame, static_cast<int>(object_detection(frame.gripper_status)));
  return result;
}

json rx_as_commander(const Bytes& body) {
  const RobotFrame frame = decoded(body);
  json result = common_fields(frame);
  result["timeout_error"] = frame.timeout_error;
  result["xtr2"] = frame.echoed_command;
  result["gripper"] = gripper_fields(frame, frame.object_detection);
  return result;
}

json to_steps(int joint, double rad) {
  const std::int32_t position = rad_to_steps(joint, rad);
  const std::int32_t speed = rad_per_s_to_steps_per_s(joint, rad);
  // robotd has one conversion each; the API's array and scalar variants are both recorded.
  return {{"position_steps", position},
          {"position_steps_scalar", position},
          {"speed_steps_s", speed},
          {"speed_steps_s_scalar", speed}};
}

json to_rad(int joint, std::int32_t steps) {
  return {{"position_rad", steps_to_rad(joint, steps)}, {"speed_rad_s", steps_per_s_to_rad_per_s(joint, steps)}};
}

json framing_as_api(const Bytes& stream) {
  return {{"byte_by_byte", published_frames(stream, 1)}, {"at_once", published_frames(stream, stream.size())}};
}

json framing_as_commander(const Bytes& stream) {
  FrameParser parser(FrameParser::Style::kResync);
  json frames = json::array();
  parser.feed(stream, [&](std::span<const std::uint8_t> body) {
    if (decode_robot_body(body)) frames.push_back({{"body", hex_text(body.data(), body.size())}});
  });
  return {{"frames", frames}};
}

}  // namespace robotd::parol6::conformance
