// The PAROL6 serial codec (drivers/parol6/codec) on any byte stream a tty can deliver: the
// stream parser in both styles (the driver's resynchronising one and the firmware's, which the
// simulator uses), then every accepted body read as the board's reply and as the host's command.
// A decoded reply must re-encode into a frame that the parser accepts and that decodes and
// encodes to the same bytes again; its joint values must convert to finite SI values.
//
// Input: u8 options (bit 0: firmware style; bits 1–7: read size − 1), then the stream.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "codec/joint_units.hpp"
#include "codec/parol6_frames.hpp"
#include "fuzz_check.hpp"
#include "fuzz_input.hpp"

namespace {

using namespace robotd::parol6;
using robotd::fuzz::FuzzInput;

/// The body of the one frame in `frame`, parsed as the driver parses the board's stream.
std::optional<RobotFrame> reparse(const std::array<std::uint8_t, kRobotFrameSize>& frame) {
  FrameParser parser(FrameParser::Style::kResync);
  std::optional<RobotFrame> decoded;
  parser.feed(frame, [&](std::span<const std::uint8_t> body) { decoded = decode_robot_body(body); });
  return decoded;
}

void check_reply(const RobotFrame& reply) {
  const auto encoded = encode(reply);
  const auto again = reparse(encoded);
  FUZZ_CHECK(again.has_value());
  FUZZ_CHECK(encode(*again) == encoded);
  for (int joint = 0; joint < kJoints; ++joint) {
    const auto j = static_cast<std::size_t>(joint);
    FUZZ_CHECK(std::isfinite(steps_to_rad(joint, reply.position_steps[j])));
    FUZZ_CHECK(std::isfinite(steps_per_s_to_rad_per_s(joint, reply.speed_steps_s[j])));
    static_cast<void>(reply.joint_homed(joint));
  }
  static_cast<void>(object_detection(reply.gripper_status));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzInput input(data, size);
  const std::uint8_t options = input.u8();
  const auto style = (options & 1U) != 0 ? FrameParser::Style::kFirmware : FrameParser::Style::kResync;
  FrameParser parser(style);
  std::uint64_t bodies = 0;
  const auto on_body = [&](std::span<const std::uint8_t> body) {
    ++bodies;
    if (const auto reply = decode_robot_body(body)) check_reply(*reply);
    if (const auto command = decode_host_body(body)) static_cast<void>(encode(*command));
  };
  const auto read_size = static_cast<std::uint8_t>(options >> 1);
  robotd::fuzz::feed_in_pieces(input.rest(), read_size,
                               [&](std::span<const std::uint8_t> piece) { parser.feed(piece, on_body); });
  FUZZ_CHECK(parser.frames() == bodies);
  return 0;
}
