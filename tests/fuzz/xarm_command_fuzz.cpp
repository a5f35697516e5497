// The xArm codec (drivers/xarm/codec) on any byte stream the command port (502) can deliver:
// the frame splitter, then every frame read both ways, as the driver reads a reply (status byte,
// every reply-data parser, motion feedback) and as the simulator reads a request (every
// parameter parser). Frames and parsed values that have an encoder must survive a round trip:
// a frame re-splits to itself, and parse → encode → parse → encode reaches the same bytes.
//
// Input: u8 read size − 1, then the stream.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "codec/xarm_codec.hpp"
#include "fuzz_check.hpp"
#include "fuzz_input.hpp"

namespace {

using namespace robotd::xarm;
using robotd::fuzz::FuzzInput;
using robotd::fuzz::is_printable_ascii;

bool same_frame(const Frame& a, const Frame& b) {
  return a.transaction_id == b.transaction_id && a.protocol == b.protocol && a.reg == b.reg && a.body == b.body;
}

/// encode(parse(data)) is a fixed point of parse then encode.
template <class Parse, class Encode>
void check_round_trip(ByteView data, Parse parse, Encode encode) {
  const auto parsed = parse(data);
  if (!parsed) return;
  const Bytes encoded = encode(parsed.value());
  const auto again = parse(encoded);
  FUZZ_CHECK(again.ok());
  FUZZ_CHECK(encode(again.value()) == encoded);
}

void read_reply(const Frame& frame) {
  const auto reply = parse_reply(frame);
  if (!reply) return;
  const int state = execution_state(reply.value());
  static_cast<void>(execution_state_text(state));
  static_cast<void>(execution_succeeded(reply.value().reg, state));
  static_cast<void>(register_name(reply.value().reg));

  const ByteView data = reply.value().data;
  if (const auto version = parse_version(data)) {
    static_cast<void>(model_for_type(version.value().axes, version.value().type));
    FUZZ_CHECK(is_printable_ascii(version.value().robot_sn) && is_printable_ascii(version.value().control_box_sn));
    FUZZ_CHECK(is_printable_ascii(version.value().firmware));
  }
  if (const auto serials = parse_robot_sn(data)) {
    FUZZ_CHECK(is_printable_ascii(serials.value().robot_sn) && is_printable_ascii(serials.value().control_box_sn));
  }
  check_round_trip(data, parse_state, encode_state);
  check_round_trip(data, parse_cmdnum, encode_cmdnum);
  check_round_trip(data, parse_err_code, encode_err_code);
  check_round_trip(data, parse_pose, encode_pose);
  check_round_trip(data, parse_joints, encode_joints);
  check_round_trip(data, parse_limit_flag, encode_limit_flag);
  if (const auto servos = parse_servo_dbmsg(data)) {
    for (const ServoStatus& servo : servos.value()) static_cast<void>(servo_error_text(servo.error));
  }
  if (const auto codes = parse_err_code(data)) {
    static_cast<void>(controller_error_text(codes.value().error));
    static_cast<void>(controller_warning_text(codes.value().warning));
    static_cast<void>(is_estop_error(codes.value().error));
  }
}

void read_motion_feedback(const Frame& frame) {
  const auto feedback = parse_motion_feedback(frame);
  if (!feedback) return;
  const Frame encoded = motion_feedback_frame(feedback.value(), frame.protocol);
  const auto again = parse_motion_feedback(encoded);
  FUZZ_CHECK(again.ok());
  FUZZ_CHECK(same_frame(motion_feedback_frame(again.value(), frame.protocol), encoded));
}

/// What the simulator reads from a request frame's parameters.
void read_request(const Frame& frame) {
  const ByteView params = frame.body;
  static_cast<void>(parse_motion_enable(params));
  static_cast<void>(parse_set_brake(params));
  static_cast<void>(parse_u8_param(frame.reg, params));
  if (const auto move = parse_line_move(frame.reg, params)) {
    const Request request = move_lineb_request(move.value());
    const auto again = parse_line_move(request.reg, request.params);
    FUZZ_CHECK(again.ok());
    FUZZ_CHECK(move_lineb_request(again.value()).params == request.params);
  }
  if (const auto move = parse_joint_move(params)) {
    const Request request = move_joint_request(move.value());
    const auto again = parse_joint_move(request.params);
    FUZZ_CHECK(again.ok());
    FUZZ_CHECK(move_joint_request(again.value()).params == request.params);
  }
  static_cast<void>(parse_gohome(params));
  static_cast<void>(parse_joint_params(frame.reg, params));
  static_cast<void>(parse_pose_params(frame.reg, params));
  static_cast<void>(parse_scalar_param(frame.reg, params));
}

void check_reframes(const Frame& frame) {
  FrameSplitter splitter;
  splitter.append(encode_frame(frame));
  const auto again = splitter.next();
  FUZZ_CHECK(again.ok() && again.value().has_value());
  FUZZ_CHECK(same_frame(*again.value(), frame));
  FUZZ_CHECK(splitter.buffered() == 0);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzInput input(data, size);
  const std::uint8_t piece = input.u8();
  FrameSplitter splitter;
  bool broken = false;
  robotd::fuzz::feed_in_pieces(input.rest(), piece, [&](std::span<const std::uint8_t> bytes) {
    splitter.append(bytes);
    while (!broken) {
      const auto next = splitter.next();
      broken = !next.ok();  // the stream lost its framing: the driver reconnects
      if (broken || !next.value()) return;
      const Frame& frame = *next.value();
      FUZZ_CHECK(frame.body.size() < kMaxFrameBytes);
      check_reframes(frame);
      if (is_motion_feedback(frame)) {
        read_motion_feedback(frame);
      } else {
        read_reply(frame);
      }
      read_request(frame);
    }
  });
  return 0;
}
