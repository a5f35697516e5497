// The HighTorque codec against the spec (../shared/protocols/hightorque_and_ros2.md §1.6.1,
// §1.6.3 and the errata) and the vendor's worked examples: frames byte for byte, round trips of
// every frame kind (host ⇄ motor, host ⇄ USB board), truncation / saturation / sentinels,
// malformed input, the board's stream re-framing, and random input to every decoder.
#include "codec/hightorque_codec.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <initializer_list>
#include <iomanip>
#include <limits>
#include <new>
#include <numbers>
#include <optional>
#include <ostream>
#include <random>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "thread_allocations.hpp"

namespace robotd::hightorque {
namespace {

using transport::CanMessage;
using Bytes = std::vector<std::uint8_t>;

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const MotorScaling kCanFd{};  // CAN-FD firmware: N·m on the wire, gains per revolution
const std::array<MotorScaling, kMaxBlockMotorId + 1> kCanFdById{};  // block frames: by motor id

/// Revolutions (the motor's unit) → rad (robotd's).
constexpr double rev(double revolutions) { return revolutions * kTwoPi; }
/// A per-revolution motor gain → robotd's per-radian gain (with gain_factor 1).
constexpr double gain(double per_revolution) { return per_revolution / kTwoPi; }

/// What a frame puts on the bus, comparable and printable.
struct Wire {
  std::uint32_t id = 0;
  Bytes bytes;
  bool operator==(const Wire&) const = default;
};

std::ostream& operator<<(std::ostream& out, const Wire& wire) {
  out << "0x" << std::hex << std::uppercase << wire.id << " [";
  for (std::size_t i = 0; i < wire.bytes.size(); ++i) {
    out << (i == 0 ? "" : " ") << std::setw(2) << std::setfill('0') << static_cast<int>(wire.bytes[i]);
  }
  return out << "]" << std::dec;
}

Wire wire_of(const CanMessage& message) {
  return {message.id, Bytes(message.data.begin(), message.data.begin() + message.length)};
}

/// A received CAN-FD frame with a 29-bit id.
CanMessage fd_message(std::uint32_t id, const Bytes& bytes) {
  CanMessage message;
  message.id = id;
  message.extended = true;
  message.fd = true;
  message.length = static_cast<std::uint8_t>(bytes.size());
  std::copy(bytes.begin(), bytes.end(), message.data.begin());
  return message;
}

/// `bytes` followed by zero padding up to `length`.
Bytes padded(Bytes bytes, std::size_t length) {
  bytes.resize(length, 0);
  return bytes;
}

MotorCommand mit(double position_rad, double velocity_rad_s, double torque_nm, double kp, double kd) {
  MotorCommand command;
  command.mode = Mode::kMit;
  command.position_rad = position_rad;
  command.velocity_rad_s = velocity_rad_s;
  command.torque_nm = torque_nm;
  command.kp = kp;
  command.kd = kd;
  return command;
}

MotorCommand velocity(double velocity_rad_s) {
  MotorCommand command;
  command.mode = Mode::kVelocity;
  command.velocity_rad_s = velocity_rad_s;
  return command;
}

MotorCommand stopped(Mode mode) {
  MotorCommand command;
  command.mode = mode;
  return command;
}

// Decoded values carry the vendor's float precision (its parsers compute in float).
#define EXPECT_AS_FLOAT_EQ(actual, expected) EXPECT_FLOAT_EQ(static_cast<float>(actual), static_cast<float>(expected))

std::vector<MotorRequest> requests_of(const CanMessage& message, const MotorScaling& scaling = kCanFd) {
  std::vector<MotorRequest> out(64);
  out.resize(decode_request(message, scaling, out));
  return out;
}

/// Block frames for a bus of motors 1…motor_count (0: up to the highest motor of `slots`).
std::vector<CanMessage> blocks_of(const std::vector<BlockSlot>& slots, Query query = Query::kState,
                                  std::span<const MotorScaling> scaling = kCanFdById, int motor_count = 0) {
  if (motor_count == 0) {
    for (const BlockSlot& slot : slots) motor_count = std::max(motor_count, slot.motor);
  }
  std::vector<CanMessage> out(8);
  out.resize(encode_block(slots, query, scaling, motor_count, out));
  return out;
}

// ---- Identifiers ---------------------------------------------------------------------------

TEST(CanIds, CommandIdIsTypeCommandBitAndMotor) {
  EXPECT_EQ(command_id(Width::kInt16, 1), 0x18001U);
  EXPECT_EQ(command_id(Width::kInt32, 1), 0x28001U);
  EXPECT_EQ(command_id(Width::kFloat, 126), 0x3807EU);
}

TEST(CanIds, BlockCodeTakesTheMotorsPlace) { EXPECT_EQ(command_id(Width::kInt16, 0x98), 0x18098U); }

TEST(CanIds, ReplyIdMovesTheMotorToBits14To8WithBit15Clear) {
  EXPECT_EQ(reply_id(Width::kInt16, 1), 0x10100U);
  EXPECT_EQ(reply_id(Width::kInt32, 5), 0x20500U);
  EXPECT_EQ(reply_id(Width::kFloat, 126), 0x37E00U);
}

// ---- Single-motor commands (FDCan_Protocol.md examples) --------------------------------------

TEST(SingleCommands, AreCanFdExtendedWithBitRateSwitch) {
  const CanMessage message = encode_command(1, velocity(rev(0.1)), Width::kInt16, Query::kState, kCanFd);
  EXPECT_TRUE(message.extended);
  EXPECT_TRUE(message.fd);
  EXPECT_TRUE(message.bitrate_switch);
}

TEST(SingleCommands, VelocityInt16) {
  EXPECT_EQ(wire_of(encode_command(1, velocity(rev(0.1)), Width::kInt16, Query::kState, kCanFd)),
            (Wire{0x18001, {0x1C, 0x0B, 0x90, 0x01}}));
}

TEST(SingleCommands, StopAndBrakeCarryModeAndQueryOnly) {
  EXPECT_EQ(wire_of(encode_command(1, stopped(Mode::kStop), Width::kInt16, Query::kState, kCanFd)),
            (Wire{0x18001, {0x01, 0x0B}}));
  EXPECT_EQ(wire_of(encode_command(1, stopped(Mode::kBrake), Width::kInt32, Query::kState, kCanFd)),
            (Wire{0x28001, {0x18, 0x0B}}));
}

TEST(SingleCommands, VoltageSendsZeroDAxisThenQ) {
  MotorCommand command;
  command.mode = Mode::kVoltage;
  command.voltage_q_v = 1.5;
  EXPECT_EQ(wire_of(encode_command(1, command, Width::kInt16, Query::kState, kCanFd)),
            (Wire{0x18001, {0x19, 0x0B, 0x00, 0x00, 0x0F, 0x00}}));
}

TEST(SingleCommands, TorqueInt16IsHundredthsOfNewtonMetre) {
  MotorCommand command;
  command.mode = Mode::kTorque;
  command.torque_nm = 0.35;
  EXPECT_EQ(wire_of(encode_command(1, command, Width::kInt16, Query::kState, kCanFd)),
            (Wire{0x18001, {0x1B, 0x0B, 0x23, 0x00}}));
}

TEST(SingleCommands, PositionVelocityTorqueInt32PadsFourteenBytesToSixteen) {
  MotorCommand command;
  command.mode = Mode::kPositionVelocityTorque;
  command.position_rad = rev(0.5);
  command.velocity_rad_s = rev(0.5);
  command.torque_nm = 1.0;
  EXPECT_EQ(wire_of(encode_command(1, command, Width::kInt32, Query::kState, kCanFd)),
            (Wire{0x28001,
                  padded({0x1F, 0x0B, 0x50, 0xC3, 0x00, 0x00, 0x50, 0xC3, 0x00, 0x00, 0xE8, 0x03, 0x00, 0x00}, 16)}));
}

TEST(SingleCommands, MitInt16) {
  EXPECT_EQ(wire_of(encode_command(1, mit(rev(1.0), 0, 0, gain(20), gain(2)), Width::kInt16, Query::kState, kCanFd)),
            (Wire{0x18001, {0x21, 0x0B, 0x10, 0x27, 0x00, 0x00, 0x00, 0x00, 0xC8, 0x00, 0x14, 0x00}}));
}

TEST(SingleCommands, MitInt32PadsTwentyTwoBytesToTwentyFour) {
  EXPECT_EQ(wire_of(encode_command(1, mit(rev(3.0), 0, 0, gain(30), gain(3)), Width::kInt32, Query::kState, kCanFd)),
            (Wire{0x28001, padded({0x21, 0x0B, 0xE0, 0x93, 0x04, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
                                   0x00, 0x00, 0x00, 0x30, 0x75, 0x00, 0x00, 0xB8, 0x0B, 0x00, 0x00},
                                  24)}));
}

TEST(SingleCommands, MitFloatIsRevolutionsAsIeeeSingles) {
  EXPECT_EQ(
      wire_of(encode_command(1, mit(rev(0.5), rev(1.0), 2.0, gain(10), gain(1)), Width::kFloat, Query::kState, kCanFd)),
      (Wire{0x38001, padded({0x21, 0x0B, 0x00, 0x00, 0x00, 0x3F, 0x00, 0x00, 0x80, 0x3F, 0x00,
                             0x00, 0x00, 0x40, 0x00, 0x00, 0x20, 0x41, 0x00, 0x00, 0x80, 0x3F},
                            24)}));
}

TEST(SingleCommands, QueryGoesInByteOne) {
  const CanMessage message = encode_command(7, velocity(0), Width::kInt16, Query::kStateTemperature, kCanFd);
  EXPECT_EQ(message.id, 0x18007U);
  EXPECT_EQ(message.data[1], 0x0C);
}

TEST(SingleCommands, GainFactorAndTorqueScalingApply) {
  const MotorScaling scaling{.torque_per_unit = 0.5, .torque_offset_nm = 1.0, .gain_factor = 2.0};
  // τ: (3 − 1) / 0.5 = 4 N·m → 400; kp: 2π·(20/2π)/2 = 10 → 100.
  EXPECT_EQ(wire_of(encode_command(1, mit(0, 0, 3.0, gain(20), 0), Width::kInt16, Query::kState, scaling)),
            (Wire{0x18001, {0x21, 0x0B, 0x00, 0x00, 0x00, 0x00, 0x90, 0x01, 0x64, 0x00, 0x00, 0x00}}));
}

// ---- Conversion: truncation, saturation, sentinels ------------------------------------------

TEST(Conversion, TruncatesTowardZero) {
  // 0.2999 rev/s × 4000 = 1199.6 → 1199 (0x04AF), as the vendor's C cast does.
  EXPECT_EQ(wire_of(encode_command(1, velocity(rev(0.2999)), Width::kInt16, Query::kState, kCanFd)).bytes,
            (Bytes{0x1C, 0x0B, 0xAF, 0x04}));
}

TEST(Conversion, TruncatesNegativeNumbersTowardZero) {
  // −1199.6 → −1199 = 0xFB51.
  EXPECT_EQ(wire_of(encode_command(1, velocity(rev(-0.2999)), Width::kInt16, Query::kState, kCanFd)).bytes,
            (Bytes{0x1C, 0x0B, 0x51, 0xFB}));
}

TEST(Conversion, Int16SaturatesOneCountInsideTheSentinel) {
  EXPECT_EQ(wire_of(encode_command(1, velocity(rev(100.0)), Width::kInt16, Query::kState, kCanFd)).bytes,
            (Bytes{0x1C, 0x0B, 0xFF, 0x7F}));
  EXPECT_EQ(wire_of(encode_command(1, velocity(rev(-100.0)), Width::kInt16, Query::kState, kCanFd)).bytes,
            (Bytes{0x1C, 0x0B, 0x01, 0x80}));
}

TEST(Conversion, Int32Saturates) {
  EXPECT_EQ(wire_of(encode_command(1, velocity(rev(1e9)), Width::kInt32, Query::kState, kCanFd)).bytes,
            (Bytes{0x1C, 0x0B, 0xFF, 0xFF, 0xFF, 0x7F}));
  EXPECT_EQ(wire_of(encode_command(1, velocity(-std::numeric_limits<double>::infinity()), Width::kInt32, Query::kState,
                                   kCanFd))
                .bytes,
            (Bytes{0x1C, 0x0B, 0x01, 0x00, 0x00, 0x80}));
}

TEST(Conversion, NaNEncodesAsTheNoValueSentinel) {
  EXPECT_EQ(wire_of(encode_command(1, velocity(kNaN), Width::kInt16, Query::kState, kCanFd)).bytes,
            (Bytes{0x1C, 0x0B, 0x00, 0x80}));
  EXPECT_EQ(wire_of(encode_command(1, velocity(kNaN), Width::kInt32, Query::kState, kCanFd)).bytes,
            (Bytes{0x1C, 0x0B, 0x00, 0x00, 0x00, 0x80}));
  const std::vector<MotorRequest> requests =
      requests_of(encode_command(1, velocity(kNaN), Width::kFloat, Query::kState, kCanFd));
  ASSERT_EQ(requests.size(), 1U);
  EXPECT_TRUE(std::isnan(requests[0].command.velocity_rad_s));
}

TEST(Conversion, SentinelDecodesAsUnsetField) {
  const std::vector<MotorRequest> requests = requests_of(fd_message(0x18001, {0x1C, 0x0B, 0x00, 0x80}));
  ASSERT_EQ(requests.size(), 1U);
  EXPECT_FALSE(requests[0].has_velocity);
  EXPECT_TRUE(std::isnan(requests[0].command.velocity_rad_s));
}

// ---- Block (one-to-many) frames --------------------------------------------------------------

TEST(BlockFrames, MitSixMotorsFillBlock0x98) {
  std::vector<BlockSlot> slots;
  for (int motor = 1; motor <= 6; ++motor) slots.push_back({motor, mit(rev(0.5), 0, 0, gain(10), gain(1))});
  const std::vector<CanMessage> frames = blocks_of(slots);
  ASSERT_EQ(frames.size(), 1U);
  Bytes expected;
  for (int motor = 1; motor <= 6; ++motor) {
    expected.insert(expected.end(), {0x88, 0x13, 0x00, 0x00, 0x00, 0x00, 0x64, 0x00, 0x0A, 0x00});
  }
  expected = padded(expected, 63);  // 60 data bytes + 3 of padding
  expected.push_back(0x0B);         // the query in the last byte of the 64
  EXPECT_EQ(wire_of(frames[0]), (Wire{0x18098, expected}));
}

TEST(BlockFrames, MotorsWithoutACommandGetTheNoValueMarker) {
  const std::vector<CanMessage> frames =
      blocks_of({{4, mit(rev(0.5), 0, 0, gain(10), gain(1))}, {2, mit(rev(1.0), 0, 0, gain(20), gain(2))}});
  ASSERT_EQ(frames.size(), 1U);
  const Bytes unset{0x00, 0x80, 0x00, 0x80, 0x00, 0x80, 0x00, 0x80, 0x00, 0x80};
  Bytes expected = unset;                                                                         // motor 1
  expected.insert(expected.end(), {0x10, 0x27, 0x00, 0x00, 0x00, 0x00, 0xC8, 0x00, 0x14, 0x00});  // motor 2
  expected.insert(expected.end(), unset.begin(), unset.end());                                    // motor 3
  expected.insert(expected.end(), {0x88, 0x13, 0x00, 0x00, 0x00, 0x00, 0x64, 0x00, 0x0A, 0x00});  // motor 4
  expected = padded(expected, 47);
  expected.push_back(0x0B);
  EXPECT_EQ(wire_of(frames[0]), (Wire{0x18098, expected}));
}

TEST(BlockFrames, EveryMotorOfTheBusIsSentEvenInFramesWithoutACommand) {
  // As the vendor's motor_many.c: a bus of 13 motors is 0x98 (1–6), 0x99 (7–12), 0x9A (13).
  const std::vector<CanMessage> frames = blocks_of({{7, mit(0, 0, 0, 0, 0)}}, Query::kState, kCanFdById, 13);
  ASSERT_EQ(frames.size(), 3U);
  EXPECT_EQ(frames[0].id, 0x18098U);
  EXPECT_EQ(frames[1].id, 0x18099U);
  EXPECT_EQ(frames[2].id, 0x1809AU);
  EXPECT_EQ(frames[0].length, 64U);
  EXPECT_EQ(frames[2].length, 12U);  // one slot + query → 11 → 12
  for (std::size_t at = 0; at < 60; at += 2) {
    EXPECT_EQ(frames[0].data[at + 1], 0x80) << "motor 1–6 byte " << at;  // 0x8000: no value
    if (at >= 10) {
      EXPECT_EQ(frames[1].data[at + 1], 0x80) << "motor 8–12 byte " << at;
    }
  }
  EXPECT_EQ(frames[1].data[1], 0x00);  // motor 7: position 0
}

TEST(BlockFrames, VelocityThreeMotorsNeedNoPadding) {
  EXPECT_EQ(wire_of(blocks_of({{1, velocity(rev(0.1))}, {2, velocity(rev(0.5))}, {3, velocity(rev(1.0))}})[0]),
            (Wire{0x18081, {0x90, 0x01, 0xD0, 0x07, 0xA0, 0x0F, 0x0B}}));
}

TEST(BlockFrames, PaddingReadsAsUnsetSlotsAndTheQueryIsTheLastByte) {
  std::vector<BlockSlot> slots;
  for (int motor = 1; motor <= 4; ++motor) slots.push_back({motor, velocity(0)});
  // 8 data bytes + query = 9 → 12: bytes 8–9 are a fifth (unset) slot, byte 10 padding.
  EXPECT_EQ(wire_of(blocks_of(slots, Query::kCompact)[0]),
            (Wire{0x18081, {0, 0, 0, 0, 0, 0, 0, 0, 0x00, 0x80, 0x00, 0x0E}}));
}

TEST(BlockFrames, RejectMotorsAboveTheBusMotorCount) {
  EXPECT_TRUE(blocks_of({{5, velocity(0)}}, Query::kState, kCanFdById, 4).empty());
  EXPECT_TRUE(blocks_of({{1, velocity(0)}}, Query::kState, kCanFdById, 31).empty());
}

TEST(BlockFrames, VelocityAccelerationIsFourBytesPerMotor) {
  MotorCommand first = velocity(rev(0.1));
  first.mode = Mode::kVelocityAcceleration;
  first.acceleration_rad_s2 = rev(1.0);
  MotorCommand second = velocity(rev(0.5));
  second.mode = Mode::kVelocityAcceleration;
  second.acceleration_rad_s2 = rev(2.0);
  EXPECT_EQ(wire_of(blocks_of({{1, first}, {2, second}})[0]),
            (Wire{0x18090, {0x90, 0x01, 0xE8, 0x03, 0xD0, 0x07, 0xD0, 0x07, 0x00, 0x00, 0x00, 0x0B}}));
}

TEST(BlockFrames, PositionVelocityAccelerationIsSixBytesPerMotor) {
  MotorCommand first;
  first.mode = Mode::kPositionVelocityAcceleration;
  first.position_rad = rev(0.5);
  first.velocity_rad_s = rev(0.5);
  first.acceleration_rad_s2 = rev(0.1);
  MotorCommand second = first;
  second.position_rad = rev(1.0);
  second.velocity_rad_s = rev(1.0);
  second.acceleration_rad_s2 = rev(0.5);
  Bytes expected = padded({0x88, 0x13, 0xD0, 0x07, 0x64, 0x00, 0x10, 0x27, 0xA0, 0x0F, 0xF4, 0x01}, 15);
  expected.push_back(0x0B);
  EXPECT_EQ(wire_of(blocks_of({{1, first}, {2, second}})[0]), (Wire{0x18095, expected}));
}

TEST(BlockFrames, StopIsOneFlagBytePerMotor) {
  EXPECT_EQ(wire_of(blocks_of({{1, stopped(Mode::kStop)}, {3, stopped(Mode::kStop)}})[0]),
            (Wire{0x18085, {0x01, 0x00, 0x01, 0x0B}}));
}

TEST(BlockFrames, BrakeIsBlock0x86) {
  EXPECT_EQ(wire_of(blocks_of({{2, stopped(Mode::kBrake)}})[0]), (Wire{0x18086, {0x00, 0x01, 0x0B}}));
}

TEST(BlockFrames, PositionVelocityTorqueIsTenMotorsPerFrame) {
  MotorCommand command;
  command.mode = Mode::kPositionVelocityTorque;
  const std::vector<CanMessage> frames = blocks_of({{10, command}, {11, command}, {30, command}});
  ASSERT_EQ(frames.size(), 3U);
  EXPECT_EQ(frames[0].id, 0x18092U);
  EXPECT_EQ(frames[1].id, 0x18093U);
  EXPECT_EQ(frames[2].id, 0x18094U);
}

TEST(BlockFrames, RejectMixedModes) { EXPECT_TRUE(blocks_of({{1, velocity(0)}, {2, stopped(Mode::kStop)}}).empty()); }

TEST(BlockFrames, RejectMotorsOutsideOneToThirty) {
  EXPECT_TRUE(blocks_of({{31, velocity(0)}}).empty());
  EXPECT_TRUE(blocks_of({{0, velocity(0)}}).empty());
}

TEST(BlockFrames, RejectOutputTooSmall) {
  const std::vector<BlockSlot> slots{{1, mit(0, 0, 0, 0, 0)}, {7, mit(0, 0, 0, 0, 0)}};
  std::array<CanMessage, 1> out{};
  EXPECT_EQ(encode_block(slots, Query::kState, kCanFdById, 7, out), 0U);
}

TEST(BlockFrames, EachMotorUsesItsOwnScaling) {
  std::array<MotorScaling, 3> scaling{};
  scaling[2].torque_per_unit = 0.5;
  MotorCommand torque;
  torque.mode = Mode::kTorque;
  torque.torque_nm = 1.0;
  EXPECT_EQ(wire_of(blocks_of({{1, torque}, {2, torque}}, Query::kState, scaling)[0]),
            (Wire{0x18082, {0x64, 0x00, 0xC8, 0x00, 0x0B}}));
}

TEST(BlockFrames, RejectMotorsWithoutScaling) {
  EXPECT_TRUE(blocks_of({{3, velocity(0)}}, Query::kState, std::array<MotorScaling, 3>{}).empty());
}

TEST(BlockFrames, NoSlotsNoFrames) { EXPECT_TRUE(blocks_of({}).empty()); }

// ---- System commands ---------------------------------------------------------------------------

TEST(SystemCommands, ConfigurationOperations) {
  EXPECT_EQ(wire_of(encode_soft_reboot(1)), (Wire{0x18001, {0x03, 0x03, 0x01}}));
  EXPECT_EQ(wire_of(encode_save_to_flash(1)), (Wire{0x18001, {0x03, 0x03, 0x02}}));
  EXPECT_EQ(wire_of(encode_set_zero(1)), (Wire{0x18001, {0x03, 0x03, 0x03}}));
  EXPECT_EQ(wire_of(encode_change_id(1, 2).value()), (Wire{0x18001, {0x03, 0x03, 0x04, 0x02}}));
}

TEST(SystemCommands, ChangeIdRefusesIdsOutsideOneToThirty) {
  // The vendor's hightorque_id() sends nothing for these; 200 used to go out as 72 (masked).
  for (const auto& [motor, new_id] :
       {std::pair{1, 200}, std::pair{1, 127}, std::pair{1, 31}, std::pair{1, 0}, std::pair{31, 2}, std::pair{0, 2}}) {
    const Result<CanMessage> frame = encode_change_id(motor, new_id);
    ASSERT_FALSE(frame) << motor << " → " << new_id;
    EXPECT_EQ(frame.error().code, ErrorCode::kInvalidArgument);
    EXPECT_NE(frame.error().message.find("outside the motor ids 1…30"), std::string::npos) << frame.error().message;
  }
  EXPECT_NE(encode_change_id(1, 200).error().message.find("new id 200"), std::string::npos);
  EXPECT_TRUE(encode_change_id(30, 1));
}

TEST(SystemCommands, CommandTimeoutIs05ThenMillisecondsLittleEndian) {
  EXPECT_EQ(wire_of(encode_command_timeout(1, 500)), (Wire{0x18001, {0x05, 0xF4, 0x01}}));
}

TEST(SystemCommands, StatusPushIs03_00_05QueryThenMicroseconds) {
  EXPECT_EQ(wire_of(encode_status_push(3, Query::kState, 1000)),
            (Wire{0x18003, {0x03, 0x00, 0x05, 0x0B, 0xE8, 0x03, 0x00, 0x00}}));
}

TEST(SystemCommands, InfoRequests) {
  EXPECT_EQ(wire_of(encode_info_request(1, InfoKind::kFirmwareVersion)), (Wire{0x18001, {0x00, 0x04}}));
  EXPECT_EQ(wire_of(encode_info_request(1, InfoKind::kHardwareVersion)), (Wire{0x18001, {0x00, 0x05}}));
  EXPECT_EQ(wire_of(encode_info_request(1, InfoKind::kModel)), (Wire{0x18001, {0x00, 0x07}}));
}

TEST(SystemCommands, QueryWithoutModeChangeUsesModeByteZero) {
  EXPECT_EQ(wire_of(encode_query(1, Query::kState, Width::kInt32)), (Wire{0x28001, {0x00, 0x0B}}));
}

// ---- Replies ------------------------------------------------------------------------------------

std::optional<Reply> reply_of(std::uint32_t id, const Bytes& bytes, int max_motor_id = kMaxMotorId) {
  return decode_reply(fd_message(id, bytes), max_motor_id, kCanFd);
}

/// A reply's position, velocity (in revolutions) and torque.
void expect_motion(const MotorState& state, double position_rev, double velocity_rev, double torque_nm) {
  EXPECT_AS_FLOAT_EQ(state.position_rad, rev(position_rev));
  EXPECT_AS_FLOAT_EQ(state.velocity_rad_s, rev(velocity_rev));
  EXPECT_AS_FLOAT_EQ(state.torque_nm, torque_nm);
}

TEST(Replies, StateInt16) {
  const std::optional<Reply> reply = reply_of(0x10100, {0x0B, 0x1C, 0x00, 0xC8, 0x00, 0x90, 0x01, 0x03, 0x00});
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->kind, Reply::Kind::kState);
  EXPECT_EQ(reply->state.motor, 1);
  EXPECT_EQ(reply->state.query, Query::kState);
  EXPECT_EQ(reply->state.mode, 0x1C);
  EXPECT_EQ(reply->state.fault, 0x00);
  expect_motion(reply->state, 0.02, 0.1, 0.03);  // raw torque 3 is 0.03 N·m, not the readme's 0.3
  EXPECT_FALSE(reply->state.temperature_c.has_value());
  EXPECT_FALSE(reply->state.counter.has_value());
}

TEST(Replies, StatePaddedToTwelveBytes) {
  EXPECT_TRUE(reply_of(0x10100, padded({0x0B, 0x1C, 0x00, 0xC8, 0x00, 0x90, 0x01, 0x03, 0x00}, 12)).has_value());
}

TEST(Replies, StateInt32) {
  const std::optional<Reply> reply =
      reply_of(0x20200, {0x0B, 0x1D, 0x00, 0x50, 0xC3, 0x00, 0x00, 0xA0, 0x86, 0x01, 0x00, 0xE8, 0x03, 0x00, 0x00});
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->state.motor, 2);
  expect_motion(reply->state, 0.5, 1.0, 1.0);
}

TEST(Replies, StateFloat) {
  const std::optional<Reply> reply =
      reply_of(0x30100, {0x0B, 0x21, 0x15, 0x00, 0x00, 0x00, 0x3F, 0x00, 0x00, 0x80, 0x3F, 0x00, 0x00, 0x00, 0x40});
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->state.mode, 0x21);
  EXPECT_EQ(reply->state.fault, 0x15);
  expect_motion(reply->state, 0.5, 1.0, 2.0);
}

TEST(Replies, TheNoValueMarkerReadsAsASaturatedNumberLikeTheVendor) {
  // motor.c reads 0x8000 as −32768 (a saturated reading), not as "no value".
  const std::optional<Reply> reply = reply_of(0x10100, {0x0B, 0x21, 0x00, 0x00, 0x80, 0x00, 0x80, 0x00, 0x80});
  ASSERT_TRUE(reply.has_value());
  expect_motion(reply->state, -3.2768, -8.192, -327.68);
}

TEST(Replies, MotorsAboveThirtyAreNotRead) {
  EXPECT_TRUE(reply_of(0x11E00, {0x0B, 0x21, 0x00, 0, 0, 0, 0, 0, 0}).has_value());
  EXPECT_FALSE(reply_of(0x11F00, {0x0B, 0x21, 0x00, 0, 0, 0, 0, 0, 0}).has_value());
}

TEST(Replies, StateTemperatureInt16IsTenthsOfDegrees) {
  const std::optional<Reply> reply =
      reply_of(0x10100, {0x0C, 0x1C, 0x00, 0xFA, 0x00, 0xC8, 0x00, 0x90, 0x01, 0x03, 0x00});
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->state.query, Query::kStateTemperature);
  ASSERT_TRUE(reply->state.temperature_c.has_value());
  EXPECT_AS_FLOAT_EQ(*reply->state.temperature_c, 25.0);
  EXPECT_AS_FLOAT_EQ(reply->state.position_rad, rev(0.02));
  EXPECT_AS_FLOAT_EQ(reply->state.torque_nm, 0.03);
}

TEST(Replies, StateTemperatureInt32IsThousandthsOfDegrees) {
  Bytes bytes{0x0C, 0x1C, 0x00, 0x9C, 0x63, 0x00, 0x00};  // 25500
  bytes.resize(bytes.size() + 12, 0);
  const std::optional<Reply> reply = reply_of(0x20100, bytes);
  ASSERT_TRUE(reply.has_value());
  ASSERT_TRUE(reply->state.temperature_c.has_value());
  EXPECT_AS_FLOAT_EQ(*reply->state.temperature_c, 25.5);
}

TEST(Replies, CompactHasNoMode) {
  const std::optional<Reply> reply = reply_of(0x10100, {0x0E, 0x14, 0xC8, 0x00, 0x90, 0x01, 0x03, 0x00});
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->state.query, Query::kCompact);
  EXPECT_EQ(reply->state.mode, 0);
  EXPECT_EQ(reply->state.fault, 0x14);
  expect_motion(reply->state, 0.02, 0.1, 0.03);
}

TEST(Replies, CounterInt16) {
  const std::optional<Reply> reply = reply_of(0x10100, {0x0A, 0x1C, 0x00, 0x2A, 0x01});
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->state.query, Query::kCounter);
  EXPECT_EQ(reply->state.counter, std::optional<std::uint16_t>(0x012A));
}

TEST(Replies, FirmwareVersionIsPatchMinorMajor) {
  const std::optional<Reply> reply = reply_of(0x10100, {0x04, 0x03, 0x03, 0x00});
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->kind, Reply::Kind::kFirmwareVersion);
  EXPECT_EQ(reply->version.motor, 1);
  EXPECT_EQ(reply->version.major, 0);
  EXPECT_EQ(reply->version.minor, 3);
  EXPECT_EQ(reply->version.patch, 3);
}

TEST(Replies, HardwareVersionHasTheSameLayout) {
  const std::optional<Reply> reply = reply_of(0x10100, {0x05, 0x01, 0x02, 0x03});
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->kind, Reply::Kind::kHardwareVersion);
  EXPECT_EQ(reply->version.major, 3);
}

TEST(Replies, ModelIsLengthThenAscii) {
  const std::optional<Reply> reply = reply_of(0x10300, padded({0x07, 0x07, '5', '0', '4', '7', '_', '3', '6'}, 12));
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->kind, Reply::Kind::kModel);
  EXPECT_EQ(reply->model.motor, 3);
  EXPECT_STREQ(reply->model.text.data(), "5047_36");
}

TEST(Replies, CommandResultSucceedsOnZero) {
  const std::optional<Reply> ok = reply_of(0x10100, {0x03, 0x00});
  ASSERT_TRUE(ok.has_value());
  EXPECT_EQ(ok->kind, Reply::Kind::kResult);
  EXPECT_TRUE(ok->result.success);
  const std::optional<Reply> failed = reply_of(0x10100, {0x03, 0x05});
  ASSERT_TRUE(failed.has_value());
  EXPECT_FALSE(failed->result.success);
  EXPECT_EQ(failed->result.code, 0x05);
}

Bytes state_reply() { return {0x0B, 0x1C, 0x00, 0xC8, 0x00, 0x90, 0x01, 0x03, 0x00}; }

TEST(Replies, RejectCommandIds) { EXPECT_FALSE(reply_of(0x18001, state_reply()).has_value()); }

TEST(Replies, RejectTypeZero) { EXPECT_FALSE(reply_of(0x00100, state_reply()).has_value()); }

TEST(Replies, RejectMotorZero) { EXPECT_FALSE(reply_of(0x10000, state_reply()).has_value()); }

TEST(Replies, RejectMotorAboveTheConfiguredCount) {
  EXPECT_FALSE(reply_of(0x10500, state_reply(), 4).has_value());
  EXPECT_TRUE(reply_of(0x10400, state_reply(), 4).has_value());
}

TEST(Replies, RejectEmptyFrames) { EXPECT_FALSE(reply_of(0x10100, {}).has_value()); }

TEST(Replies, RejectTruncatedPayloads) {
  Bytes truncated = state_reply();
  truncated.pop_back();
  EXPECT_FALSE(reply_of(0x10100, truncated).has_value());
  EXPECT_FALSE(reply_of(0x10100, {0x07, 0x05, 'a', 'b'}).has_value());
  EXPECT_FALSE(reply_of(0x10100, {0x04, 0x01}).has_value());
}

TEST(Replies, RejectUnknownQueryCodes) {
  EXPECT_FALSE(reply_of(0x10100, {0x0D, 0x1C, 0x00, 0x00, 0x00, 0x00, 0x00}).has_value());
}

TEST(Replies, RejectReservedBitsAndStandardIds) {
  EXPECT_FALSE(reply_of(0x50100, state_reply()).has_value());
  CanMessage standard = fd_message(0x100, state_reply());
  standard.extended = false;
  EXPECT_FALSE(decode_reply(standard, kMaxMotorId, kCanFd).has_value());
}

TEST(Replies, NeverReadPastTheBuffer) {
  CanMessage message = fd_message(0x10100, state_reply());
  message.length = 255;  // a corrupt length: the decoder reads at most the 64-byte buffer
  EXPECT_TRUE(decode_reply(message, kMaxMotorId, kCanFd).has_value());
}

// ---- Motor side: encode_reply and the info replies round-trip through decode_reply ---------

TEST(MotorReplies, EveryStateReplyRoundTripsAtEveryWidth) {
  for (const Query query : {Query::kCounter, Query::kState, Query::kStateTemperature, Query::kCompact}) {
    for (const Width width : {Width::kInt16, Width::kInt32, Width::kFloat}) {
      SCOPED_TRACE(::testing::Message() << "query " << static_cast<int>(query) << " width " << static_cast<int>(width));
      MotorState state;
      state.motor = 9;
      state.query = query;
      state.mode = 0x21;
      state.fault = 0x15;
      state.position_rad = rev(-1.25);
      state.velocity_rad_s = rev(0.5);
      state.torque_nm = -2.5;
      state.temperature_c = 41.5;
      state.counter = 777;
      const std::optional<Reply> reply = decode_reply(encode_reply(state, width, kCanFd), kMaxMotorId, kCanFd);
      ASSERT_TRUE(reply.has_value());
      EXPECT_EQ(reply->state.motor, 9);
      EXPECT_EQ(reply->state.query, query);
      EXPECT_EQ(reply->state.fault, 0x15);
      EXPECT_EQ(reply->state.mode, query == Query::kCompact ? 0 : 0x21);
      EXPECT_EQ(reply->state.counter.has_value(), query == Query::kCounter);
      EXPECT_EQ(reply->state.temperature_c.has_value(), query == Query::kStateTemperature);
      if (query == Query::kCounter) {
        EXPECT_EQ(reply->state.counter, std::optional<std::uint16_t>(777));
        continue;
      }
      if (query == Query::kStateTemperature) {
        EXPECT_AS_FLOAT_EQ(reply->state.temperature_c.value_or(0), 41.5);
      }
      expect_motion(reply->state, -1.25, 0.5, -2.5);
    }
  }
}

TEST(MotorReplies, CompactInt16FitsEightBytes) {
  MotorState state;
  state.motor = 1;
  state.query = Query::kCompact;
  EXPECT_EQ(encode_reply(state, Width::kInt16, kCanFd).length, 8U);
}

TEST(MotorReplies, NoQueryNoReply) {
  MotorState state;
  state.motor = 1;
  EXPECT_EQ(encode_reply(state, Width::kInt16, kCanFd).length, 0U);
}

TEST(MotorReplies, FirmwareVersion) {
  EXPECT_EQ(
      wire_of(encode_firmware_version({.motor = 2, .major = 0, .minor = 3, .patch = 3}, InfoKind::kFirmwareVersion)),
      (Wire{0x10200, {0x04, 0x03, 0x03, 0x00}}));
}

TEST(MotorReplies, ModelNameRoundTrips) {
  const CanMessage message = encode_model_name(4, "5047_36");
  EXPECT_EQ(wire_of(message), (Wire{0x10400, padded({0x07, 0x07, '5', '0', '4', '7', '_', '3', '6'}, 12)}));
  const std::optional<Reply> reply = decode_reply(message, kMaxMotorId, kCanFd);
  ASSERT_TRUE(reply.has_value());
  EXPECT_STREQ(reply->model.text.data(), "5047_36");
}

TEST(MotorReplies, LongModelNamesAreCutToFiftyNineCharacters) {
  const std::string name(80, 'x');
  const std::optional<Reply> reply = decode_reply(encode_model_name(1, name), kMaxMotorId, kCanFd);
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(std::string_view(reply->model.text.data()), std::string(59, 'x'));
}

TEST(MotorReplies, CommandResult) { EXPECT_EQ(wire_of(encode_command_result(1, 0x00)), (Wire{0x10100, {0x03, 0x00}})); }

// ---- Motor side: decode_request ----------------------------------------------------------------

TEST(Requests, EveryModeRoundTripsAtEveryWidth) {
  for (const Mode mode :
       {Mode::kStop, Mode::kBrake, Mode::kVoltage, Mode::kCurrent, Mode::kTorque, Mode::kVelocity, Mode::kPosition,
        Mode::kVelocityAcceleration, Mode::kPositionVelocityTorque, Mode::kPositionVelocityAcceleration, Mode::kMit}) {
    for (const Width width : {Width::kInt16, Width::kInt32, Width::kFloat}) {
      SCOPED_TRACE(::testing::Message() << "mode " << mode_text(static_cast<std::uint8_t>(mode)) << " width "
                                        << static_cast<int>(width));
      MotorCommand command = mit(rev(0.25), rev(-0.5), 1.5, gain(20), gain(2));
      command.mode = mode;
      command.acceleration_rad_s2 = rev(2.0);
      command.voltage_q_v = 1.5;
      command.current_q_a = -2.5;
      const std::vector<MotorRequest> requests =
          requests_of(encode_command(12, command, width, Query::kStateTemperature, kCanFd));
      ASSERT_EQ(requests.size(), 1U);
      const MotorRequest& request = requests[0];
      EXPECT_EQ(request.kind, MotorRequest::Kind::kCommand);
      EXPECT_EQ(request.motor, 12);
      EXPECT_EQ(request.width, width);
      EXPECT_EQ(request.query, Query::kStateTemperature);
      EXPECT_EQ(request.command.mode, mode);
      const bool moves = mode != Mode::kStop && mode != Mode::kBrake && mode != Mode::kVoltage &&
                         mode != Mode::kCurrent && mode != Mode::kTorque;
      const bool positions = mode == Mode::kPosition || mode == Mode::kPositionVelocityTorque ||
                             mode == Mode::kPositionVelocityAcceleration || mode == Mode::kMit;
      EXPECT_EQ(request.has_position, positions);
      EXPECT_EQ(request.has_velocity, moves && mode != Mode::kPosition);
      EXPECT_EQ(request.has_kp, mode == Mode::kMit);
      if (positions) {
        EXPECT_AS_FLOAT_EQ(request.command.position_rad, rev(0.25));
      }
      if (request.has_velocity) {
        EXPECT_AS_FLOAT_EQ(request.command.velocity_rad_s, rev(-0.5));
      }
      if (request.has_torque) {
        EXPECT_AS_FLOAT_EQ(request.command.torque_nm, 1.5);
      }
      if (request.has_kp) {
        EXPECT_AS_FLOAT_EQ(request.command.kp, gain(20));
      }
      if (request.has_kd) {
        EXPECT_AS_FLOAT_EQ(request.command.kd, gain(2));
      }
      if (mode == Mode::kVoltage) {
        EXPECT_AS_FLOAT_EQ(request.command.voltage_q_v, 1.5);
      }
      if (mode == Mode::kCurrent) {
        EXPECT_AS_FLOAT_EQ(request.command.current_q_a, -2.5);
      }
      if (mode == Mode::kVelocityAcceleration) {
        EXPECT_AS_FLOAT_EQ(request.command.acceleration_rad_s2, rev(2.0));
      }
    }
  }
}

TEST(Requests, QueryOnly) {
  const std::vector<MotorRequest> requests = requests_of(encode_query(5, Query::kCompact, Width::kInt32));
  ASSERT_EQ(requests.size(), 1U);
  EXPECT_EQ(requests[0].kind, MotorRequest::Kind::kQuery);
  EXPECT_EQ(requests[0].motor, 5);
  EXPECT_EQ(requests[0].query, Query::kCompact);
  EXPECT_EQ(requests[0].width, Width::kInt32);
}

TEST(Requests, SystemCommandsRoundTrip) {
  const auto single = [](const CanMessage& message) {
    const std::vector<MotorRequest> requests = requests_of(message);
    EXPECT_EQ(requests.size(), 1U);
    return requests.empty() ? MotorRequest{} : requests[0];
  };
  EXPECT_EQ(single(encode_soft_reboot(1)).kind, MotorRequest::Kind::kSoftReboot);
  EXPECT_EQ(single(encode_save_to_flash(1)).kind, MotorRequest::Kind::kSaveToFlash);
  EXPECT_EQ(single(encode_set_zero(1)).kind, MotorRequest::Kind::kSetZero);
  const MotorRequest change = single(encode_change_id(1, 9).value());
  EXPECT_EQ(change.kind, MotorRequest::Kind::kChangeId);
  EXPECT_EQ(change.new_id, 9);
  const MotorRequest timeout = single(encode_command_timeout(1, 500));
  EXPECT_EQ(timeout.kind, MotorRequest::Kind::kCommandTimeout);
  EXPECT_EQ(timeout.timeout_ms, 500);
  const MotorRequest push = single(encode_status_push(1, Query::kCompact, 250));
  EXPECT_EQ(push.kind, MotorRequest::Kind::kStatusPush);
  EXPECT_EQ(push.query, Query::kCompact);
  EXPECT_EQ(push.period_us, 250U);
  const MotorRequest info = single(encode_info_request(1, InfoKind::kModel));
  EXPECT_EQ(info.kind, MotorRequest::Kind::kInfo);
  EXPECT_EQ(info.info, InfoKind::kModel);
}

TEST(Requests, BlockYieldsOneRequestPerCommandedMotor) {
  const std::vector<CanMessage> frames =
      blocks_of({{2, mit(rev(1.0), 0, 0, gain(20), gain(2))}, {4, mit(rev(0.5), rev(0.25), -1.0, gain(10), gain(1))}},
                Query::kCompact);
  ASSERT_EQ(frames.size(), 1U);
  const std::vector<MotorRequest> requests = requests_of(frames[0]);
  ASSERT_EQ(requests.size(), 2U);
  EXPECT_EQ(requests[0].motor, 2);
  EXPECT_EQ(requests[1].motor, 4);
  EXPECT_EQ(requests[1].kind, MotorRequest::Kind::kCommand);
  EXPECT_EQ(requests[1].command.mode, Mode::kMit);
  EXPECT_EQ(requests[1].query, Query::kCompact);
  EXPECT_EQ(requests[1].width, Width::kInt16);
  EXPECT_AS_FLOAT_EQ(requests[1].command.position_rad, rev(0.5));
  EXPECT_AS_FLOAT_EQ(requests[1].command.velocity_rad_s, rev(0.25));
  EXPECT_AS_FLOAT_EQ(requests[1].command.torque_nm, -1.0);
  EXPECT_AS_FLOAT_EQ(requests[1].command.kd, gain(1));
}

TEST(Requests, BlockInLaterFramesNamesMotorsFromTheFrameIndex) {
  const std::vector<CanMessage> frames = blocks_of({{8, velocity(rev(0.5))}});
  ASSERT_EQ(frames.size(), 1U);
  EXPECT_EQ(frames[0].id, 0x18081U);  // 2-byte modes carry 30 motors in one frame
  const std::vector<CanMessage> mit_frames = blocks_of({{29, mit(0, 0, 0, 0, 0)}});
  ASSERT_EQ(mit_frames.size(), 5U);  // motors 1–29, six a frame
  const std::vector<MotorRequest> requests = requests_of(mit_frames[4]);
  ASSERT_EQ(requests.size(), 1U);
  EXPECT_EQ(requests[0].motor, 29);
}

TEST(Requests, BlockSlotWithSomeUnsetFieldsFlagsThem) {
  // Block 0x92 (pos, vel, τ) for motor 1: position unset, velocity 400, torque 100.
  const std::vector<MotorRequest> requests =
      requests_of(fd_message(0x18092, {0x00, 0x80, 0x90, 0x01, 0x64, 0x00, 0x0B}));
  ASSERT_EQ(requests.size(), 1U);
  EXPECT_FALSE(requests[0].has_position);
  EXPECT_TRUE(requests[0].has_velocity);
  EXPECT_TRUE(requests[0].has_torque);
  EXPECT_AS_FLOAT_EQ(requests[0].command.torque_nm, 1.0);
}

TEST(Requests, StopBlockFlagsOnlyTheNamedMotors) {
  const std::vector<MotorRequest> requests = requests_of(fd_message(0x18085, {0x01, 0x00, 0x01, 0x0B}));
  ASSERT_EQ(requests.size(), 2U);
  EXPECT_EQ(requests[0].motor, 1);
  EXPECT_EQ(requests[1].motor, 3);
  EXPECT_EQ(requests[1].command.mode, Mode::kStop);
}

TEST(Requests, RezeroBlockYieldsSetZero) {
  const std::vector<MotorRequest> requests = requests_of(fd_message(0x18088, {0x00, 0x01, 0x0B}));
  ASSERT_EQ(requests.size(), 1U);
  EXPECT_EQ(requests[0].kind, MotorRequest::Kind::kSetZero);
  EXPECT_EQ(requests[0].motor, 2);
}

TEST(Requests, StopsWhenOutIsFull) {
  std::array<MotorRequest, 1> out{};
  EXPECT_EQ(decode_request(fd_message(0x18085, {0x01, 0x01, 0x01, 0x0B}), kCanFd, out), 1U);
}

TEST(Requests, RejectReplyIds) { EXPECT_TRUE(requests_of(fd_message(0x10100, {0x1C, 0x0B, 0x90, 0x01})).empty()); }

TEST(Requests, RejectTypeZero) { EXPECT_TRUE(requests_of(fd_message(0x08001, {0x1C, 0x0B, 0x90, 0x01})).empty()); }

TEST(Requests, RejectMotorZero) { EXPECT_TRUE(requests_of(fd_message(0x18000, {0x1C, 0x0B, 0x90, 0x01})).empty()); }

TEST(Requests, RejectEmptyFrames) { EXPECT_TRUE(requests_of(fd_message(0x18001, {})).empty()); }

TEST(Requests, RejectUnknownModes) { EXPECT_TRUE(requests_of(fd_message(0x18001, {0x22, 0x0B, 0x00, 0x00})).empty()); }

TEST(Requests, RejectUnknownQueries) {
  EXPECT_TRUE(requests_of(fd_message(0x18001, {0x1C, 0x0D, 0x90, 0x01})).empty());
  EXPECT_TRUE(requests_of(fd_message(0x18081, {0x90, 0x01, 0x0D})).empty());
}

TEST(Requests, RejectTruncatedPayloads) {
  EXPECT_TRUE(requests_of(fd_message(0x18001, {0x21, 0x0B, 0, 0, 0, 0, 0, 0, 0, 0, 0})).empty());
  EXPECT_TRUE(requests_of(fd_message(0x18001, {0x03, 0x00, 0x05, 0x0B, 0xE8})).empty());
}

TEST(Requests, RejectUnknownBlockCodesAndWideBlocks) {
  EXPECT_TRUE(requests_of(fd_message(0x18089, {0x01, 0x0B})).empty());
  EXPECT_TRUE(requests_of(fd_message(0x28081, {0x90, 0x01, 0x0B})).empty());
}

// ---- Texts ----------------------------------------------------------------------------------------

TEST(Texts, KnownFaults) {
  EXPECT_STREQ(fault_text(0x00), "ok");
  EXPECT_STREQ(fault_text(0x15), "communication timeout");
  EXPECT_STREQ(fault_text(0x12), "under-voltage");
}

TEST(Texts, UnknownFaultsNameTheirCodeFromStaticStorage) {
  EXPECT_STREQ(fault_text(0x42), "unknown fault 0x42");
  EXPECT_STREQ(fault_text(0xFF), "unknown fault 0xFF");
  EXPECT_EQ(fault_text(0x42), fault_text(0x42));
}

TEST(Texts, Modes) {
  EXPECT_STREQ(mode_text(0x21), "mit");
  EXPECT_STREQ(mode_text(0x01), "stop");
  EXPECT_STREQ(mode_text(0x02), "unknown");
}

// ---- USB-CDC board: CRCs and framing -------------------------------------------------------------

// The CRC catalogue's check input.
constexpr std::array<std::uint8_t, 9> kCheckInput{'1', '2', '3', '4', '5', '6', '7', '8', '9'};

TEST(BoardCrc, Crc8MaximFromFFCheckValue) { EXPECT_EQ(board_crc8(kCheckInput), 0x0B); }

TEST(BoardCrc, Crc16Mcrf4xxCheckValue) { EXPECT_EQ(board_crc16(kCheckInput), 0x6F91); }

Bytes board_packet(BoardCommand command, const Bytes& payload) {
  Bytes out(kBoardHeaderSize + payload.size());
  out.resize(encode_board_frame(command, payload, out));
  return out;
}

TEST(BoardFrames, HeaderCrc8Crc16ThenPayload) {
  EXPECT_EQ(board_packet(BoardCommand::kMotorState, {0x7F}), (Bytes{0xF7, 0x06, 0x01, 0x00, 0xC7, 0xF7, 0x84, 0x7F}));
}

TEST(BoardFrames, RejectOversizePayloadAndShortOutput) {
  const Bytes big(kMaxBoardPayload + 1, 0);
  Bytes out(big.size() + kBoardHeaderSize);
  EXPECT_EQ(encode_board_frame(BoardCommand::kPosition, big, out), 0U);
  Bytes small(4);
  EXPECT_EQ(encode_board_frame(BoardCommand::kStop, Bytes{0x7F}, small), 0U);
}

/// Feeds `stream` in pieces of `chunk` bytes and collects every packet.
std::vector<BoardFrame> split(BoardFrameSplitter& splitter, const Bytes& stream, std::size_t chunk) {
  std::vector<BoardFrame> frames;
  std::span<const std::uint8_t> rest(stream);
  while (!rest.empty()) {
    auto piece = rest.first(std::min(chunk, rest.size()));
    rest = rest.subspan(piece.size());
    while (!piece.empty()) {
      piece = piece.subspan(splitter.feed(piece));
      BoardFrame frame;
      while (splitter.next(frame)) frames.push_back(frame);
    }
  }
  return frames;
}

Bytes concat(std::initializer_list<Bytes> parts) {
  Bytes out;
  for (const Bytes& part : parts) out.insert(out.end(), part.begin(), part.end());
  return out;
}

Bytes payload_of(const BoardFrame& frame) { return {frame.bytes().begin(), frame.bytes().end()}; }

TEST(BoardSplitter, WholePacket) {
  BoardFrameSplitter splitter;
  const std::vector<BoardFrame> frames = split(splitter, board_packet(BoardCommand::kMotorState2, {1, 2, 3}), 4096);
  ASSERT_EQ(frames.size(), 1U);
  EXPECT_EQ(frames[0].command, BoardCommand::kMotorState2);
  EXPECT_EQ(payload_of(frames[0]), (Bytes{1, 2, 3}));
  EXPECT_EQ(splitter.crc_errors(), 0U);
  EXPECT_EQ(splitter.skipped_bytes(), 0U);
}

TEST(BoardSplitter, ByteByByte) {
  BoardFrameSplitter splitter;
  const Bytes stream = concat({board_packet(BoardCommand::kVersion, {9}), board_packet(BoardCommand::kStop, {0x7F})});
  const std::vector<BoardFrame> frames = split(splitter, stream, 1);
  ASSERT_EQ(frames.size(), 2U);
  EXPECT_EQ(frames[0].command, BoardCommand::kVersion);
  EXPECT_EQ(frames[1].command, BoardCommand::kStop);
}

TEST(BoardSplitter, FeedStopsAtTheEndOfAPacket) {
  BoardFrameSplitter splitter;
  const Bytes first = board_packet(BoardCommand::kStop, {0x7F});
  const Bytes stream = concat({first, board_packet(BoardCommand::kBrake, {0x7F})});
  EXPECT_EQ(splitter.feed(stream), first.size());
  EXPECT_EQ(splitter.feed(stream), 0U);  // nothing more until the packet is taken
  BoardFrame frame;
  EXPECT_TRUE(splitter.next(frame));
  EXPECT_FALSE(splitter.next(frame));
}

/// Splits `noise` followed by a good packet in pieces of `chunk` bytes: only the good one comes out.
void expect_only_the_good_packet(BoardFrameSplitter& splitter, const Bytes& noise, std::size_t chunk) {
  const std::vector<BoardFrame> frames =
      split(splitter, concat({noise, board_packet(BoardCommand::kStop, {0x7F})}), chunk);
  ASSERT_EQ(frames.size(), 1U);
  EXPECT_EQ(frames[0].command, BoardCommand::kStop);
  EXPECT_EQ(payload_of(frames[0]), Bytes{0x7F});
}

TEST(BoardSplitter, SkipsGarbageBeforeTheHeader) {
  BoardFrameSplitter splitter;
  expect_only_the_good_packet(splitter, {0x00, 0x11, 0x22}, 2);
  EXPECT_EQ(splitter.skipped_bytes(), 3U);
}

TEST(BoardSplitter, DropsAndCountsABadCrc8) {
  BoardFrameSplitter splitter;
  Bytes bad = board_packet(BoardCommand::kBrake, {0x01});  // F7 04 01 00 88 0E 1E 01: one 0xF7 only
  bad[4] ^= 0x01U;
  expect_only_the_good_packet(splitter, bad, 3);
  EXPECT_EQ(splitter.crc_errors(), 1U);
  EXPECT_EQ(splitter.skipped_bytes(), bad.size());
}

TEST(BoardSplitter, DropsAndCountsABadCrc16) {
  BoardFrameSplitter splitter;
  Bytes bad = board_packet(BoardCommand::kMotorState2, {1, 2, 3, 4});
  bad.back() ^= 0x80U;
  expect_only_the_good_packet(splitter, bad, 64);
  EXPECT_EQ(splitter.crc_errors(), 1U);
}

TEST(BoardSplitter, OversizeLengthIsNotAPacketStart) {
  BoardFrameSplitter splitter;
  // A header with a valid CRC-8 but a length (0x0801) above kMaxBoardPayload.
  Bytes oversize{0xF7, 0x06, 0x01, 0x08, 0x00, 0x00, 0x00};
  oversize[4] = board_crc8(std::span(oversize).subspan(1, 3));
  expect_only_the_good_packet(splitter, oversize, 5);
  EXPECT_EQ(splitter.crc_errors(), 0U);
  EXPECT_EQ(splitter.skipped_bytes(), oversize.size());
}

TEST(BoardSplitter, FindsAPacketInsideTheBytesOfABrokenOne) {
  BoardFrameSplitter splitter;
  // A header announcing 20 bytes whose "payload" is really the next packet: the CRC-16 fails and
  // the splitter re-scans what it had buffered.
  const Bytes inner = board_packet(BoardCommand::kBrake, {0x7F});
  Bytes outer = board_packet(BoardCommand::kMotorState2, Bytes(20, 0));
  std::copy(inner.begin(), inner.end(), outer.begin() + kBoardHeaderSize);
  const std::vector<BoardFrame> frames = split(splitter, outer, 1024);
  ASSERT_EQ(frames.size(), 1U);
  EXPECT_EQ(frames[0].command, BoardCommand::kBrake);
  EXPECT_EQ(splitter.crc_errors(), 1U);
}

TEST(BoardSplitter, EmptyPayloadIsAPacket) {
  BoardFrameSplitter splitter;
  const std::vector<BoardFrame> frames = split(splitter, board_packet(BoardCommand::kReboot, {}), 1);
  ASSERT_EQ(frames.size(), 1U);
  EXPECT_EQ(frames[0].length, 0U);
}

// ---- USB-CDC board: slots and states -------------------------------------------------------------

// The 5047_36 per the SDK's motor.cc: 0.004938 N·m per LSB, offset −0.03313 N·m, k_pid 0.4938.
const MotorScaling k5047{.torque_per_unit = 0.004938, .torque_offset_nm = -0.03313, .gain_factor = 0.4938};
const std::array<MotorScaling, 5> kBoardScaling{MotorScaling{}, k5047, k5047, k5047, k5047};  // ids 1–4

/// One update of a fresh port whose highest motor id is the highest of `slots`.
Bytes board_slots(BoardCommand command, const std::vector<BlockSlot>& slots) {
  int highest = 0;
  for (const BlockSlot& slot : slots) highest = std::max(highest, slot.motor);
  BoardSlotBuffer buffer(highest);
  const std::span<const std::uint8_t> payload = buffer.update(command, slots, kBoardScaling);
  return {payload.begin(), payload.end()};
}

TEST(BoardSlots, KpTenOnA5047_36IsAbout1272) {
  // The figure: 10 / 0.4938 × 10 × 2π = 1272.4 (with the old gain_factor 0.004938: 32700).
  const Bytes slots = board_slots(BoardCommand::kPositionVelocityTorqueKpKd, {{1, mit(0, 0, 0, 10.0, 0.7)}});
  ASSERT_EQ(slots.size(), 10U);
  EXPECT_EQ(slots[6] | (slots[7] << 8), 1272);
  EXPECT_EQ(slots[8] | (slots[9] << 8), 89);  // 0.7 / 0.4938 × 10 × 2π = 89.07
}

TEST(BoardSlots, MotorsNotCommandedKeepTheirLastValuesUntilTheModeChanges) {
  BoardSlotBuffer buffer(3);
  const std::vector<BlockSlot> all{
      {1, mit(0, 0, 0, 1.0, 0.1)}, {2, mit(0, 0, 0, 2.0, 0.2)}, {3, mit(0, 0, 0, 3.0, 0.3)}};
  const std::span<const std::uint8_t> first =
      buffer.update(BoardCommand::kPositionVelocityTorqueKpKd, all, kBoardScaling);
  const Bytes before(first.begin(), first.end());
  const std::vector<BlockSlot> only_two{{2, mit(rev(0.25), 0, 0, 5.0, 0.5)}};
  const std::span<const std::uint8_t> second =
      buffer.update(BoardCommand::kPositionVelocityTorqueKpKd, only_two, kBoardScaling);
  ASSERT_EQ(second.size(), 30U);
  EXPECT_EQ(Bytes(second.begin(), second.begin() + 10), Bytes(before.begin(), before.begin() + 10));  // motor 1
  EXPECT_EQ(Bytes(second.begin() + 20, second.end()), Bytes(before.begin() + 20, before.end()));      // motor 3
  EXPECT_EQ(second[10] | (second[11] << 8), 2500);                                                    // motor 2
  // Another command resets every slot: position unset, the rest 0.
  const std::span<const std::uint8_t> torque = buffer.update(BoardCommand::kTorque, {}, kBoardScaling);
  EXPECT_EQ(Bytes(torque.begin(), torque.end()), Bytes(6, 0));
  const std::span<const std::uint8_t> back =
      buffer.update(BoardCommand::kPositionVelocityTorqueKpKd, {}, kBoardScaling);
  EXPECT_EQ(back[0] | (back[1] << 8), 0x8000);
  buffer.reset();
  const std::vector<BlockSlot> beyond{{4, mit(0, 0, 0, 0, 0)}};  // the port's motors are 1–3
  EXPECT_TRUE(buffer.update(BoardCommand::kPositionVelocityTorqueKpKd, beyond, kBoardScaling).empty());
}

TEST(BoardSlots, The0x93FormHasTheSameSlotsAs0xB0) {
  const std::vector<BlockSlot> slots{{2, mit(rev(0.25), rev(0.5), 1.0, 1.0, 0.1)}};
  EXPECT_EQ(board_slots(BoardCommand::kPositionVelocityTorqueKpKdV1, slots),
            board_slots(BoardCommand::kPositionVelocityTorqueKpKd, slots));
}

TEST(BoardPackets, AdminAndTimeoutPacketsAsTheSdkSendsThem) {
  // Recorded from the SDK's canport.cc (tests/conformance/hightorque/board_admin_packets.jsonl).
  Bytes packet(64);
  packet.resize(encode_board_admin(BoardCommand::kStop, kBroadcastId, packet));
  EXPECT_EQ(packet, (Bytes{0xF7, 0x03, 0x01, 0x00, 0xF2, 0xF7, 0x84, 0x7F}));
  packet.resize(64);
  packet.resize(encode_board_timeout(200, 3, packet));
  EXPECT_EQ(packet, (Bytes{0xF7, 0x85, 0x06, 0x00, 0x2F, 0x30, 0xF4, 0xC8, 0x00, 0xC8, 0x00, 0xC8, 0x00}));
  EXPECT_EQ(encode_board_timeout(200, 31, packet), 0U);
}

TEST(BoardSlots, MitV2SlotsInIdOrderWithUnsetPositions) {
  // Motor 2: 0.25 rev → 2500, 0.5 rev/s → 2000, (1 + 0.03313)/0.004938 = 209.2 → 209,
  // kp 1 N·m/rad · 2π / 0.4938 · 10 = 127.2 → 127, kd 0.1 → 12.7 → 12. Motor 1 is unset.
  EXPECT_EQ(board_slots(BoardCommand::kPositionVelocityTorqueKpKd, {{2, mit(rev(0.25), rev(0.5), 1.0, 1.0, 0.1)}}),
            (Bytes{0x00, 0x80, 0, 0, 0, 0, 0, 0, 0, 0, 0xC4, 0x09, 0xD0, 0x07, 0xD1, 0x00, 0x7F, 0x00, 0x0C, 0x00}));
}

TEST(BoardSlots, GainsSaturateAt32700) {
  const Bytes slots = board_slots(BoardCommand::kPositionVelocityTorqueKpKd, {{1, mit(0, 0, 0, 1000.0, -1000.0)}});
  ASSERT_EQ(slots.size(), 10U);
  EXPECT_EQ(Bytes(slots.begin() + 6, slots.end()), (Bytes{0xBC, 0x7F, 0x44, 0x80}));
}

TEST(BoardSlots, PositionVelocityTorqueMaxIsThreeValues) {
  MotorCommand command;
  command.position_rad = rev(0.25);
  command.velocity_rad_s = rev(0.5);
  command.torque_nm = 1.0;
  EXPECT_EQ(board_slots(BoardCommand::kPositionVelocityTorqueMax, {{1, command}}),
            (Bytes{0xC4, 0x09, 0xD0, 0x07, 0xD1, 0x00}));
}

TEST(BoardSlots, RejectMotorsWithoutScalingAndNonSlotCommands) {
  EXPECT_TRUE(board_slots(BoardCommand::kPosition, {{5, velocity(0)}}).empty());
  EXPECT_TRUE(board_slots(BoardCommand::kPosition, {{0, velocity(0)}}).empty());
  EXPECT_TRUE(board_slots(BoardCommand::kMotorState, {{1, velocity(0)}}).empty());
}

TEST(BoardSlots, RoundTripThroughTheBoardSide) {
  const Bytes payload =
      board_slots(BoardCommand::kPositionVelocityTorqueKpKd, {{3, mit(rev(0.25), rev(-0.5), 1.0, 1.0, 0.1)}});
  std::array<MotorRequest, 8> out{};
  ASSERT_EQ(decode_board_slots(BoardCommand::kPositionVelocityTorqueKpKd, payload, kBoardScaling, out), 3U);
  EXPECT_EQ(out[0].motor, 1);
  EXPECT_FALSE(out[0].has_position);  // an unset slot: the board's 0x8000
  EXPECT_TRUE(out[0].has_kp);
  const MotorRequest& third = out[2];
  EXPECT_EQ(third.motor, 3);
  EXPECT_EQ(third.command.mode, Mode::kMit);
  EXPECT_AS_FLOAT_EQ(third.command.position_rad, rev(0.25));
  EXPECT_AS_FLOAT_EQ(third.command.velocity_rad_s, rev(-0.5));
  EXPECT_NEAR(third.command.torque_nm, 1.0, 0.004938);  // within one LSB (truncated)
  EXPECT_NEAR(third.command.kp, 1.0, 0.4938 / kTwoPi / 10);
  EXPECT_NEAR(third.command.kd, 0.1, 0.4938 / kTwoPi / 10);
}

TEST(BoardStates, State2RecordRoundTrips) {
  const std::array<BoardMotorState, 2> states{
      BoardMotorState{.motor = 2,
                      .mode = 0x21,
                      .fault = 0x15,
                      .position_rad = rev(0.25),
                      .velocity_rad_s = rev(-0.1),
                      .torque_nm = 0.999},
      BoardMotorState{.motor = 4, .mode = 0x01, .fault = 0, .position_rad = 0, .velocity_rad_s = 0, .torque_nm = 0}};
  Bytes payload(64);
  payload.resize(encode_board_states(BoardCommand::kMotorState2, states, kBoardScaling, payload));
  ASSERT_EQ(payload.size(), 2 * kBoardStateRecordSize);
  EXPECT_EQ(Bytes(payload.begin(), payload.begin() + 9), (Bytes{0x02, 0x21, 0x15, 0xC4, 0x09, 0x70, 0xFE, 0xD1, 0x00}));
  std::array<BoardMotorState, 4> out{};
  ASSERT_EQ(decode_board_states(BoardCommand::kMotorState2, payload, kBoardScaling, out), 2U);
  EXPECT_EQ(out[0].motor, 2);
  EXPECT_EQ(out[0].mode, 0x21);
  EXPECT_EQ(out[0].fault, 0x15);
  EXPECT_AS_FLOAT_EQ(out[0].position_rad, rev(0.25));
  EXPECT_AS_FLOAT_EQ(out[0].velocity_rad_s, rev(-0.1));
  EXPECT_NEAR(out[0].torque_nm, 0.998912, 1e-6);
  EXPECT_EQ(out[1].motor, 4);
}

TEST(BoardStates, ShortRecordsHaveNoModeOrFault) {
  const Bytes payload{0x01, 0xC4, 0x09, 0x90, 0x01, 0xD1, 0x00};
  std::array<BoardMotorState, 2> out{};
  ASSERT_EQ(decode_board_states(BoardCommand::kMotorState, payload, kBoardScaling, out), 1U);
  EXPECT_EQ(out[0].mode, 0);
  EXPECT_AS_FLOAT_EQ(out[0].velocity_rad_s, rev(0.1));
  EXPECT_NEAR(out[0].torque_nm, 209 * 0.004938 - 0.03313, 1e-6);
}

TEST(BoardStates, StopAtATruncatedRecordAndSkipUnknownMotors) {
  const Bytes payload{0x09, 0, 0, 0, 0, 0, 0, 0, 0,  // motor 9: no scaling
                      0x01, 0, 0, 0, 0, 0, 0, 0, 0,  // motor 1
                      0x02, 0, 0};                   // truncated
  std::array<BoardMotorState, 4> out{};
  ASSERT_EQ(decode_board_states(BoardCommand::kMotorState2, payload, kBoardScaling, out), 1U);
  EXPECT_EQ(out[0].motor, 1);
  EXPECT_EQ(decode_board_states(BoardCommand::kPosition, payload, kBoardScaling, out), 0U);
}

TEST(BoardVersions, OneRecordPerMotorRoundTrips) {
  const std::array<FirmwareVersion, 2> versions{
      {{.motor = 1, .major = 0, .minor = 3, .patch = 3}, {.motor = 7, .major = 2, .minor = 10, .patch = 255}}};
  std::array<std::uint8_t, 16> payload{};
  ASSERT_EQ(encode_board_versions(versions, payload), 8U);
  EXPECT_EQ(Bytes(payload.begin(), payload.begin() + 8), (Bytes{0x01, 0, 3, 3, 0x07, 2, 10, 255}));
  std::array<FirmwareVersion, 4> out{};
  ASSERT_EQ(decode_board_versions(std::span(payload).first(8), out), 2U);
  EXPECT_EQ(out[1].motor, 7);
  EXPECT_EQ(out[1].minor, 10);
  EXPECT_EQ(out[1].patch, 255);
}

TEST(BoardVersions, TruncatedRecordsMotorZeroAndOverflowAreNotDecoded) {
  const Bytes payload{0x00, 1, 1, 1, 0x02, 0, 3, 3, 0x03, 0};  // motor 0, motor 2, truncated
  std::array<FirmwareVersion, 4> out{};
  ASSERT_EQ(decode_board_versions(payload, out), 1U);
  EXPECT_EQ(out[0].motor, 2);
  std::array<FirmwareVersion, 0> none{};
  EXPECT_EQ(decode_board_versions(payload, none), 0U);
  std::array<std::uint8_t, 8> room{};
  EXPECT_EQ(encode_board_versions(std::array<FirmwareVersion, 1>{{{.motor = 256}}}, room), 0U);
  EXPECT_EQ(encode_board_versions(std::array<FirmwareVersion, 3>{}, room), 0U) << "12 bytes do not fit 8";
}

// ---- Robustness --------------------------------------------------------------------------------

// The SDK's motor_version_detection(): the lowest motor firmware picks the board's function version.
TEST(BoardStartUp, FunctionVersionFollowsTheLowestMotorFirmware) {
  const auto function = [](int major, int minor, int patch) {
    return board_function_for(FirmwareVersion{.motor = 1, .major = major, .minor = minor, .patch = patch});
  };
  EXPECT_EQ(function(4, 4, 6), BoardFunction::kV5);
  EXPECT_EQ(function(5, 0, 0), BoardFunction::kV5);
  EXPECT_EQ(function(4, 4, 5), BoardFunction::kV4);
  EXPECT_EQ(function(4, 2, 3), BoardFunction::kV4);
  EXPECT_EQ(function(4, 2, 2), BoardFunction::kV3);
  EXPECT_EQ(function(4, 2, 0), BoardFunction::kV2);
  EXPECT_EQ(function(4, 1, 9), BoardFunction::kV1);
  EXPECT_EQ(function(0, 3, 3), BoardFunction::kV1);
}

TEST(BoardStartUp, BoardFirmwareRoundTripsAndAShortAnswerIsNotOne) {
  std::array<std::uint8_t, 4> payload{};
  ASSERT_EQ(encode_board_firmware(BoardFirmware{.major = 4, .minor = 3}, payload), 4U);
  const std::optional<BoardFirmware> firmware = decode_board_firmware(payload);
  ASSERT_TRUE(firmware);
  EXPECT_EQ(firmware->tenths(), 43);
  EXPECT_FALSE(decode_board_firmware(std::span(payload).first(3)));
}

TEST(BlockSystem, RefusesNoMotorsAndMotorsOutsideTheBus) {
  std::array<transport::CanMessage, 1> out{};
  EXPECT_EQ(encode_block_system(BlockSystem::kSetZero, std::span<const int>{}, Query::kState, 7, out), 0U);
  EXPECT_EQ(encode_block_system(BlockSystem::kSetZero, std::array<int, 1>{8}, Query::kState, 7, out), 0U);
  EXPECT_EQ(encode_block_system(BlockSystem::kSetZero, std::array<int, 1>{0}, Query::kState, 7, out), 0U);
  EXPECT_EQ(encode_block_system(BlockSystem::kSoftReboot, std::array<int, 1>{1}, Query::kState, 31, out), 0U);
  ASSERT_EQ(encode_block_system(BlockSystem::kSoftReboot, std::array<int, 2>{1, 7}, Query::kState, 7, out), 1U);
  // The motor's side reads the same frame back as two reboots.
  std::array<MotorRequest, 8> requests{};
  ASSERT_EQ(decode_request(out[0], MotorScaling{}, requests), 2U);
  EXPECT_EQ(requests[0].kind, MotorRequest::Kind::kSoftReboot);
  EXPECT_EQ(requests[1].motor, 7);
}

TEST(Robustness, RandomFramesAndStreamsNeverBreakADecoder) {
  std::mt19937 random(20240611);  // a fixed seed: reproducible
  std::uniform_int_distribution<int> byte(0, 255);
  const std::array<std::uint32_t, 6> id_bases{0x10000, 0x20000, 0x30000, 0x18000, 0x28000, 0x38000};
  std::array<MotorRequest, 8> requests{};
  std::array<BoardMotorState, 8> states{};
  BoardFrameSplitter splitter;
  std::size_t replies = 0;
  for (int round = 0; round < 20000; ++round) {
    CanMessage message;
    const auto pick = static_cast<std::size_t>(byte(random)) % id_bases.size();
    message.id = id_bases[pick] | static_cast<std::uint32_t>(byte(random) << 8 | byte(random));
    message.extended = byte(random) != 0;
    message.length = static_cast<std::uint8_t>(byte(random) % 70);
    for (std::uint8_t& value : message.data) value = static_cast<std::uint8_t>(byte(random));
    if (decode_reply(message, kMaxMotorId, kCanFd)) ++replies;
    EXPECT_LE(decode_request(message, kCanFd, requests), requests.size());
    const auto payload = message.payload().first(std::min<std::size_t>(message.length, message.data.size()));
    EXPECT_LE(decode_board_states(BoardCommand::kMotorState2, payload, kBoardScaling, states), states.size());
    EXPECT_LE(decode_board_slots(BoardCommand::kPositionVelocityTorqueKpKd, payload, kBoardScaling, requests),
              requests.size());
    std::span<const std::uint8_t> rest = payload;
    while (!rest.empty()) {
      rest = rest.subspan(splitter.feed(rest));
      BoardFrame frame;
      while (splitter.next(frame)) EXPECT_LE(frame.length, kMaxBoardPayload);
    }
  }
  EXPECT_GT(replies, 0U);  // the generator does reach the decoders' accepting paths
}

TEST(Robustness, HotPathDoesNotAllocate) {
  const std::vector<BlockSlot> slots{{1, mit(0, 0, 0, 0, 0)}, {9, mit(0, 0, 0, 0, 0)}};
  const Bytes stream = board_packet(BoardCommand::kMotorState2, Bytes(18, 1));
  std::array<CanMessage, 5> frames{};
  BoardFrameSplitter splitter;
  BoardFrame frame;
  const std::size_t before = testing::allocations_on_this_thread();
  const CanMessage command = encode_command(1, mit(1, 2, 3, 4, 5), Width::kInt32, Query::kState, kCanFd);
  const std::size_t blocks = encode_block(slots, Query::kState, kCanFdById, 9, frames);
  MotorState state;
  state.motor = 1;
  state.query = Query::kStateTemperature;
  const std::optional<Reply> reply = decode_reply(encode_reply(state, Width::kInt16, kCanFd), kMaxMotorId, kCanFd);
  const std::size_t used = splitter.feed(stream);
  const bool ready = splitter.next(frame);
  const char* text = fault_text(0x99);
  EXPECT_EQ(testing::allocations_on_this_thread(), before);
  EXPECT_EQ(command.length, 24U);
  EXPECT_EQ(blocks, 2U);
  EXPECT_TRUE(reply.has_value());
  EXPECT_EQ(used, stream.size());
  EXPECT_TRUE(ready);
  EXPECT_STREQ(text, "unknown fault 0x99");
}

}  // namespace
}  // namespace robotd::hightorque
