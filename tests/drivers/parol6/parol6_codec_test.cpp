// The PAROL6 serial codec against the byte-level spec (../shared/protocols/parol6_serial.md): the
// §3 primitive examples and the §13 worked frames byte for byte, round trips, short bodies, the
// stream parser in both styles (clean streams, lost and garbled bytes, the FF FF FF FF quirk,
// chunking, fuzz), and the §10 joint unit table.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <iomanip>
#include <iterator>
#include <limits>
#include <new>
#include <numbers>
#include <optional>
#include <ostream>
#include <random>
#include <span>
#include <vector>

#include <gtest/gtest.h>

#include "codec/joint_units.hpp"
#include "codec/parol6_frames.hpp"
#include "thread_allocations.hpp"

namespace robotd::parol6 {
namespace {

using Bytes = std::vector<std::uint8_t>;

/// Printable byte strings, so a mismatch shows as hex.
struct Hex {
  Bytes bytes;
  bool operator==(const Hex&) const = default;
};

std::ostream& operator<<(std::ostream& out, const Hex& hex) {
  out << std::hex << std::uppercase;
  for (std::size_t i = 0; i < hex.bytes.size(); ++i) {
    out << (i == 0 ? "" : " ") << std::setw(2) << std::setfill('0') << static_cast<int>(hex.bytes[i]);
  }
  return out << std::dec;
}

template <std::size_t kSize>
Hex hex(const std::array<std::uint8_t, kSize>& bytes) {
  return Hex{Bytes(bytes.begin(), bytes.end())};
}

/// Concatenates byte groups: {{0xFF, 0xFF}, zeros(18), ...}.
Hex hex(std::initializer_list<Bytes> groups) {
  Hex out;
  for (const Bytes& group : groups) out.bytes.insert(out.bytes.end(), group.begin(), group.end());
  return out;
}

Bytes zeros(std::size_t count) { return Bytes(count, 0x00); }
void append(Bytes& bytes, const Bytes& more) { bytes.insert(bytes.end(), more.begin(), more.end()); }

Bytes int24(std::int32_t value) {
  std::array<std::uint8_t, 3> out{};
  put_int24(out, value);
  return Bytes(out.begin(), out.end());
}

std::int32_t int24_of(std::uint8_t b0, std::uint8_t b1, std::uint8_t b2) {
  const std::array<std::uint8_t, 3> in{b0, b1, b2};
  return get_int24(in);
}

template <std::size_t kSize>
std::span<const std::uint8_t> body_of(const std::array<std::uint8_t, kSize>& frame) {
  return std::span<const std::uint8_t>(frame).subspan(4);
}

constexpr std::array<std::int32_t, kJoints> kStandbySteps{10240, -32000, 57905, 0, 0, 32000};

// --- §3 primitives -------------------------------------------------------------------------------

TEST(Parol6Primitives, Int24EncodesTheSpecExamples) {
  EXPECT_EQ(Hex{int24(-32000)}, (Hex{{0xFF, 0x83, 0x00}}));
  EXPECT_EQ(Hex{int24(57905)}, (Hex{{0x00, 0xE2, 0x31}}));
  EXPECT_EQ(Hex{int24(10240)}, (Hex{{0x00, 0x28, 0x00}}));
  EXPECT_EQ(Hex{int24(-1)}, (Hex{{0xFF, 0xFF, 0xFF}}));
  EXPECT_EQ(Hex{int24(-1500)}, (Hex{{0xFF, 0xFA, 0x24}}));
  EXPECT_EQ(Hex{int24(32000)}, (Hex{{0x00, 0x7D, 0x00}}));
}

TEST(Parol6Primitives, Int24DecodesTheSpecExamplesSignExtended) {
  EXPECT_EQ(int24_of(0xFF, 0x83, 0x00), -32000);
  EXPECT_EQ(int24_of(0x00, 0xE2, 0x31), 57905);
  EXPECT_EQ(int24_of(0x00, 0x28, 0x00), 10240);
  EXPECT_EQ(int24_of(0xFF, 0xFF, 0xFF), -1);
  EXPECT_EQ(int24_of(0xFF, 0xFA, 0x24), -1500);
  EXPECT_EQ(int24_of(0x80, 0x00, 0x00), -8388608);
  EXPECT_EQ(int24_of(0x7F, 0xFF, 0xFF), 8388607);
}

TEST(Parol6Primitives, Int24RoundTripsItsWholeRange) {
  for (const std::int32_t value : {-8388608, -8388607, -65536, -257, -256, -255, -1, 0, 1, 255, 256, 65535, 8388607}) {
    const Bytes bytes = int24(value);
    EXPECT_EQ(int24_of(bytes[0], bytes[1], bytes[2]), value);
  }
  std::mt19937 random(7);
  std::uniform_int_distribution<std::int32_t> any(-8388608, 8388607);
  for (int i = 0; i < 10000; ++i) {
    const std::int32_t value = any(random);
    const Bytes bytes = int24(value);
    ASSERT_EQ(int24_of(bytes[0], bytes[1], bytes[2]), value);
  }
}

TEST(Parol6Primitives, Int24WrapsModulo2To24LikeTheFirmware) {
  EXPECT_EQ(Hex{int24(8388608)}, (Hex{{0x80, 0x00, 0x00}}));  // 2^23 comes back as −2^23
  EXPECT_EQ(int24_of(0x80, 0x00, 0x00), -8388608);
  EXPECT_EQ(Hex{int24(-8388609)}, (Hex{{0x7F, 0xFF, 0xFF}}));  // −2^23 − 1 comes back as 2^23 − 1
  EXPECT_EQ(Hex{int24(16777216 + 5)}, (Hex{{0x00, 0x00, 0x05}}));
  EXPECT_EQ(Hex{int24(std::numeric_limits<std::int32_t>::max())}, (Hex{{0xFF, 0xFF, 0xFF}}));
  EXPECT_EQ(Hex{int24(std::numeric_limits<std::int32_t>::lowest())}, (Hex{{0x00, 0x00, 0x00}}));
}

TEST(Parol6Primitives, BitfieldElementZeroIsTheMsb) {
  for (std::size_t k = 0; k < 8; ++k) {
    std::array<bool, 8> bits{};
    bits[k] = true;
    EXPECT_EQ(pack_bits(bits), 0x80 >> k) << "element " << k;
  }
  EXPECT_EQ(pack_bits({true, true, true, true, true, true, false, false}), 0xFC);
  EXPECT_EQ(pack_bits({false, false, true, false, false, false, false, false}), 0x20);  // OUT1
  EXPECT_EQ(unpack_bits(0x0F), (std::array<bool, 8>{false, false, false, false, true, true, true, true}));
  EXPECT_EQ(unpack_bits(0x80), (std::array<bool, 8>{true, false, false, false, false, false, false, false}));
}

TEST(Parol6Primitives, BitfieldRoundTripsEveryByte) {
  for (int byte = 0; byte < 256; ++byte) {
    EXPECT_EQ(pack_bits(unpack_bits(static_cast<std::uint8_t>(byte))), byte);
  }
}

// --- §13 worked frames ---------------------------------------------------------------------------

TEST(Parol6HostFrame, WorkedExampleAIdleAtStandby) {
  HostFrame frame;
  frame.position_steps = kStandbySteps;
  EXPECT_EQ(frame.command, command::kIdle);  // the defaults are the commander's
  EXPECT_EQ(hex(encode(frame)), hex({{0xFF, 0xFF, 0xFF, 0x34},
                                     {0x00, 0x28, 0x00, 0xFF, 0x83, 0x00, 0x00, 0xE2, 0x31},
                                     {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x7D, 0x00},
                                     zeros(18),
                                     {0xFF, 0xFF, 0x00, 0x00},
                                     zeros(9),
                                     {0xE4, 0x01, 0x02}}));
  EXPECT_EQ(encode(frame).size(), 56U);
}

TEST(Parol6HostFrame, WorkedExampleBJogJ6WithOut1AndGripper) {
  HostFrame frame;
  frame.speed_steps_s[5] = -1500;
  frame.command = command::kJog;
  frame.io = io::kOut1;
  frame.gripper_position = 128;
  frame.gripper_speed = 50;
  frame.gripper_current_ma = 180;
  frame.gripper_command = gripper_command::kActivate | gripper_command::kMove | gripper_command::kReleaseDirection;
  EXPECT_EQ(hex(encode(frame)), hex({{0xFF, 0xFF, 0xFF, 0x34},
                                     zeros(18),
                                     zeros(15),
                                     {0xFF, 0xFA, 0x24},
                                     {0x7B, 0xFF, 0x20, 0x00},
                                     {0x00, 0x80, 0x00, 0x32, 0x00, 0xB4, 0xD0, 0x00, 0x00},
                                     {0xE4, 0x01, 0x02}}));
}

TEST(Parol6HostFrame, EveryFieldLandsAtItsSpecOffset) {
  const HostFrame frame{.position_steps = {1, 2, 3, 4, 5, 6},
                        .speed_steps_s = {-1, -2, -3, -4, -5, -6},
                        .command = command::kGoToPosition,
                        .affected_joints = 0x00,
                        .io = io::kOut2,
                        .timeout_ms = 7,
                        .gripper_position = 0x0102,
                        .gripper_speed = 0x0304,
                        .gripper_current_ma = -2,
                        .gripper_command = 0x90,
                        .gripper_mode = static_cast<std::uint8_t>(GripperMode::kCalibrate),
                        .gripper_id = 15,
                        .crc = 212};
  const auto bytes = encode(frame);
  EXPECT_EQ(bytes[4 + 2], 1);
  EXPECT_EQ(bytes[19 + 2], 6);
  EXPECT_EQ(Hex{Bytes(bytes.begin() + 22, bytes.begin() + 25)}, (Hex{{0xFF, 0xFF, 0xFF}}));
  EXPECT_EQ(Hex{Bytes(bytes.begin() + 37, bytes.begin() + 40)}, (Hex{{0xFF, 0xFF, 0xFA}}));
  EXPECT_EQ(bytes[40], 156);
  EXPECT_EQ(bytes[41], 0x00);
  EXPECT_EQ(bytes[42], 0x10);
  EXPECT_EQ(bytes[43], 7);
  EXPECT_EQ(Hex{Bytes(bytes.begin() + 44, bytes.begin() + 50)}, (Hex{{0x01, 0x02, 0x03, 0x04, 0xFF, 0xFE}}));
  EXPECT_EQ(bytes[50], 0x90);
  EXPECT_EQ(bytes[51], 1);
  EXPECT_EQ(bytes[52], 15);
  EXPECT_EQ(bytes[53], 212);  // the CRC placeholder comes from the struct
  EXPECT_EQ(bytes[54], 0x01);
  EXPECT_EQ(bytes[55], 0x02);
}

RobotFrame worked_example_c() {
  RobotFrame frame;
  frame.position_steps = kStandbySteps;
  frame.homed = 0xFF;
  frame.io = 0x0F;
  frame.timing_ticks = 7031;
  frame.echoed_command = command::kIdle;
  return frame;
}

Hex worked_example_c_bytes() {
  return hex({{0xFF, 0xFF, 0xFF, 0x38},
              {0x00, 0x28, 0x00, 0xFF, 0x83, 0x00, 0x00, 0xE2, 0x31},
              {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x7D, 0x00},
              zeros(18),
              {0xFF, 0x0F, 0x03, 0x03},
              {0x1B, 0x77},
              {0x64, 0xFF},
              {0x00},
              {0x00, 0x00},
              {0x00, 0x01},
              {0x00, 0x02},
              {0x01},
              {0x01},
              {0xD4, 0x01, 0x02}});
}

TEST(Parol6RobotFrame, WorkedExampleCHomedAtStandby) {
  EXPECT_EQ(hex(encode(worked_example_c())), worked_example_c_bytes());
  EXPECT_EQ(encode(worked_example_c()).size(), 60U);
}

TEST(Parol6RobotFrame, DecodesWorkedExampleC) {
  const Hex bytes = worked_example_c_bytes();
  const std::span<const std::uint8_t> body = std::span<const std::uint8_t>(bytes.bytes).subspan(4);
  const std::optional<RobotFrame> frame = decode_robot_body(body);
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->position_steps, kStandbySteps);
  EXPECT_EQ(frame->speed_steps_s, (std::array<std::int32_t, kJoints>{}));
  EXPECT_EQ(frame->homed, 0xFF);
  EXPECT_TRUE(frame->all_homed());
  EXPECT_EQ(frame->io, 0x0F);
  EXPECT_FALSE(frame->estop_pressed());
  EXPECT_EQ(frame->temperature_error, 0x03);
  EXPECT_EQ(frame->position_error, 0x03);
  EXPECT_EQ(frame->timing_ticks, 7031);
  EXPECT_NEAR(frame->timing_ticks * kTimingTickSeconds, 0.01, 1e-5);
  EXPECT_EQ(frame->timeout_error, 100);
  EXPECT_EQ(frame->echoed_command, command::kIdle);
  EXPECT_EQ(frame->gripper_id, 0);
  EXPECT_EQ(frame->gripper_position, 0);
  EXPECT_EQ(frame->gripper_speed, 1);
  EXPECT_EQ(frame->gripper_current, 2);
  EXPECT_EQ(frame->gripper_status, 1);
  EXPECT_EQ(frame->object_detection, 1);
  EXPECT_EQ(frame->crc, kRobotCrcPlaceholder);
}

TEST(Parol6RobotFrame, WorkedExampleDAfterPowerUp) {
  RobotFrame frame;  // the defaults are the board's power-up reply
  frame.timing_ticks = 0x1234;
  frame.echoed_command = command::kEnable;
  EXPECT_EQ(hex(encode(frame)), hex({{0xFF, 0xFF, 0xFF, 0x38},
                                     zeros(36),
                                     {0x03, 0x0F, 0x03, 0x03, 0x12, 0x34},
                                     {0x64, 101, 0x00, 0x00, 0x00, 0x00, 0x01, 0x00, 0x02, 0x01, 0x01},
                                     {0xD4, 0x01, 0x02}}));
  EXPECT_FALSE(frame.all_homed());
}

TEST(Parol6HostFrame, DecodesWorkedExampleB) {
  const Hex b = hex({{0xFF, 0xFF, 0xFF, 0x34},
                     zeros(33),
                     {0xFF, 0xFA, 0x24},
                     {0x7B, 0xFF, 0x20, 0x00},
                     {0x00, 0x80, 0x00, 0x32, 0x00, 0xB4, 0xD0, 0x00, 0x00},
                     {0xE4, 0x01, 0x02}});
  const std::optional<HostFrame> frame = decode_host_body(std::span<const std::uint8_t>(b.bytes).subspan(4));
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->position_steps, (std::array<std::int32_t, kJoints>{}));
  EXPECT_EQ(frame->speed_steps_s, (std::array<std::int32_t, kJoints>{0, 0, 0, 0, 0, -1500}));
  EXPECT_EQ(frame->command, command::kJog);
  EXPECT_EQ(frame->affected_joints, 0xFF);
  EXPECT_EQ(frame->io, io::kOut1);
  EXPECT_EQ(frame->timeout_ms, 0);
  EXPECT_EQ(frame->gripper_position, 128);
  EXPECT_EQ(frame->gripper_speed, 50);
  EXPECT_EQ(frame->gripper_current_ma, 180);
  EXPECT_EQ(frame->gripper_command, 0xD0);
  EXPECT_EQ(frame->gripper_mode, 0);
  EXPECT_EQ(frame->gripper_id, 0);
  EXPECT_EQ(frame->crc, kHostCrcPlaceholder);
}

// --- round trips and bodies ----------------------------------------------------------------------

class RandomFrames {
 public:
  explicit RandomFrames(std::uint32_t seed) : random_(seed) {}

  HostFrame host() {
    HostFrame frame;
    for (auto& position : frame.position_steps) position = int24_value();
    for (auto& speed : frame.speed_steps_s) speed = int24_value();
    frame.command = byte();
    frame.affected_joints = byte();
    frame.io = byte();
    frame.timeout_ms = byte();
    frame.gripper_position = int16_value();
    frame.gripper_speed = int16_value();
    frame.gripper_current_ma = int16_value();
    frame.gripper_command = byte();
    frame.gripper_mode = byte();
    frame.gripper_id = byte();
    frame.crc = byte();
    return frame;
  }

  RobotFrame robot() {
    RobotFrame frame;
    for (auto& position : frame.position_steps) position = int24_value();
    for (auto& speed : frame.speed_steps_s) speed = int24_value();
    frame.homed = byte();
    frame.io = byte();
    frame.temperature_error = byte();
    frame.position_error = byte();
    frame.timing_ticks = static_cast<std::uint16_t>(int16_value());
    frame.timeout_error = byte();
    frame.echoed_command = byte();
    frame.gripper_id = byte();
    frame.gripper_position = int16_value();
    frame.gripper_speed = int16_value();
    frame.gripper_current = int16_value();
    frame.gripper_status = byte();
    frame.object_detection = byte();
    frame.crc = byte();
    return frame;
  }

  /// What a host streams in practice: positions and speeds within the joints' ranges.
  HostFrame realistic_host() {
    HostFrame frame;
    for (auto& position : frame.position_steps) position = uniform(-60000, 95000);
    for (auto& speed : frame.speed_steps_s) speed = uniform(-30000, 30000);
    frame.command = command::kGoToPosition;
    frame.gripper_position = static_cast<std::int16_t>(uniform(0, 255));
    frame.gripper_speed = static_cast<std::int16_t>(uniform(0, 255));
    frame.gripper_current_ma = static_cast<std::int16_t>(uniform(100, 1000));
    frame.gripper_command = 0xD0;
    return frame;
  }

  /// A frame with no 0xFF in its body, so nothing inside it can look like a start.
  HostFrame quiet_host() {
    HostFrame frame;
    for (auto& position : frame.position_steps) position = uniform(0, 60000);
    for (auto& speed : frame.speed_steps_s) speed = uniform(0, 30000);
    frame.command = command::kGoToPosition;
    frame.affected_joints = 0x00;
    return frame;
  }

  std::int32_t uniform(std::int32_t low, std::int32_t high) {
    return std::uniform_int_distribution<std::int32_t>(low, high)(random_);
  }
  std::uint8_t byte() { return static_cast<std::uint8_t>(uniform(0, 255)); }
  std::mt19937& engine() { return random_; }

 private:
  std::int32_t int24_value() { return uniform(-8388608, 8388607); }
  std::int16_t int16_value() { return static_cast<std::int16_t>(uniform(-32768, 32767)); }

  std::mt19937 random_;
};

/// `count` results of `make()`.
template <typename Make>
auto many(int count, Make&& make) {
  std::vector<decltype(make())> out;
  out.reserve(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) out.push_back(make());
  return out;
}

void expect_same(const HostFrame& a, const HostFrame& b) { EXPECT_EQ(hex(encode(a)), hex(encode(b))); }
void expect_same(const RobotFrame& a, const RobotFrame& b) { EXPECT_EQ(hex(encode(a)), hex(encode(b))); }

TEST(Parol6Frames, HostFramesRoundTrip) {
  RandomFrames random(1);
  for (int i = 0; i < 500; ++i) {
    const HostFrame frame = random.host();
    const auto bytes = encode(frame);
    const std::optional<HostFrame> back = decode_host_body(body_of(bytes));
    ASSERT_TRUE(back);
    expect_same(*back, frame);
    EXPECT_EQ(back->position_steps, frame.position_steps);
    EXPECT_EQ(back->gripper_current_ma, frame.gripper_current_ma);
  }
}

TEST(Parol6Frames, RobotFramesRoundTrip) {
  RandomFrames random(2);
  for (int i = 0; i < 500; ++i) {
    const RobotFrame frame = random.robot();
    const auto bytes = encode(frame);
    const std::optional<RobotFrame> back = decode_robot_body(body_of(bytes));
    ASSERT_TRUE(back);
    expect_same(*back, frame);
    EXPECT_EQ(back->speed_steps_s, frame.speed_steps_s);
    EXPECT_EQ(back->timing_ticks, frame.timing_ticks);
  }
}

TEST(Parol6Frames, GripperFieldsAreSigned16Bit) {
  HostFrame host;
  host.gripper_current_ma = -5;
  const auto bytes = encode(host);
  EXPECT_EQ(bytes[48], 0xFF);
  EXPECT_EQ(bytes[49], 0xFB);
  EXPECT_EQ(decode_host_body(body_of(bytes))->gripper_current_ma, -5);
  RobotFrame robot;
  robot.gripper_current = -300;
  EXPECT_EQ(decode_robot_body(body_of(encode(robot)))->gripper_current, -300);
}

TEST(Parol6Frames, DecodeRefusesBodiesTooShortForTheFields) {
  const auto host = encode(HostFrame{});
  const auto robot = encode(worked_example_c());
  for (std::size_t size = 0; size < kHostLength; ++size) {
    EXPECT_FALSE(decode_host_body(body_of(host).first(size))) << size;
  }
  EXPECT_TRUE(decode_host_body(body_of(host).first(kHostLength)));
  for (std::size_t size = 0; size < kRobotLength; ++size) {
    EXPECT_FALSE(decode_robot_body(body_of(robot).first(size))) << size;
  }
  EXPECT_TRUE(decode_robot_body(body_of(robot).first(kRobotLength)));
}

TEST(Parol6Frames, DecodeReadsFixedOffsetsWhateverTheLength) {
  // A LEN-255 body the board would accept: its fields are still read at body 0..49.
  HostFrame frame;
  frame.position_steps = kStandbySteps;
  frame.command = command::kHome;
  const auto bytes = encode(frame);
  Bytes body(255, 0x00);
  std::copy(bytes.begin() + 4, bytes.begin() + 54, body.begin());
  body[253] = 0x01;
  body[254] = 0x02;
  const std::optional<HostFrame> decoded = decode_host_body(body);
  ASSERT_TRUE(decoded);
  expect_same(*decoded, frame);
}

TEST(Parol6Frames, HomedBitsAreMsbFirstPerJoint) {
  RobotFrame frame;
  EXPECT_EQ(frame.homed, 0x03);
  for (int joint = 0; joint < kJoints; ++joint) EXPECT_FALSE(frame.joint_homed(joint));
  frame.homed = 0x80 | 0x03;
  EXPECT_TRUE(frame.joint_homed(0));
  EXPECT_FALSE(frame.joint_homed(1));
  frame.homed = 0x04;
  EXPECT_TRUE(frame.joint_homed(5));
  EXPECT_FALSE(frame.all_homed());
  frame.homed = 0xFC;  // the two always-1 bits do not matter
  EXPECT_TRUE(frame.all_homed());
  frame.homed = 0xF8 | 0x03;
  EXPECT_FALSE(frame.all_homed());
  frame.homed = 0xFF;
  EXPECT_FALSE(frame.joint_homed(-1));
  EXPECT_FALSE(frame.joint_homed(6));
}

TEST(Parol6Frames, EstopBitIsOneWhenReleased) {
  RobotFrame frame;
  frame.io = 0x0F;
  EXPECT_FALSE(frame.estop_pressed());
  frame.io = 0x07;
  EXPECT_TRUE(frame.estop_pressed());
}

TEST(Parol6Frames, ObjectDetectionFollowsTheGripperFirmware) {
  EXPECT_EQ(object_detection(0x00), ObjectDetection::kMoving);
  EXPECT_EQ(object_detection(0x20), ObjectDetection::kClosingOnObject);  // bit 0x20 is the code's LSB
  EXPECT_EQ(object_detection(0x10), ObjectDetection::kOpeningOnObject);
  EXPECT_EQ(object_detection(0x30), ObjectDetection::kAtPosition);
  EXPECT_EQ(object_detection(0xCF), ObjectDetection::kMoving);  // every other bit is not part of it
  EXPECT_EQ(object_detection(0x81 | 0x20), ObjectDetection::kClosingOnObject);
}

// --- stream parser -------------------------------------------------------------------------------

struct Parsed {
  std::vector<Bytes> bodies;
  std::uint64_t frames = 0;
  std::uint64_t rejected = 0;
  std::uint64_t discarded = 0;
  std::size_t accepted_bytes = 0;  // 4 + LEN of every accepted frame
  bool operator==(const Parsed&) const = default;
};

/// Feeds `stream` in chunks of the sizes `chunk` returns (the whole stream when it returns 0).
template <typename Chunk>
Parsed parse(FrameParser::Style style, const Bytes& stream, Chunk&& chunk) {
  FrameParser parser(style);
  Parsed parsed;
  std::span<const std::uint8_t> rest(stream);
  while (!rest.empty()) {
    std::size_t size = chunk();
    size = size == 0 ? rest.size() : std::min(size, rest.size());
    parser.feed(rest.first(size), [&](std::span<const std::uint8_t> body) {
      parsed.bodies.emplace_back(body.begin(), body.end());
      parsed.accepted_bytes += 4 + body.size();
    });
    rest = rest.subspan(size);
  }
  parsed.frames = parser.frames();
  parsed.rejected = parser.rejected();
  parsed.discarded = parser.discarded();
  return parsed;
}

Parsed parse(FrameParser::Style style, const Bytes& stream) {
  return parse(style, stream, [] { return std::size_t{0}; });
}

template <std::size_t kSize>
Bytes body_bytes(const std::array<std::uint8_t, kSize>& frame) {
  return Bytes(frame.begin() + 4, frame.end());
}

struct Stream {
  Bytes bytes;
  std::vector<Bytes> bodies;    // of each frame, in order
  std::vector<std::size_t> at;  // where each frame starts
};

/// Bytes that finish any pending candidate (LEN ≤ 255) without looking like a frame: a damaged
/// LEN can leave the parser waiting for up to 255 bytes, which a live link sends soon enough.
Bytes quiet_tail() { return zeros(4 + 255); }

template <typename Frame>
Stream stream_of(const std::vector<Frame>& frames) {
  Stream stream;
  for (const Frame& frame : frames) {
    const auto bytes = encode(frame);
    stream.at.push_back(stream.bytes.size());
    stream.bytes.insert(stream.bytes.end(), bytes.begin(), bytes.end());
    stream.bodies.push_back(body_bytes(bytes));
  }
  return stream;
}

constexpr int kHostFrameBytes = static_cast<int>(kHostFrameSize);
constexpr std::array<FrameParser::Style, 2> kStyles{FrameParser::Style::kFirmware, FrameParser::Style::kResync};

TEST(Parol6Parser, CleanStreamOfNFramesGivesN) {
  RandomFrames random(3);
  const auto hosts = many(40, [&] { return random.realistic_host(); });
  const auto robots = many(40, [&] { return random.robot(); });
  for (const auto style : kStyles) {
    const Stream host_stream = stream_of(hosts);
    const Parsed host = parse(style, host_stream.bytes);
    EXPECT_EQ(host.bodies, host_stream.bodies);
    EXPECT_EQ(host.frames, 40U);
    EXPECT_EQ(host.rejected, 0U);
    EXPECT_EQ(host.discarded, 0U);
    const Stream robot_stream = stream_of(robots);
    const Parsed robot = parse(style, robot_stream.bytes);
    EXPECT_EQ(robot.bodies, robot_stream.bodies);
    EXPECT_EQ(robot.frames, 40U);
    for (const Bytes& body : robot.bodies) EXPECT_TRUE(decode_robot_body(body));
  }
}

TEST(Parol6Parser, PayloadFullOfStartBytesParses) {
  HostFrame frame;
  frame.position_steps = {-1, -1, -1, -1, -1, -1};  // FF FF FF each
  frame.speed_steps_s = {-1, -1, -1, -1, -1, -1};
  frame.gripper_position = -1;
  for (const auto style : kStyles) {
    const Stream stream = stream_of(std::vector<HostFrame>(5, frame));
    const Parsed parsed = parse(style, stream.bytes);
    ASSERT_EQ(parsed.bodies.size(), 5U);
    for (const Bytes& body : parsed.bodies) {
      const std::optional<HostFrame> decoded = decode_host_body(body);
      ASSERT_TRUE(decoded);
      EXPECT_EQ(decoded->position_steps, frame.position_steps);
      EXPECT_EQ(decoded->speed_steps_s, frame.speed_steps_s);
    }
    EXPECT_EQ(parsed.rejected, 0U);
  }
}

TEST(Parol6Parser, NoiseBeforeAndBetweenFramesIsDiscarded) {
  const auto frame = encode(worked_example_c());
  Bytes stream = {0x00, 0x01, 0x02, 0xFF, 0x12, 0xFF, 0xFF, 0x34};
  stream.insert(stream.end(), frame.begin(), frame.end());
  stream.insert(stream.end(), {0x55, 0xAA});
  stream.insert(stream.end(), frame.begin(), frame.end());
  for (const auto style : kStyles) {
    const Parsed parsed = parse(style, stream);
    EXPECT_EQ(parsed.bodies, (std::vector<Bytes>{body_bytes(frame), body_bytes(frame)}));
    EXPECT_EQ(parsed.discarded, 10U);
    EXPECT_EQ(parsed.rejected, 0U);
  }
}

TEST(Parol6Parser, FeedingOneByteAtATimeOrInRandomChunksChangesNothing) {
  RandomFrames random(4);
  Bytes stream;
  for (int i = 0; i < 30; ++i) {
    const auto frame = encode(random.realistic_host());
    stream.insert(stream.end(), frame.begin(), frame.end());
    for (int noise = random.uniform(0, 3); noise > 0; --noise) stream.push_back(random.byte());
    if (i % 7 == 3) stream.erase(stream.end() - 20);  // a lost byte now and then
    if (i % 5 == 1) stream.insert(stream.end(), {0xFF, 0xFF, 0xFF});
  }
  for (const auto style : kStyles) {
    const Parsed whole = parse(style, stream);
    // The inserted FF FF FF make the board take the next frame's first FF as LEN 255.
    EXPECT_GT(whole.frames, style == FrameParser::Style::kResync ? 15U : 0U);
    // Every byte is accepted, discarded, or still waiting in at most one candidate.
    ASSERT_LE(whole.accepted_bytes + whole.discarded, stream.size());
    EXPECT_LT(stream.size() - whole.accepted_bytes - whole.discarded, 4U + 255U);
    EXPECT_EQ(parse(style, stream, [] { return std::size_t{1}; }), whole);
    for (int trial = 0; trial < 20; ++trial) {
      EXPECT_EQ(parse(style, stream, [&] { return static_cast<std::size_t>(random.uniform(1, 300)); }), whole);
    }
  }
}

/// Whether `got` is `expected` without frame `lost` (`lost` may also come through altered).
::testing::AssertionResult only_frame_lost(const std::vector<Bytes>& got, const std::vector<Bytes>& expected,
                                           std::size_t lost) {
  std::vector<Bytes> others = expected;
  others.erase(others.begin() + static_cast<std::ptrdiff_t>(lost));
  if (got == others) return ::testing::AssertionSuccess();
  if (got.size() == expected.size()) {
    std::vector<Bytes> without = got;
    without.erase(without.begin() + static_cast<std::ptrdiff_t>(lost));
    if (without == others) return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "got " << got.size() << " frames of " << expected.size()
                                       << ", not all but frame " << lost;
}

std::vector<HostFrame> quiet_frames(RandomFrames& random, int count) {
  return many(count, [&] { return random.quiet_host(); });
}

TEST(Parol6Parser, ResyncStyleLosesOnlyTheFrameThatLostAByteWhereverItWas) {
  RandomFrames random(5);
  constexpr int kFrames = 8;
  for (std::size_t k = 0; k < kFrames; ++k) {
    for (std::size_t offset = 0; offset < kHostFrameSize; ++offset) {
      Stream stream = stream_of(quiet_frames(random, kFrames));
      stream.bytes.erase(stream.bytes.begin() + static_cast<std::ptrdiff_t>(stream.at[k] + offset));
      append(stream.bytes, quiet_tail());
      const Parsed parsed = parse(FrameParser::Style::kResync, stream.bytes);
      ASSERT_TRUE(only_frame_lost(parsed.bodies, stream.bodies, k)) << "byte " << offset << " of frame " << k;
      EXPECT_EQ(parsed.bodies.size(), kFrames - 1U);
    }
  }
}

/// A LEN that puts a candidate's end bytes exactly on those of frame k + m (m ≥ 1).
bool lands_on_a_later_frame(std::uint8_t length) {
  return length > kHostLength && (length - kHostLength) % kHostFrameSize == 0;
}

TEST(Parol6Parser, ResyncStyleLosesAtMostTheFrameWithAGarbledByteWhereverItWas) {
  RandomFrames random(6);
  constexpr int kFrames = 8;
  for (std::size_t k = 0; k < kFrames; ++k) {
    for (std::size_t offset = 0; offset < kHostFrameSize; ++offset) {
      for (int trial = 0; trial < 4; ++trial) {
        Stream stream = stream_of(quiet_frames(random, kFrames));
        std::uint8_t& byte = stream.bytes[stream.at[k] + offset];
        byte = static_cast<std::uint8_t>(byte ^ random.uniform(1, 255));
        if (offset == 3 && lands_on_a_later_frame(byte)) continue;  // the next test
        append(stream.bytes, quiet_tail());
        const Parsed parsed = parse(FrameParser::Style::kResync, stream.bytes);
        ASSERT_TRUE(only_frame_lost(parsed.bodies, stream.bodies, k))
            << "byte " << offset << " of frame " << k << " now " << static_cast<int>(byte);
      }
    }
  }
}

TEST(Parol6Parser, AGarbledLengthThatLandsOnALaterFramesEndBytesSwallowsThatFrame) {
  // With no CRC, FF FF FF 6C followed by 108 bytes that end in 01 02 is a frame (§2.1): frames
  // k and k + 1 arrive as one 108-byte body. Only its length gives it away.
  RandomFrames random(12);
  Stream stream = stream_of(quiet_frames(random, 4));
  stream.bytes[stream.at[1] + 3] = kHostLength + kHostFrameSize;
  for (const auto style : kStyles) {
    const Parsed parsed = parse(style, stream.bytes);
    ASSERT_EQ(parsed.bodies.size(), 3U);
    EXPECT_EQ(parsed.bodies[0], stream.bodies[0]);
    EXPECT_EQ(parsed.bodies[1].size(), kHostLength + kHostFrameSize);
    EXPECT_EQ(parsed.bodies[2], stream.bodies[3]);
  }
}

TEST(Parol6Parser, ResyncStyleWithRealisticPayloadsLosesOnlyTheDamagedFrame) {
  // Negative positions and speeds put FF bytes in the payload, so a damaged frame can expose
  // false starts; their LEN would have to land exactly on a later frame's end bytes to pass.
  RandomFrames random(13);
  constexpr int kFrames = 10;
  for (int trial = 0; trial < 4000; ++trial) {
    Stream stream = stream_of(many(kFrames, [&] { return random.realistic_host(); }));
    const auto k = static_cast<std::size_t>(random.uniform(0, kFrames - 1));
    const auto offset = static_cast<std::size_t>(random.uniform(0, kHostFrameBytes - 1));
    const std::size_t at = stream.at[k] + offset;
    if (trial % 2 == 0) {
      stream.bytes.erase(stream.bytes.begin() + static_cast<std::ptrdiff_t>(at));
    } else {
      stream.bytes[at] = static_cast<std::uint8_t>(stream.bytes[at] ^ random.uniform(1, 255));
      if (offset == 3 && lands_on_a_later_frame(stream.bytes[at])) continue;
    }
    append(stream.bytes, quiet_tail());
    const Parsed parsed = parse(FrameParser::Style::kResync, stream.bytes);
    ASSERT_TRUE(only_frame_lost(parsed.bodies, stream.bodies, k))
        << "trial " << trial << ", byte " << offset << " of frame " << k << (trial % 2 == 0 ? " lost" : " garbled");
  }
}

TEST(Parol6Parser, ADamagedLengthDelaysTheFramesBehindItUntilItsCandidateIsFull) {
  // LEN 200 instead of 52: the frames inside the candidate come out only once its 204 bytes are
  // in, which at one 56-byte frame per cycle is about three cycles late.
  RandomFrames random(14);
  Stream stream = stream_of(quiet_frames(random, 3));
  stream.bytes[stream.at[0] + 3] = 200;
  EXPECT_TRUE(parse(FrameParser::Style::kResync, stream.bytes).bodies.empty());  // 168 of 204 bytes
  append(stream.bytes, zeros(kHostFrameSize));
  EXPECT_EQ(parse(FrameParser::Style::kResync, stream.bytes).bodies,
            std::vector<Bytes>(stream.bodies.begin() + 1, stream.bodies.end()));
}

TEST(Parol6Parser, FirmwareStyleAlsoLosesTheFrameAfterALostByte) {
  // The board hunts on after the whole (too long) candidate, which ate the next frame's first
  // start byte: the reason the host side resynchronises byte by byte instead.
  RandomFrames random(7);
  constexpr int kFrames = 8;
  for (int trial = 0; trial < 300; ++trial) {
    Stream stream = stream_of(quiet_frames(random, kFrames));
    const auto k = static_cast<std::size_t>(random.uniform(0, kFrames - 2));
    const auto offset = static_cast<std::size_t>(random.uniform(4, kHostFrameBytes - 1));  // in the body
    stream.bytes.erase(stream.bytes.begin() + static_cast<std::ptrdiff_t>(stream.at[k] + offset));
    std::vector<Bytes> expected = stream.bodies;
    expected.erase(expected.begin() + static_cast<std::ptrdiff_t>(k),
                   expected.begin() + static_cast<std::ptrdiff_t>(k + 2));
    EXPECT_EQ(parse(FrameParser::Style::kFirmware, stream.bytes).bodies, expected) << "byte " << offset;
    EXPECT_TRUE(only_frame_lost(parse(FrameParser::Style::kResync, stream.bytes).bodies, stream.bodies, k));
  }
}

TEST(Parol6Parser, FirmwareStyleTakesAFourthStartByteAsTheLength) {
  Bytes stream = {0xFF, 0xFF, 0xFF, 0xFF};  // LEN = 255
  Bytes body(255, 0x00);
  body[253] = 0x01;
  body[254] = 0x02;
  stream.insert(stream.end(), body.begin(), body.end());
  const Parsed parsed = parse(FrameParser::Style::kFirmware, stream);
  ASSERT_EQ(parsed.bodies.size(), 1U);
  EXPECT_EQ(parsed.bodies[0].size(), 255U);
  EXPECT_TRUE(decode_host_body(parsed.bodies[0]));
}

TEST(Parol6Parser, AStrayStartByteCostsTheBoardFramesButNotAResyncingHost) {
  RandomFrames random(8);
  Stream stream = stream_of(quiet_frames(random, 10));
  stream.bytes.insert(stream.bytes.begin(), 0xFF);  // FF FF FF FF 34: LEN = 255 swallows frames 0..4
  const Parsed board = parse(FrameParser::Style::kFirmware, stream.bytes);
  EXPECT_EQ(board.rejected, 1U);
  EXPECT_EQ(board.bodies.size(), 5U);
  EXPECT_EQ(board.bodies.back(), stream.bodies.back());
  const Parsed host = parse(FrameParser::Style::kResync, stream.bytes);
  EXPECT_EQ(host.bodies, stream.bodies);
  EXPECT_EQ(host.rejected, 1U);
  EXPECT_EQ(host.discarded, 1U);
}

TEST(Parol6Parser, LengthsTooShortForEndBytesAreRejected) {
  const auto frame = encode(HostFrame{});
  for (const auto style : kStyles) {
    for (const std::uint8_t length : {std::uint8_t{0}, std::uint8_t{1}}) {
      Bytes stream = {0xFF, 0xFF, 0xFF, length, 0x02};
      stream.insert(stream.end(), frame.begin(), frame.end());
      const Parsed parsed = parse(style, stream);
      EXPECT_EQ(parsed.bodies, std::vector<Bytes>{body_bytes(frame)});
      EXPECT_EQ(parsed.rejected, 1U);
    }
  }
}

TEST(Parol6Parser, AnyLengthWithTheEndBytesIsAFrame) {
  // Nothing but the end bytes is checked (§2.1): a short LEN passes, and decoding then refuses it.
  const Bytes stream = {0xFF, 0xFF, 0xFF, 0x04, 0xAA, 0xBB, 0x01, 0x02};
  for (const auto style : kStyles) {
    const Parsed parsed = parse(style, stream);
    ASSERT_EQ(parsed.bodies, (std::vector<Bytes>{{0xAA, 0xBB, 0x01, 0x02}}));
    EXPECT_FALSE(decode_host_body(parsed.bodies[0]));
  }
}

TEST(Parol6Parser, RandomBytesNeverCrashOrStall) {
  RandomFrames random(9);
  const auto frame = encode(worked_example_c());
  for (const auto style : kStyles) {
    for (int trial = 0; trial < 200; ++trial) {
      FrameParser parser(style);
      std::size_t fed = 0;
      std::size_t accepted = 0;
      const auto count = [&](std::span<const std::uint8_t> body) { accepted += 4 + body.size(); };
      for (int chunk = 0; chunk < 40; ++chunk) {
        Bytes noise(static_cast<std::size_t>(random.uniform(0, 200)));
        // Biased towards the bytes the parser looks for.
        for (std::uint8_t& byte : noise) {
          const int pick = random.uniform(0, 9);
          byte = pick < 3    ? std::uint8_t{0xFF}
                 : pick == 3 ? std::uint8_t{0x01}
                 : pick == 4 ? std::uint8_t{0x02}
                             : random.byte();
        }
        parser.feed(noise, count);
        fed += noise.size();
        // Everything fed is accepted, discarded, or waiting in one pending candidate.
        ASSERT_LE(accepted + parser.discarded(), fed);
        ASSERT_LE(fed - accepted - parser.discarded(), 4U + 255U);
      }
      // After a quiet gap long enough to finish any pending candidate the parser is in sync.
      parser.feed(zeros(260), count);
      std::size_t frames = 0;
      for (int i = 0; i < 3; ++i) {
        parser.feed(frame, [&](std::span<const std::uint8_t> body) {
          EXPECT_EQ(Bytes(body.begin(), body.end()), body_bytes(frame));
          ++frames;
        });
      }
      EXPECT_EQ(frames, 3U);
    }
  }
}

TEST(Parol6Parser, ParsingAndDecodingDoNotAllocate) {
  RandomFrames random(10);
  Bytes stream;
  for (int i = 0; i < 20; ++i) {
    const auto frame = encode(random.robot());
    stream.insert(stream.end(), frame.begin(), frame.end());
    stream.push_back(0xFF);
  }
  FrameParser parser(FrameParser::Style::kResync);
  std::int64_t sum = 0;
  const std::size_t before = testing::allocations_on_this_thread();
  parser.feed(stream, [&](std::span<const std::uint8_t> body) {
    if (const auto frame = decode_robot_body(body)) sum += frame->position_steps[0];
  });
  const auto bytes = encode(HostFrame{});
  sum += decode_host_body(body_of(bytes))->command;
  EXPECT_EQ(testing::allocations_on_this_thread(), before);
  EXPECT_GE(parser.frames(), 1U);
  EXPECT_NE(sum, 0);
}

// --- §10 joint units -----------------------------------------------------------------------------

constexpr double kPi = std::numbers::pi;
constexpr double degrees(double rad) { return rad * 180.0 / kPi; }

TEST(Parol6JointUnits, TableMatchesTheSpec) {
  const auto& units = joint_units();
  const std::array<double, kJoints> ratios{6.4, 20.0, 20.0 * 38.0 / 42.0, 4.0, 4.0, 10.0};
  const std::array<double, kJoints> max_speeds{15000, 25000, 32000, 10000, 10000, 27000};
  const std::array<double, kJoints> jog{12000, 20000, 25600, 8000, 8000, 21600};
  const std::array<double, kJoints> accelerations{45000, 75000, 96000, 30000, 30000, 81000};
  for (std::size_t j = 0; j < units.size(); ++j) {
    EXPECT_DOUBLE_EQ(units[j].gear_ratio, ratios[j]);
    EXPECT_EQ(units[j].standby_steps, kStandbySteps[j]);
    EXPECT_DOUBLE_EQ(units[j].max_speed_steps_s, max_speeds[j]);
    EXPECT_DOUBLE_EQ(units[j].jog_max_steps_s, jog[j]);
    EXPECT_DOUBLE_EQ(units[j].max_acceleration_steps_s2, accelerations[j]);
    EXPECT_LT(units[j].min_rad, units[j].max_rad);
    EXPECT_LE(units[j].max_speed_steps_s, kFirmwareMaxSpeedStepsPerSecond);
  }
  const std::array<std::array<double, 2>, kJoints> limits_deg{{{-123.046875, 123.046875},
                                                               {-145.0088, -3.375},
                                                               {107.866, 287.8675},
                                                               {-105.46975, 105.46975},
                                                               {-90, 90},
                                                               {0, 360}}};
  for (std::size_t j = 0; j < units.size(); ++j) {
    EXPECT_NEAR(degrees(units[j].min_rad), limits_deg[j][0], 1e-9);
    EXPECT_NEAR(degrees(units[j].max_rad), limits_deg[j][1], 1e-9);
  }
}

TEST(Parol6JointUnits, StepsPerDegreeMatchTheSpec) {
  const std::array<double, kJoints> steps_per_degree{113.7778, 355.5556, 321.6931, 71.1111, 71.1111, 177.7778};
  for (int j = 0; j < kJoints; ++j) {
    EXPECT_NEAR(steps_per_rad(j) * kPi / 180.0, steps_per_degree[static_cast<std::size_t>(j)], 1e-4);
  }
}

TEST(Parol6JointUnits, LimitsInStepsAreTheApisRoundedValues) {
  const std::array<std::array<std::int32_t, 2>, kJoints> steps{
      {{-14000, 14000}, {-51559, -1200}, {34700, 92605}, {-7500, 7500}, {-6400, 6400}, {0, 64000}}};
  for (int j = 0; j < kJoints; ++j) {
    const auto& units = joint_units()[static_cast<std::size_t>(j)];
    EXPECT_EQ(rad_to_steps(j, units.min_rad), steps[static_cast<std::size_t>(j)][0]) << "J" << j + 1;
    EXPECT_EQ(rad_to_steps(j, units.max_rad), steps[static_cast<std::size_t>(j)][1]) << "J" << j + 1;
  }
  EXPECT_NEAR(degrees(steps_to_rad(0, 14000)), 123.046875, 1e-12);
  EXPECT_NEAR(degrees(steps_to_rad(0, -14000)), -123.046875, 1e-12);
  // J3's limits sit within one step of the API's step values.
  EXPECT_NEAR(joint_units()[2].min_rad * steps_per_rad(2), 34700, 1.0);
  EXPECT_NEAR(joint_units()[2].max_rad * steps_per_rad(2), 92605, 1.0);
}

TEST(Parol6JointUnits, StandbyCountersAreTheHomedAngles) {
  const std::array<double, kJoints> standby_deg{90, -90, 180.0007, 0, 0, 180};
  for (int j = 0; j < kJoints; ++j) {
    const auto index = static_cast<std::size_t>(j);
    EXPECT_NEAR(degrees(steps_to_rad(j, joint_units()[index].standby_steps)), standby_deg[index], 1e-4);
  }
}

TEST(Parol6JointUnits, StepsRoundTripThroughRadians) {
  std::mt19937 random(11);
  for (int j = 0; j < kJoints; ++j) {
    for (int i = 0; i < 2000; ++i) {
      const std::int32_t steps = std::uniform_int_distribution<std::int32_t>(-100000, 100000)(random);
      ASSERT_EQ(rad_to_steps(j, steps_to_rad(j, steps)), steps);
      // Speeds truncate like both vendor hosts: a product a hair below the whole step loses it.
      const std::int32_t speed = rad_per_s_to_steps_per_s(j, steps_per_s_to_rad_per_s(j, steps));
      ASSERT_LE(std::abs(speed), std::abs(steps));
      ASSERT_LE(std::abs(steps) - std::abs(speed), 1);
    }
  }
}

TEST(Parol6JointUnits, PositionsRoundToTheNearestStepTiesToEvenAsTheApi) {
  const double step = 1.0 / steps_per_rad(5);
  EXPECT_EQ(rad_to_steps(5, 0.4 * step), 0);
  EXPECT_EQ(rad_to_steps(5, 0.6 * step), 1);
  EXPECT_EQ(rad_to_steps(5, -0.6 * step), -1);
  EXPECT_EQ(rad_to_steps(5, kPi), 32000);
  // Exact half steps of J1 (the product is 2.5 and 6.5 exactly): np.rint gives the even step,
  // where rounding half away from zero would give 3 and 7.
  EXPECT_EQ(rad_to_steps(0, 0.0003834951969714103), 2);
  EXPECT_EQ(rad_to_steps(0, -0.0003834951969714103), -2);
  EXPECT_EQ(rad_to_steps(0, 0.0009970875121256668), 6);
}

TEST(Parol6JointUnits, SpeedsTruncateTowardZeroAsBothHosts) {
  EXPECT_EQ(rad_per_s_to_steps_per_s(0, 1.0), 6518);  // 6400 · 6.4 / 2π = 6518.9
  EXPECT_EQ(rad_per_s_to_steps_per_s(0, -1.0), -6518);
  EXPECT_EQ(rad_per_s_to_steps_per_s(0, 0.1), 651);  // 651.9: the rounding robotd used to do gave 652
  EXPECT_NEAR(steps_per_s_to_rad_per_s(0, 15000), 15000 * 2 * kPi / 6400 / 6.4, 1e-12);
}

TEST(Parol6JointUnits, OutOfRangeValuesSaturate) {
  EXPECT_EQ(rad_to_steps(0, 1e12), std::numeric_limits<std::int32_t>::max());
  EXPECT_EQ(rad_to_steps(0, -1e12), std::numeric_limits<std::int32_t>::lowest());
  EXPECT_EQ(rad_to_steps(0, std::nan("")), 0);
  EXPECT_EQ(rad_per_s_to_steps_per_s(0, std::numeric_limits<double>::infinity()),
            std::numeric_limits<std::int32_t>::max());
}

}  // namespace
}  // namespace robotd::parol6
