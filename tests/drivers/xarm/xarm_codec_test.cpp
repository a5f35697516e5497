// The xArm codec against the protocol spec (../shared/protocols/xarm_tcp.md) and the vendor's API
// doc: the spec's byte examples, units and float rounding, both frame and report splitters, every
// request against the simulator's parser, the reply data, motion feedback, the three report
// layouts, the error and model tables, the argument checks, and truncated and random input fed to
// every decoder.
#include "codec/xarm_codec.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

namespace robotd::xarm {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRadPerDegree = kPi / 180.0;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

constexpr std::uint8_t reg_of(Register reg) { return static_cast<std::uint8_t>(reg); }

/// What a double becomes after a trip through the wire's float.
double as_float(double value) { return static_cast<double>(static_cast<float>(value)); }

Bytes f32_bytes(double value) { return ByteWriter().f32_le(value).take(); }

/// Expects `actual` to be `expected` within the precision of a float.
void expect_float_near(double actual, double expected) {
  EXPECT_NEAR(actual, expected, 1e-6 * std::max(1.0, std::abs(expected)));
}

void expect_pose_near(const Pose& actual, const Pose& expected) {
  for (std::size_t i = 0; i < 3; ++i) {
    expect_float_near(actual.position_m[i], expected.position_m[i]);
    expect_float_near(actual.rpy_rad[i], expected.rpy_rad[i]);
  }
}

void expect_joints_near(const JointValues& actual, const JointValues& expected) {
  for (std::size_t j = 0; j < kMaxDof; ++j) expect_float_near(actual[j], expected[j]);
}

/// Every frame the splitter has; fails the test on a framing error.
std::vector<Frame> drain(FrameSplitter& splitter) {
  std::vector<Frame> frames;
  while (true) {
    auto next = splitter.next();
    EXPECT_TRUE(next.ok()) << (next.ok() ? "" : next.error().message);
    if (!next.ok() || !next.value()) return frames;
    frames.push_back(*next.value());
  }
}

std::vector<Bytes> drain(ReportSplitter& splitter) {
  std::vector<Bytes> packets;
  while (true) {
    auto next = splitter.next();
    EXPECT_TRUE(next.ok()) << (next.ok() ? "" : next.error().message);
    if (!next.ok() || !next.value()) return packets;
    packets.push_back(*next.value());
  }
}

Frame request_frame(const Request& request, std::uint16_t transaction_id = 1) {
  return Frame{
      .transaction_id = transaction_id, .protocol = kProtocolPrivate, .reg = request.reg, .body = request.params};
}

Pose sample_pose() { return Pose{.position_m = {0.3, -0.1, 0.4}, .rpy_rad = {kPi, -0.25, 1.5}}; }

JointValues sample_joints() { return {0.1, -0.7, 1.2, -2.5, 3.0, -6.2, 0.0}; }

Report sample_report() {
  Report report;
  report.state = 1;
  report.mode = 1;
  report.cmd_num = 513;
  report.position_rad = {0.5, -1.0, 1.5, -2.0, 2.5, -3.0, 6.0};
  report.velocity_rad_s = {0.1, -0.2, 0.3, -0.4, 0.5, -0.6, 0.7};
  report.effort = {1.5, -22.25, 10.0, -3.0, 0.125, 0.0, -0.5};
  report.tcp_pose = sample_pose();
  report.error_code = 23;
  report.warning_code = 11;
  report.brake_mask = 0x3F;
  report.enable_mask = 0x1F;
  report.tcp_offset = Pose{.position_m = {0.01, -0.02, 0.125}, .rpy_rad = {0, 0, kPi / 2}};
  report.payload_kg = 1.5;
  report.payload_centre_m = {0, 0.01, 0.05};
  report.collision_sensitivity = 4;
  report.teach_sensitivity = 2;
  report.gravity_direction = {0, -0.5, -0.75};
  report.timestamp_us = 0x0102030405060708ULL;
  report.force_torque = {1.0, -2.0, 30.5, 0.25, -0.5, 0.75};
  report.target_position_rad = {0.25, -1.25, 1.5, -2.0, 2.5, -3.0, 6.25};
  report.target_velocity_rad_s = {1.0, -0.25, 0.3, -0.4, 0.5, -0.6, -3.0};
  return report;
}

std::string error_of(const Result<void>& result) { return result.ok() ? "" : result.error().message; }

template <class T>
std::string error_of(const Result<T>& result) {
  return result.ok() ? "" : result.error().message;
}

// ---- Wire primitives -----------------------------------------------------------------------

TEST(Wire, FloatsAreLittleEndianAsTheSpecExamples) {
  EXPECT_EQ(f32_bytes(400.0), (Bytes{0x00, 0x00, 0xC8, 0x43}));
  EXPECT_EQ(f32_bytes(kPi), (Bytes{0xDB, 0x0F, 0x49, 0x40}));
  EXPECT_EQ(f32_bytes(-1.5), (Bytes{0x00, 0x00, 0xC0, 0xBF}));
  EXPECT_EQ(f32_bytes(0.0), (Bytes{0x00, 0x00, 0x00, 0x00}));
}

TEST(Wire, IntegersAreBigEndian) {
  EXPECT_EQ(ByteWriter().u8(0xAB).u16_be(0x0102).u32_be(0x03040506).u64_be(0x0708090A0B0C0D0EULL).take(),
            (Bytes{0xAB, 0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07, 0x08, 0x09, 0x0A, 0x0B, 0x0C, 0x0D, 0x0E}));
}

TEST(Wire, FloatsRoundToTheNearestSingle) {
  EXPECT_EQ(f32_bytes(0.1), (Bytes{0xCD, 0xCC, 0xCC, 0x3D}));  // 0x3DCCCCCD, the nearest to 0.1
  EXPECT_EQ(f32_bytes(1.0 + 1e-9), f32_bytes(1.0));
  EXPECT_EQ(f32_bytes(-kPi), (Bytes{0xDB, 0x0F, 0x49, 0xC0}));
}

TEST(Wire, NanAndInfinityPassButFiniteValuesSaturate) {
  const Bytes nan_bytes = f32_bytes(kNaN);
  ByteReader nan_reader(nan_bytes);
  EXPECT_TRUE(std::isnan(nan_reader.f32_le().value_or(0)));
  EXPECT_EQ(f32_bytes(kInf), (Bytes{0x00, 0x00, 0x80, 0x7F}));
  EXPECT_EQ(f32_bytes(-kInf), (Bytes{0x00, 0x00, 0x80, 0xFF}));
  // Beyond float's range: FLT_MAX, not +inf (which newer firmware reads as "keep current").
  EXPECT_EQ(f32_bytes(1e300), (Bytes{0xFF, 0xFF, 0x7F, 0x7F}));
  EXPECT_EQ(f32_bytes(-1e300), (Bytes{0xFF, 0xFF, 0x7F, 0xFF}));
  EXPECT_EQ(f32_bytes(std::numeric_limits<double>::max()), (Bytes{0xFF, 0xFF, 0x7F, 0x7F}));
}

TEST(Wire, ReaderReadsInOrderAndConsumesNothingPastTheEnd) {
  const Bytes data{0x01, 0x02, 0x03, 0x00, 0x00, 0xC8, 0x43, 0x09};
  ByteReader reader(data);
  EXPECT_EQ(reader.u8(), 0x01);
  EXPECT_EQ(reader.u16_be(), 0x0203);
  EXPECT_EQ(reader.f32_le(), 400.0);
  EXPECT_EQ(reader.remaining(), 1U);
  EXPECT_EQ(reader.u16_be(), std::nullopt);
  EXPECT_EQ(reader.u32_be(), std::nullopt);
  EXPECT_EQ(reader.u64_be(), std::nullopt);
  EXPECT_EQ(reader.f32_le(), std::nullopt);
  EXPECT_EQ(reader.offset(), 7U);
  EXPECT_EQ(reader.u8(), 0x09);
  EXPECT_EQ(reader.u8(), std::nullopt);
  EXPECT_EQ(reader.remaining(), 0U);
}

TEST(Wire, ReaderReadsWideIntegersBigEndian) {
  const Bytes data{0xFF, 0xFE, 0xFD, 0xFC, 0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07, 0x08};
  ByteReader reader(data);
  EXPECT_EQ(reader.u32_be(), 0xFFFEFDFCU);
  EXPECT_EQ(reader.u64_be(), 0x0102030405060708ULL);
  ByteReader empty(ByteView{});
  EXPECT_EQ(empty.u8(), std::nullopt);
}

// ---- Registers -----------------------------------------------------------------------------

TEST(Registers, NamedAsTheSpecOrByNumber) {
  EXPECT_EQ(register_name(21), "move_line");
  EXPECT_EQ(register_name(15), "get_err_code");
  EXPECT_EQ(register_name(11), "motion_en");
  EXPECT_EQ(register_name(106), "servo_get_dbmsg");
  EXPECT_EQ(register_name(255), "motion_feedback");
  EXPECT_EQ(register_name(99), "register 99");
  EXPECT_EQ(register_name(0), "register 0");
}

TEST(Registers, MotionsQueuedMotionsAndSystemResets) {
  for (int reg = 0; reg < 256; ++reg) {
    const auto r = static_cast<std::uint8_t>(reg);
    EXPECT_EQ(is_motion_register(r), reg >= 21 && reg <= 30) << reg;
    EXPECT_EQ(is_queued_motion(r), reg >= 21 && reg <= 28) << reg;
    const bool resets = reg == 11 || reg == 16 || reg == 18 || reg == 19 || reg == 35 || reg == 37 || reg == 38;
    EXPECT_EQ(resets_system(r), resets) << reg;
  }
}

// ---- Framing -------------------------------------------------------------------------------

TEST(Framing, EnableAllJointsMatchesTheSpecExample) {
  const Request request = motion_enable_request(8, true);
  EXPECT_EQ(encode_frame(request_frame(request)), (Bytes{0x00, 0x01, 0x00, 0x02, 0x00, 0x03, 0x0B, 0x08, 0x01}));
}

TEST(Framing, TheSpecReplyExampleIsNotReady) {
  FrameSplitter splitter;
  splitter.append(Bytes{0x00, 0x01, 0x00, 0x02, 0x00, 0x02, 0x0B, 0x10});
  const auto frames = drain(splitter);
  ASSERT_EQ(frames.size(), 1U);
  const auto reply = parse_reply(frames[0]);
  ASSERT_TRUE(reply.ok()) << error_of(reply);
  EXPECT_EQ(reply.value().transaction_id, 1);
  EXPECT_EQ(reply.value().protocol, kProtocolPrivate);
  EXPECT_EQ(reply.value().reg, reg_of(Register::kMotionEnable));
  EXPECT_EQ(reply.value().status_byte, 0x10);
  EXPECT_TRUE(reply.value().status.not_ready);
  EXPECT_TRUE(reply.value().data.empty());
  // Not ready is information only for motion_en, a failure for a motion.
  EXPECT_EQ(execution_state(reply.value()), kExecOk);
  Reply motion = reply.value();
  motion.reg = reg_of(Register::kMoveJoint);
  EXPECT_EQ(execution_state(motion), kExecNotReady);
}

TEST(Framing, GetErrCodeReplyByteByByte) {
  // Error 23 and warning 11 active: status 0x60, data 17 0B; length = register + status + 2.
  const Bytes wire{0x00, 0x05, 0x00, 0x02, 0x00, 0x04, 0x0F, 0x60, 0x17, 0x0B};
  EXPECT_EQ(encode_frame(reply_frame(5, kProtocolPrivate, reg_of(Register::kGetErrCode), 0x60,
                                     encode_err_code({.error = 23, .warning = 11}))),
            wire);
  FrameSplitter splitter;
  splitter.append(wire);
  const auto frames = drain(splitter);
  ASSERT_EQ(frames.size(), 1U);
  const auto reply = parse_reply(frames[0]);
  ASSERT_TRUE(reply.ok());
  EXPECT_TRUE(reply.value().status.error);
  EXPECT_TRUE(reply.value().status.warning);
  EXPECT_EQ(execution_state(reply.value()), kExecErrorActive);
  EXPECT_TRUE(execution_succeeded(reply.value().reg, execution_state(reply.value())));
  const auto codes = parse_err_code(reply.value().data);
  ASSERT_TRUE(codes.ok());
  EXPECT_EQ(codes.value().error, 23);
  EXPECT_EQ(codes.value().warning, 11);
  EXPECT_EQ(controller_error_text(codes.value().error), "C23 joint angle exceeds limit");
  EXPECT_EQ(controller_warning_text(codes.value().warning), "W11 command cache full");
}

TEST(Framing, RequestsKeepTheirTransactionAndProtocol) {
  Frame frame = request_frame(plain_request(Register::kGetState), 0xFFFF);
  frame.protocol = kProtocolKeepAlive;
  EXPECT_EQ(encode_frame(frame), (Bytes{0xFF, 0xFF, 0x00, 0x03, 0x00, 0x01, 0x0D}));
}

TEST(FrameSplitter, JoinsAFrameSplitOverManyAppends) {
  const Bytes wire = encode_frame(request_frame(move_joint_request({}), 42));
  FrameSplitter splitter;
  for (std::size_t i = 0; i + 1 < wire.size(); ++i) {
    splitter.append(ByteView(wire).subspan(i, 1));
    const auto next = splitter.next();
    ASSERT_TRUE(next.ok());
    EXPECT_FALSE(next.value().has_value()) << "after byte " << i;
  }
  EXPECT_EQ(splitter.buffered(), wire.size() - 1);
  splitter.append(ByteView(wire).last(1));
  const auto frames = drain(splitter);
  ASSERT_EQ(frames.size(), 1U);
  EXPECT_EQ(frames[0].transaction_id, 42);
  EXPECT_EQ(frames[0].reg, reg_of(Register::kMoveJoint));
  EXPECT_EQ(frames[0].body.size(), 40U);
  EXPECT_EQ(splitter.buffered(), 0U);
}

TEST(FrameSplitter, CutsSeveralFramesInOneAppendAndKeepsTheRest) {
  Bytes stream = encode_frame(request_frame(plain_request(Register::kGetState), 1));
  const Bytes second = encode_frame(request_frame(set_mode_request(1), 2));
  const Bytes third = encode_frame(request_frame(sleep_instruction_request(1.5), 3));
  stream.insert(stream.end(), second.begin(), second.end());
  stream.insert(stream.end(), third.begin(), third.end() - 2);
  FrameSplitter splitter;
  splitter.append(stream);
  auto frames = drain(splitter);
  ASSERT_EQ(frames.size(), 2U);
  EXPECT_EQ(frames[0].transaction_id, 1);
  EXPECT_TRUE(frames[0].body.empty());
  EXPECT_EQ(frames[1].body, (Bytes{1}));
  EXPECT_EQ(splitter.buffered(), third.size() - 2);
  splitter.append(ByteView(third).last(2));
  frames = drain(splitter);
  ASSERT_EQ(frames.size(), 1U);
  EXPECT_EQ(frames[0].transaction_id, 3);
}

TEST(FrameSplitter, ReadsTheClientHeartbeat) {
  FrameSplitter splitter;
  splitter.append(Bytes{0x00, 0x00, 0x00, 0x01, 0x00, 0x02, 0x00, 0x00});
  const auto frames = drain(splitter);
  ASSERT_EQ(frames.size(), 1U);
  EXPECT_EQ(frames[0].protocol, 1);
  EXPECT_EQ(frames[0].reg, 0);
  EXPECT_EQ(frames[0].body, (Bytes{0}));
}

TEST(FrameSplitter, LengthZeroIsAStickyErrorUntilClear) {
  FrameSplitter splitter;
  splitter.append(Bytes{0x00, 0x01, 0x00, 0x02, 0x00, 0x00, 0x0B});
  auto next = splitter.next();
  ASSERT_FALSE(next.ok());
  EXPECT_EQ(next.error().code, ErrorCode::kInvalidArgument);
  EXPECT_EQ(next.error().message,
            "frame length field 0 is outside 1..2042: the command stream lost its framing (reconnect)");
  splitter.append(encode_frame(request_frame(plain_request(Register::kGetState))));
  EXPECT_FALSE(splitter.next().ok());
  EXPECT_FALSE(splitter.next().ok());
  splitter.clear();
  EXPECT_EQ(splitter.buffered(), 0U);
  splitter.append(encode_frame(request_frame(plain_request(Register::kGetState))));
  EXPECT_EQ(drain(splitter).size(), 1U);
}

TEST(FrameSplitter, RefusesALengthBeyondTheLimitButTakesOneAtIt) {
  FrameSplitter splitter;
  splitter.append(Bytes{0x00, 0x01, 0x00, 0x02, 0x07, 0xFB});  // 2043: one too many
  const auto next = splitter.next();
  ASSERT_FALSE(next.ok());
  EXPECT_NE(next.error().message.find("2043"), std::string::npos);

  splitter.clear();
  const Frame largest{.transaction_id = 9,
                      .protocol = kProtocolPrivate,
                      .reg = 1,
                      .body = Bytes(kMaxFrameBytes - kHeaderBytes - 1, 0xAA)};
  const Bytes wire = encode_frame(largest);
  EXPECT_EQ(wire.size(), kMaxFrameBytes);
  splitter.append(wire);
  const auto frames = drain(splitter);
  ASSERT_EQ(frames.size(), 1U);
  EXPECT_EQ(frames[0].body.size(), largest.body.size());
}

TEST(FrameSplitter, FFFFLengthIsRefusedBeforeBuffering) {
  FrameSplitter splitter;
  splitter.append(Bytes{0x12, 0x34, 0x00, 0x02, 0xFF, 0xFF});
  EXPECT_FALSE(splitter.next().ok());
  EXPECT_EQ(splitter.buffered(), 0U);
}

// ---- Status byte and execution states ------------------------------------------------------

TEST(Status, BitsOfTheSpec) {
  EXPECT_TRUE(decode_status(0x08).invalid);
  EXPECT_TRUE(decode_status(0x10).not_ready);
  EXPECT_TRUE(decode_status(0x20).warning);
  EXPECT_TRUE(decode_status(0x40).error);
  const StatusBits none = decode_status(0x87);  // reserved bits only
  EXPECT_FALSE(none.invalid || none.not_ready || none.warning || none.error);
  for (int byte = 0; byte < 256; ++byte) {
    const auto value = static_cast<std::uint8_t>(byte);
    EXPECT_EQ(encode_status(decode_status(value)), value & 0x78) << byte;
  }
  EXPECT_EQ(encode_status({.invalid = false, .not_ready = true, .warning = false, .error = true}), 0x50);
}

TEST(Status, ParseReplyRefusesNoStatusByteAndFeedbackFrames) {
  const auto empty = parse_reply(Frame{.transaction_id = 1, .protocol = 2, .reg = 13, .body = {}});
  ASSERT_FALSE(empty.ok());
  EXPECT_EQ(empty.error().message, "get_state reply has no status byte: length field 1, expected at least 2");
  const auto feedback = parse_reply(motion_feedback_frame({}));
  ASSERT_FALSE(feedback.ok());
  EXPECT_NE(feedback.error().message.find("motion feedback"), std::string::npos);
}

TEST(Status, ReplyFrameRoundTrip) {
  const Bytes data{0x00, 0x07};
  const Frame frame = reply_frame(300, kProtocolKeepAlive, reg_of(Register::kMoveLine), 0x20, data);
  EXPECT_EQ(encode_frame(frame), (Bytes{0x01, 0x2C, 0x00, 0x03, 0x00, 0x04, 0x15, 0x20, 0x00, 0x07}));
  const auto reply = parse_reply(frame);
  ASSERT_TRUE(reply.ok());
  EXPECT_EQ(reply.value().transaction_id, 300);
  EXPECT_EQ(reply.value().protocol, kProtocolKeepAlive);
  EXPECT_EQ(reply.value().data, data);
  EXPECT_EQ(parse_cmdnum(reply.value().data).value(), 7);
  EXPECT_EQ(execution_state(reply.value()), kExecWarningActive);
  EXPECT_TRUE(execution_succeeded(reply.value().reg, kExecWarningActive));
}

TEST(Status, ExecutionStateFollowsTheSdkOrder) {
  Reply reply;
  reply.reg = reg_of(Register::kMoveLine);
  const auto state_for = [&reply](std::uint8_t status) {
    reply.status_byte = status;
    reply.status = decode_status(status);
    return execution_state(reply);
  };
  EXPECT_EQ(state_for(0x00), kExecOk);
  EXPECT_EQ(state_for(0x78), kExecInvalidResult);
  EXPECT_EQ(state_for(0x70), kExecErrorActive);
  EXPECT_EQ(state_for(0x30), kExecWarningActive);
  EXPECT_EQ(state_for(0x10), kExecNotReady);
  EXPECT_EQ(state_for(0x87), kExecOk);
  reply.reg = reg_of(Register::kGetState);
  EXPECT_EQ(state_for(0x10), kExecOk);
  EXPECT_EQ(state_for(0x08), kExecInvalidResult);
}

TEST(Status, SuccessDependsOnTheRegister) {
  const auto servo_j = reg_of(Register::kServoJ);
  EXPECT_TRUE(execution_succeeded(servo_j, kExecOk));
  EXPECT_TRUE(execution_succeeded(servo_j, kExecWarningActive));
  EXPECT_FALSE(execution_succeeded(servo_j, kExecErrorActive));
  EXPECT_FALSE(execution_succeeded(servo_j, kExecNotReady));
  EXPECT_FALSE(execution_succeeded(servo_j, kExecInvalidResult));
  const auto get_state = reg_of(Register::kGetState);
  for (const int code : {kExecOk, kExecErrorActive, kExecWarningActive, kExecNotReady}) {
    EXPECT_TRUE(execution_succeeded(get_state, code)) << code;
  }
  for (const int code :
       std::to_array<int>({kExecTimeout, kExecLengthError, kExecInvalidResult, kExecOther, kExecParameterError, 42})) {
    EXPECT_FALSE(execution_succeeded(get_state, code)) << code;
  }
}

TEST(Status, ExecutionStateTexts) {
  EXPECT_EQ(execution_state_text(kExecOk), "normal");
  EXPECT_EQ(execution_state_text(kExecErrorActive), "xArm has an error code");
  EXPECT_EQ(execution_state_text(kExecWarningActive), "xArm has a warning code");
  EXPECT_EQ(execution_state_text(kExecTimeout), "communication timed out");
  EXPECT_EQ(execution_state_text(kExecLengthError), "instruction parsing error (length)");
  EXPECT_EQ(execution_state_text(kExecNotReady), "not ready to move (not enabled, stopped or reset)");
  EXPECT_EQ(execution_state_text(kExecParameterError), "parameter error");
  EXPECT_EQ(execution_state_text(130), "Modbus exception 2 (illegal data address)");
  EXPECT_EQ(execution_state_text(42), "unknown execution state 42");
  EXPECT_EQ(execution_state_text(-1), "unknown execution state -1");
  EXPECT_EQ(execution_state_text(128), "unknown execution state 128");
}

TEST(Status, MotionStateAndModeTexts) {
  EXPECT_EQ(motion_state_text(kStateMoving), "moving");
  EXPECT_EQ(motion_state_text(kStateSleeping), "sleeping");
  EXPECT_EQ(motion_state_text(kStatePaused), "paused");
  EXPECT_EQ(motion_state_text(kStateStopped), "stopped");
  EXPECT_EQ(motion_state_text(kStateReset), "system reset (set state 0 to continue)");
  EXPECT_EQ(motion_state_text(9), "unknown state 9");
  EXPECT_EQ(motion_state_text(-3), "unknown state -3");
  EXPECT_EQ(mode_text(kModePosition), "position");
  EXPECT_EQ(mode_text(kModeServo), "servo");
  EXPECT_EQ(mode_text(kModeJointTeach), "joint teaching");
  EXPECT_EQ(mode_text(kModeCartesianOnline), "Cartesian online planning");
  EXPECT_EQ(mode_text(12), "unknown mode 12");
}

// ---- Requests: bytes -----------------------------------------------------------------------

TEST(Requests, PlainRequestsHaveNoParameters) {
  for (const Register reg : {Register::kGetVersion, Register::kGetErrCode, Register::kCleanErr, Register::kGetTcpPose,
                             Register::kServoGetDbmsg, Register::kFeedbackCheck}) {
    const Request request = plain_request(reg);
    EXPECT_EQ(request.reg, reg_of(reg));
    EXPECT_TRUE(request.params.empty());
  }
}

TEST(Requests, SwitchesStateAndMode) {
  EXPECT_EQ(motion_enable_request(3, false).params, (Bytes{3, 0}));
  EXPECT_EQ(motion_enable_request(8, true).reg, 11);
  const Request release = set_brake_request(2, true);
  EXPECT_EQ(release.reg, 18);
  EXPECT_EQ(release.params, (Bytes{2, 1}));  // 1 = release (both SDKs)
  EXPECT_EQ(set_brake_request(8, false).params, (Bytes{8, 0}));
  EXPECT_EQ(set_state_request(kStateStopped).params, (Bytes{4}));
  EXPECT_EQ(set_state_request(kStateStopped).reg, 12);
  EXPECT_EQ(set_mode_request(kModeServo).params, (Bytes{1}));
  EXPECT_EQ(set_mode_request(kModeServo).reg, 19);
}

TEST(Requests, MoveLineSendsMillimetresInTheSeedsOrder) {
  const LineMove move{.pose = {.position_m = {0.3, -0.1, 0.4}, .rpy_rad = {kPi, 0, 0}},
                      .speed_m_s = 0.1,
                      .acc_m_s2 = 2.0,
                      .mvtime_s = 0,
                      .blend_radius_m = 0.005};
  const Request line = move_line_request(move);
  EXPECT_EQ(line.reg, 21);
  EXPECT_EQ(line.params, (Bytes{0x00, 0x00, 0x96, 0x43,     // x 300 mm
                                0x00, 0x00, 0xC8, 0xC2,     // y -100 mm
                                0x00, 0x00, 0xC8, 0x43,     // z 400 mm
                                0xDB, 0x0F, 0x49, 0x40,     // roll π
                                0x00, 0x00, 0x00, 0x00,     // pitch
                                0x00, 0x00, 0x00, 0x00,     // yaw
                                0x00, 0x00, 0xC8, 0x42,     // 100 mm/s
                                0x00, 0x00, 0xFA, 0x44,     // 2000 mm/s²
                                0x00, 0x00, 0x00, 0x00}));  // mvtime
  const Request lineb = move_lineb_request(move);
  EXPECT_EQ(lineb.reg, 22);
  ASSERT_EQ(lineb.params.size(), 40U);
  EXPECT_TRUE(std::equal(line.params.begin(), line.params.end(), lineb.params.begin()));
  EXPECT_EQ(ByteView(lineb.params).last(4)[2], 0xA0);  // radius 5 mm = 0x40A00000
  EXPECT_EQ(ByteView(lineb.params).last(4)[3], 0x40);
}

TEST(Requests, MetresBecomeMillimetresBeforeRoundingToFloat) {
  const Request offset = set_tcp_offset_request(Pose{.position_m = {0.5432109, 0, 0}, .rpy_rad = {}});
  const Bytes expected = f32_bytes(0.5432109 * 1000.0);
  EXPECT_TRUE(std::equal(expected.begin(), expected.end(), offset.params.begin()));
  EXPECT_NE(f32_bytes(as_float(0.5432109) * 1000.0), expected);                    // rounding first would differ
  EXPECT_EQ(set_tcp_jerk_request(10.0).params, (Bytes{0x00, 0x40, 0x1C, 0x46}));   // 10000 mm/s³
  EXPECT_EQ(set_tcp_maxacc_request(2.0).params, (Bytes{0x00, 0x00, 0xFA, 0x44}));  // 2000 mm/s²
}

TEST(Requests, JointValuesAndScalarsInRadiansAndSeconds) {
  JointMove move;
  move.joints_rad = {kPi / 2, 0, 0, 0, 0, 0, -kPi};
  move.speed_rad_s = kPi;
  const Request joint = move_joint_request(move);
  EXPECT_EQ(joint.reg, 23);
  ASSERT_EQ(joint.params.size(), 40U);
  EXPECT_EQ(Bytes(joint.params.begin(), joint.params.begin() + 4), (Bytes{0xDB, 0x0F, 0xC9, 0x3F}));
  EXPECT_EQ(Bytes(joint.params.begin() + 24, joint.params.begin() + 32),
            (Bytes{0xDB, 0x0F, 0x49, 0xC0, 0xDB, 0x0F, 0x49, 0x40}));  // j7 -π, speed π
  const Request home = move_gohome_request(move);
  EXPECT_EQ(home.reg, 25);
  EXPECT_EQ(home.params.size(), 12U);
  EXPECT_EQ(Bytes(home.params.begin(), home.params.begin() + 4), f32_bytes(kPi));
  EXPECT_EQ(sleep_instruction_request(400.0).params, (Bytes{0x00, 0x00, 0xC8, 0x43}));
  EXPECT_EQ(sleep_instruction_request(400.0).reg, 26);
  EXPECT_EQ(set_joint_jerk_request(kPi).params, f32_bytes(kPi));
  EXPECT_EQ(set_joint_jerk_request(kPi).reg, 33);
  EXPECT_EQ(set_joint_maxacc_request(-1.5).params, (Bytes{0x00, 0x00, 0xC0, 0xBF}));
  EXPECT_EQ(set_joint_maxacc_request(-1.5).reg, 34);
}

TEST(Requests, ServoJEndsWithThreeReservedZeros) {
  JointValues joints{};
  joints.fill(1.0);
  const Request servo = servo_j_request(joints);
  EXPECT_EQ(servo.reg, 29);
  ASSERT_EQ(servo.params.size(), 40U);
  EXPECT_EQ(Bytes(servo.params.begin() + 24, servo.params.begin() + 28), f32_bytes(1.0));
  EXPECT_EQ(Bytes(servo.params.begin() + 28, servo.params.end()), Bytes(12, 0));
}

TEST(Requests, QueriesWithJointArguments) {
  EXPECT_EQ(get_fk_request(sample_joints()).reg, 44);
  EXPECT_EQ(get_fk_request(sample_joints()).params.size(), 28U);
  EXPECT_EQ(is_joint_limit_request(sample_joints()).reg, 45);
  EXPECT_EQ(is_joint_limit_request(sample_joints()).params, encode_joints(sample_joints()));
  EXPECT_EQ(set_tcp_offset_request(sample_pose()).reg, 35);
  EXPECT_EQ(set_tcp_offset_request(sample_pose()).params, encode_pose(sample_pose()));
}

TEST(Requests, InfinityMeansKeepCurrentAndPassesThrough) {
  LineMove move;
  move.pose.rpy_rad = {kInf, kInf, 0};
  const auto parsed = parse_line_move(21, move_line_request(move).params);
  ASSERT_TRUE(parsed.ok());
  EXPECT_EQ(parsed.value().pose.rpy_rad[0], kInf);
  EXPECT_EQ(parsed.value().pose.rpy_rad[1], kInf);
}

// ---- Requests: the simulator's side --------------------------------------------------------

TEST(RequestRoundTrip, SwitchesStateAndMode) {
  const auto enable = parse_motion_enable(motion_enable_request(8, true).params);
  ASSERT_TRUE(enable.ok());
  EXPECT_EQ(enable.value().joint, 8);
  EXPECT_TRUE(enable.value().on);
  const auto disable = parse_motion_enable(motion_enable_request(5, false).params);
  ASSERT_TRUE(disable.ok());
  EXPECT_EQ(disable.value().joint, 5);
  EXPECT_FALSE(disable.value().on);
  const auto brake = parse_set_brake(set_brake_request(7, true).params);
  ASSERT_TRUE(brake.ok());
  EXPECT_EQ(brake.value().joint, 7);
  EXPECT_TRUE(brake.value().on);
  EXPECT_EQ(parse_u8_param(12, set_state_request(kStatePaused).params).value(), kStatePaused);
  EXPECT_EQ(parse_u8_param(19, set_mode_request(kModeJointVelocity).params).value(), kModeJointVelocity);
  EXPECT_EQ(parse_u8_param(19, Bytes{1, 1}).value(), 1);  // set_mode's detection byte is ignored
}

TEST(RequestRoundTrip, LineMoves) {
  const LineMove move{
      .pose = sample_pose(), .speed_m_s = 0.25, .acc_m_s2 = 3.5, .mvtime_s = 0.5, .blend_radius_m = 0.012};
  const auto line = parse_line_move(21, move_line_request(move).params);
  ASSERT_TRUE(line.ok()) << error_of(line);
  expect_pose_near(line.value().pose, move.pose);
  expect_float_near(line.value().speed_m_s, 0.25);
  expect_float_near(line.value().acc_m_s2, 3.5);
  expect_float_near(line.value().mvtime_s, 0.5);
  EXPECT_EQ(line.value().blend_radius_m, 0.0);  // the legacy form has no radius
  const auto lineb = parse_line_move(22, move_lineb_request(move).params);
  ASSERT_TRUE(lineb.ok());
  expect_pose_near(lineb.value().pose, move.pose);
  expect_float_near(lineb.value().blend_radius_m, 0.012);
}

TEST(RequestRoundTrip, MoveLineInTheCommonFormCarriesItsRadius) {
  Bytes params = ByteWriter()
                     .bytes(move_lineb_request(LineMove{.pose = sample_pose(), .blend_radius_m = -0.001}).params)
                     .u8(0)
                     .u8(0)
                     .u8(0)
                     .take();  // coord, is_axis_angle, only_check_type
  const auto line = parse_line_move(21, params);
  ASSERT_TRUE(line.ok());
  expect_float_near(line.value().blend_radius_m, -0.001);  // < 0: no blend
  params.resize(38);
  EXPECT_EQ(error_of(parse_line_move(21, params)),
            "move_line request carries 38 parameter bytes, expected at least 40");
}

TEST(RequestRoundTrip, JointMovesAndHome) {
  const JointMove move{.joints_rad = sample_joints(), .speed_rad_s = 1.25, .acc_rad_s2 = 8.0, .mvtime_s = 0};
  const auto joint = parse_joint_move(move_joint_request(move).params);
  ASSERT_TRUE(joint.ok());
  expect_joints_near(joint.value().joints_rad, move.joints_rad);
  expect_float_near(joint.value().speed_rad_s, 1.25);
  expect_float_near(joint.value().acc_rad_s2, 8.0);
  const auto home = parse_gohome(move_gohome_request(move).params);
  ASSERT_TRUE(home.ok());
  expect_float_near(home.value().speed_rad_s, 1.25);
  expect_float_near(home.value().acc_rad_s2, 8.0);
  EXPECT_EQ(home.value().joints_rad, JointValues{});
}

TEST(RequestRoundTrip, JointArgumentsPosesAndScalars) {
  for (const Request& request :
       {servo_j_request(sample_joints()), get_fk_request(sample_joints()), is_joint_limit_request(sample_joints())}) {
    const auto joints = parse_joint_params(request.reg, request.params);
    ASSERT_TRUE(joints.ok()) << register_name(request.reg);
    expect_joints_near(joints.value(), sample_joints());
  }
  const auto offset = parse_pose_params(35, set_tcp_offset_request(sample_pose()).params);
  ASSERT_TRUE(offset.ok());
  expect_pose_near(offset.value(), sample_pose());
  const Request sleep = sleep_instruction_request(2.5);
  EXPECT_EQ(parse_scalar_param(sleep.reg, sleep.params).value(), 2.5);
  const Request tcp_jerk = set_tcp_jerk_request(12.5);
  expect_float_near(parse_scalar_param(tcp_jerk.reg, tcp_jerk.params).value(), 12.5);
  const Request tcp_acc = set_tcp_maxacc_request(0.3);
  expect_float_near(parse_scalar_param(tcp_acc.reg, tcp_acc.params).value(), 0.3);
  const Request joint_jerk = set_joint_jerk_request(300);
  expect_float_near(parse_scalar_param(joint_jerk.reg, joint_jerk.params).value(), 300);
  const Request joint_acc = set_joint_maxacc_request(-0.75);
  expect_float_near(parse_scalar_param(joint_acc.reg, joint_acc.params).value(), -0.75);
}

TEST(RequestParsing, ShortBodiesNameTheRegisterAndTheCounts) {
  EXPECT_EQ(error_of(parse_joint_move(Bytes(12, 0))),
            "move_joint request carries 12 parameter bytes, expected at least 40");
  EXPECT_EQ(error_of(parse_motion_enable(Bytes{8})), "motion_en request carries 1 parameter byte, expected at least 2");
  EXPECT_EQ(error_of(parse_set_brake(Bytes{})), "set_brake request carries 0 parameter bytes, expected at least 2");
  EXPECT_EQ(error_of(parse_u8_param(12, Bytes{})), "set_state request carries 0 parameter bytes, expected at least 1");
  EXPECT_EQ(error_of(parse_gohome(Bytes(11, 0))),
            "move_gohome request carries 11 parameter bytes, expected at least 12");
  EXPECT_EQ(error_of(parse_joint_params(29, Bytes(27, 0))),
            "servo_j request carries 27 parameter bytes, expected at least 28");
  EXPECT_EQ(error_of(parse_pose_params(35, Bytes(23, 0))),
            "set_tcp_offset request carries 23 parameter bytes, expected at least 24");
  EXPECT_EQ(error_of(parse_scalar_param(26, Bytes(3, 0))),
            "sleep_instruction request carries 3 parameter bytes, expected at least 4");
  EXPECT_EQ(error_of(parse_line_move(22, Bytes(36, 0))),
            "move_lineb request carries 36 parameter bytes, expected at least 40");
}

TEST(RequestParsing, LongerBodiesAreAccepted) {
  Bytes joint = move_joint_request(JointMove{.joints_rad = sample_joints()}).params;
  joint.push_back(1);  // only_check_type
  EXPECT_TRUE(parse_joint_move(joint).ok());
  Bytes home = move_gohome_request({}).params;
  home.push_back(0);
  EXPECT_TRUE(parse_gohome(home).ok());
  EXPECT_EQ(parse_motion_enable(Bytes{8, 1, 0xFF}).value().joint, 8);
}

TEST(RequestParsing, RefusesSwitchValuesOtherThanZeroOrOne) {
  EXPECT_EQ(error_of(parse_motion_enable(Bytes{8, 2})), "motion_en request value 2 is neither 0 nor 1");
  EXPECT_EQ(error_of(parse_set_brake(Bytes{1, 0xFF})), "set_brake request value 255 is neither 0 nor 1");
}

TEST(RequestParsing, RefusesRegistersOfAnotherLayout) {
  EXPECT_EQ(error_of(parse_line_move(23, Bytes(40, 0))),
            "move_joint is not a line move (move_line 21 or move_lineb 22)");
  EXPECT_NE(error_of(parse_scalar_param(12, Bytes(4, 0))).find("set_state does not take one float"), std::string::npos);
  EXPECT_FALSE(parse_scalar_param(200, Bytes(4, 0)).ok());
}

// ---- Reply data ----------------------------------------------------------------------------

Bytes padded(std::string_view text, std::size_t size = 40) {
  Bytes data(size, 0);
  std::copy_n(text.begin(), std::min(text.size(), size), data.begin());
  return data;
}

TEST(ReplyData, VersionInTheSdksOrder) {
  const auto version = parse_version(padded("6,9,LI1006B12AJA03,AC1303B12AJA03,v2.3.0"));
  ASSERT_TRUE(version.ok()) << error_of(version);
  EXPECT_EQ(version.value().axes, 6);
  EXPECT_EQ(version.value().type, 9);
  EXPECT_EQ(version.value().robot_sn, "LI1006B12AJA03");
  EXPECT_EQ(version.value().control_box_sn, "AC1303B12AJA03");
  EXPECT_EQ(version.value().firmware, "2.3.0");
}

TEST(ReplyData, VersionToleratesMissingFieldsAndNoLeadingV) {
  const auto bare = parse_version(padded("7, 7 ,XS,AC,1.12.10"));
  ASSERT_TRUE(bare.ok()) << error_of(bare);
  EXPECT_EQ(bare.value().type, 7);
  EXPECT_EQ(bare.value().firmware, "1.12.10");
  const auto short_text = parse_version(padded("5,5"));
  ASSERT_TRUE(short_text.ok());
  EXPECT_EQ(short_text.value().axes, 5);
  EXPECT_EQ(short_text.value().robot_sn, "");
  EXPECT_EQ(short_text.value().firmware, "");
  const auto unpadded = parse_version(padded("6,12,A,B,v2.5.0", 15));
  ASSERT_TRUE(unpadded.ok());
  EXPECT_EQ(unpadded.value().firmware, "2.5.0");
}

TEST(ReplyData, VersionNeedsNumericAxisAndType) {
  EXPECT_EQ(error_of(parse_version(padded("7"))),
            "get_version reply \"7\" has no device type: expected a number there in "
            "\"axis,type,robotSN,controlboxSN,vMAJ.MIN.REV\"");
  EXPECT_EQ(error_of(parse_version(padded("xArm,7,a,b,v1"))),
            "get_version reply \"xArm,7,a,b,v1\" has \"xArm\" as axis count: expected a number there in "
            "\"axis,type,robotSN,controlboxSN,vMAJ.MIN.REV\"");
  EXPECT_NE(error_of(parse_version(Bytes{})).find("has no axis count"), std::string::npos);
  EXPECT_NE(error_of(parse_version(padded("6,6x"))).find("\"6x\" as device type"), std::string::npos);
  EXPECT_NE(error_of(parse_version(padded("99999999999,6"))).find("as axis count"), std::string::npos);
  EXPECT_NE(error_of(parse_version(Bytes{'6', 0x01, ',', '6'})).find("\"6?,6\""), std::string::npos);
}

TEST(ReplyData, VersionRoundTripIsFortyBytes) {
  const Version version{.axes = 7, .type = 7, .robot_sn = "XI1303", .control_box_sn = "AC1305", .firmware = "2.4.0"};
  const Bytes data = encode_version(version);
  EXPECT_EQ(data, padded("7,7,XI1303,AC1305,v2.4.0"));
  const auto parsed = parse_version(data);
  ASSERT_TRUE(parsed.ok());
  EXPECT_EQ(parsed.value().robot_sn, "XI1303");
  EXPECT_EQ(parsed.value().control_box_sn, "AC1305");
  EXPECT_EQ(parsed.value().firmware, "2.4.0");
  const Version long_sn{.axes = 6, .type = 6, .robot_sn = std::string(50, 'S'), .control_box_sn = "", .firmware = ""};
  EXPECT_EQ(encode_version(long_sn).size(), 40U);
}

TEST(ReplyData, RobotSnIsTwoNulTerminatedSerials) {
  Bytes data = padded("XI1303B12AJA03");
  const std::string_view box = "AC1305B12AJA03";
  std::copy(box.begin(), box.end(), data.begin() + 15);  // after the robot SN's NUL
  const auto serials = parse_robot_sn(data);
  ASSERT_TRUE(serials.ok()) << error_of(serials);
  EXPECT_EQ(serials.value().robot_sn, "XI1303B12AJA03");
  EXPECT_EQ(serials.value().control_box_sn, "AC1305B12AJA03");
  EXPECT_EQ(encode_robot_sn({.robot_sn = "XI1303B12AJA03", .control_box_sn = "AC1305B12AJA03"}), data);
}

TEST(ReplyData, RobotSnWithoutAControlBoxOrPastFortyBytes) {
  const auto robot_only = parse_robot_sn(padded("XS1"));
  ASSERT_TRUE(robot_only.ok());
  EXPECT_EQ(robot_only.value().robot_sn, "XS1");
  EXPECT_EQ(robot_only.value().control_box_sn, "");
  const auto full = parse_robot_sn(Bytes(40, 'S'));
  ASSERT_TRUE(full.ok()) << "no NUL at all: the robot SN fills the data";
  EXPECT_EQ(full.value().robot_sn, std::string(40, 'S'));
  EXPECT_EQ(full.value().control_box_sn, "");
  const Bytes cut = encode_robot_sn({.robot_sn = std::string(30, 'R'), .control_box_sn = std::string(20, 'B')});
  ASSERT_EQ(cut.size(), 40U);
  EXPECT_EQ(parse_robot_sn(cut).value().control_box_sn, std::string(9, 'B'));
  EXPECT_EQ(error_of(parse_robot_sn(Bytes(39, 0))), "get_robot_sn reply carries 39 data bytes, expected at least 40");
}

TEST(ReplyData, StateCountAndCodes) {
  EXPECT_EQ(parse_state(Bytes{2}).value(), 2);
  EXPECT_EQ(encode_state(kStatePaused), Bytes{3});
  EXPECT_EQ(parse_state(encode_state(kStateReset)).value(), kStateReset);
  EXPECT_EQ(parse_cmdnum(Bytes{0x01, 0x02}).value(), 258);
  EXPECT_EQ(encode_cmdnum(1024), (Bytes{0x04, 0x00}));
  EXPECT_EQ(parse_cmdnum(encode_cmdnum(65535)).value(), 65535);
  EXPECT_EQ(encode_err_code({.error = 111, .warning = 0}), (Bytes{111, 0}));
  EXPECT_EQ(parse_limit_flag(Bytes{1}).value(), true);
  EXPECT_EQ(parse_limit_flag(Bytes{0}).value(), false);
  EXPECT_EQ(encode_limit_flag(true), Bytes{1});
  EXPECT_EQ(encode_limit_flag(false), Bytes{0});
}

TEST(ReplyData, ShortDataNamesTheReplyAndTheCounts) {
  EXPECT_EQ(error_of(parse_err_code(Bytes{0x17})), "get_err_code reply carries 1 data byte, expected at least 2");
  EXPECT_EQ(error_of(parse_state(Bytes{})), "get_state reply carries 0 data bytes, expected at least 1");
  EXPECT_EQ(error_of(parse_cmdnum(Bytes{1})), "command count reply carries 1 data byte, expected at least 2");
  EXPECT_EQ(error_of(parse_pose(Bytes(20, 0))),
            "pose (get_tcp_pose, get_fk) reply carries 20 data bytes, expected at least 24");
  EXPECT_EQ(error_of(parse_joints(Bytes(24, 0))), "get_joint_pos reply carries 24 data bytes, expected at least 28");
  EXPECT_EQ(error_of(parse_limit_flag(Bytes{})), "is_joint_limit reply carries 0 data bytes, expected at least 1");
}

TEST(ReplyData, PosesAreMillimetresOnTheWire) {
  const Bytes data = encode_pose(Pose{.position_m = {0.4, -0.4, 0}, .rpy_rad = {kPi, 0, -kPi}});
  ASSERT_EQ(data.size(), 24U);
  EXPECT_EQ(Bytes(data.begin(), data.begin() + 4), (Bytes{0x00, 0x00, 0xC8, 0x43}));
  EXPECT_EQ(Bytes(data.begin() + 4, data.begin() + 8), (Bytes{0x00, 0x00, 0xC8, 0xC3}));
  const auto pose = parse_pose(data);
  ASSERT_TRUE(pose.ok());
  expect_float_near(pose.value().position_m[0], 0.4);
  expect_float_near(pose.value().position_m[1], -0.4);
  EXPECT_EQ(pose.value().rpy_rad[0], as_float(kPi));
  EXPECT_EQ(pose.value().rpy_rad[2], as_float(-kPi));
  const auto extreme = parse_pose(encode_pose(Pose{.position_m = {1e300, -1e300, kNaN}, .rpy_rad = {}}));
  ASSERT_TRUE(extreme.ok());
  EXPECT_EQ(extreme.value().position_m[0], std::numeric_limits<float>::max() / 1000.0);
  EXPECT_TRUE(std::isnan(extreme.value().position_m[2]));
}

TEST(ReplyData, JointsRoundTripAndTheLongFormIsAccepted) {
  const Bytes data = encode_joints(sample_joints());
  EXPECT_EQ(data.size(), 28U);
  expect_joints_near(parse_joints(data).value(), sample_joints());
  Bytes with_velocities = data;
  with_velocities.resize(56, 0);  // get_joint_pos with n = 2: positions, then velocities
  expect_joints_near(parse_joints(with_velocities).value(), sample_joints());
}

TEST(ReplyData, ServoDbmsgInBothLengths) {
  std::array<ServoStatus, 8> servos{};
  servos[2] = {.state = 1, .error = 11};
  servos[7] = {.state = 3, .error = 0};
  const Bytes data = encode_servo_dbmsg(servos);
  ASSERT_EQ(data.size(), 16U);
  EXPECT_EQ(data[4], 1);
  EXPECT_EQ(data[5], 11);
  const auto sdk = parse_servo_dbmsg(data);
  ASSERT_TRUE(sdk.ok());
  EXPECT_EQ(sdk.value()[2].state, 1);
  EXPECT_EQ(sdk.value()[2].error, 11);
  EXPECT_EQ(sdk.value()[7].state, 3);
  Bytes doc_form{1};  // the doc example's leading execution status
  doc_form.insert(doc_form.end(), data.begin(), data.end());
  const auto doc = parse_servo_dbmsg(doc_form);
  ASSERT_TRUE(doc.ok());
  EXPECT_EQ(doc.value()[2].error, 11);
  EXPECT_EQ(doc.value()[0].state, 0);
  EXPECT_EQ(error_of(parse_servo_dbmsg(Bytes(15, 0))),
            "servo_get_dbmsg reply carries 15 data bytes, expected 16 (or 17 with a leading status byte)");
  EXPECT_FALSE(parse_servo_dbmsg(Bytes(18, 0)).ok());
}

// ---- Motion feedback -----------------------------------------------------------------------

TEST(MotionFeedback, ReadsTheSpecLayout) {
  // Transaction 7: move_line (0x15) task 42 finished, code 0, at 123456 µs.
  const Bytes wire{0x00, 0x07, 0x00, 0x02, 0x00, 0x0F, 0xFF, 0x00, 0x02, 0x15, 0x00,
                   0x2A, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x01, 0xE2, 0x40};
  FrameSplitter splitter;
  splitter.append(wire);
  const auto frames = drain(splitter);
  ASSERT_EQ(frames.size(), 1U);
  ASSERT_TRUE(is_motion_feedback(frames[0]));
  const auto feedback = parse_motion_feedback(frames[0]);
  ASSERT_TRUE(feedback.ok()) << error_of(feedback);
  EXPECT_EQ(feedback.value().transaction_id, 7);
  EXPECT_EQ(feedback.value().type, 2);
  EXPECT_EQ(feedback.value().command_reg, reg_of(Register::kMoveLine));
  EXPECT_EQ(feedback.value().task_id, 42);
  EXPECT_EQ(feedback.value().code, 0);
  EXPECT_EQ(feedback.value().controller_time_us, 123456U);
  EXPECT_EQ(encode_frame(motion_feedback_frame(feedback.value())), wire);
}

TEST(MotionFeedback, RoundTripWithTheKeepAliveProtocol) {
  const MotionFeedback feedback{.transaction_id = 65535,
                                .type = 4,
                                .command_reg = 23,
                                .task_id = 0xBEEF,
                                .code = 2,
                                .controller_time_us = 0xFFFFFFFFFFFFFFFFULL};
  const Frame frame = motion_feedback_frame(feedback, kProtocolKeepAlive);
  EXPECT_EQ(frame.protocol, kProtocolKeepAlive);
  EXPECT_TRUE(is_motion_feedback(frame));
  const auto parsed = parse_motion_feedback(frame);
  ASSERT_TRUE(parsed.ok());
  EXPECT_EQ(parsed.value().transaction_id, 65535);
  EXPECT_EQ(parsed.value().type, 4);
  EXPECT_EQ(parsed.value().command_reg, 23);
  EXPECT_EQ(parsed.value().task_id, 0xBEEF);
  EXPECT_EQ(parsed.value().code, 2);
  EXPECT_EQ(parsed.value().controller_time_us, 0xFFFFFFFFFFFFFFFFULL);
}

TEST(MotionFeedback, RefusesOtherFramesAndShortBodies) {
  const Frame reply = reply_frame(1, 2, 13, 0, Bytes{2});
  EXPECT_FALSE(is_motion_feedback(reply));
  EXPECT_EQ(error_of(parse_motion_feedback(reply)), "get_state frame is not motion feedback (register 0xFF)");
  Frame short_frame = motion_feedback_frame({});
  short_frame.body.resize(13);
  EXPECT_EQ(error_of(parse_motion_feedback(short_frame)),
            "motion feedback frame carries 13 bytes after its register, expected at least 14");
}

// ---- Reports -------------------------------------------------------------------------------

TEST(Reports, KindNamesAndPorts) {
  for (const ReportKind kind : {ReportKind::kReal, ReportKind::kNormal, ReportKind::kRealtime, ReportKind::kRich}) {
    EXPECT_EQ(parse_report_kind(report_kind_name(kind)), kind);
  }
  EXPECT_EQ(report_kind_name(ReportKind::kReal), "real");
  EXPECT_EQ(report_kind_name(ReportKind::kNormal), "normal");
  EXPECT_EQ(report_kind_name(ReportKind::kRealtime), "realtime");
  EXPECT_EQ(default_report_port(ReportKind::kReal), 30003);
  EXPECT_EQ(default_report_port(ReportKind::kNormal), 30001);
  EXPECT_EQ(default_report_port(ReportKind::kRealtime), 30000);
  EXPECT_EQ(default_report_port(ReportKind::kRich), 30002);
  EXPECT_EQ(parse_report_kind("fast"), std::nullopt);
  EXPECT_EQ(parse_report_kind("Real"), std::nullopt);
  EXPECT_EQ(parse_report_kind(""), std::nullopt);
}

TEST(Reports, HandBuiltRealReport) {
  Bytes packet(87, 0);
  const Bytes head{0x00, 0x00, 0x00, 0x57, 0x12, 0x00, 0x03};  // size 87, mode 1 state 2, 3 queued
  std::copy(head.begin(), head.end(), packet.begin());
  const Bytes pi{0xDB, 0x0F, 0x49, 0x40};
  std::copy(pi.begin(), pi.end(), packet.begin() + 7);  // joint 1
  const Bytes mm400{0x00, 0x00, 0xC8, 0x43};
  std::copy(mm400.begin(), mm400.end(), packet.begin() + 43);  // TCP z
  std::copy(pi.begin(), pi.end(), packet.begin() + 83);        // joint 7 torque
  const auto report = parse_report(packet, ReportKind::kReal);
  ASSERT_TRUE(report.ok()) << error_of(report);
  EXPECT_EQ(report.value().state, 2);
  EXPECT_EQ(report.value().mode, 1);
  EXPECT_EQ(report.value().cmd_num, 3);
  EXPECT_EQ(report.value().position_rad[0], as_float(kPi));
  expect_float_near(report.value().tcp_pose.position_m[2], 0.4);
  EXPECT_EQ(report.value().effort[6], as_float(kPi));
  EXPECT_FALSE(report.value().has_force_torque);
  EXPECT_FALSE(report.value().has_codes);
  EXPECT_FALSE(report.value().has_velocity);
  EXPECT_FALSE(report.value().has_timestamp);
  EXPECT_FALSE(report.value().has_settings);
  EXPECT_FALSE(report.value().has_gravity_direction);
  EXPECT_FALSE(report.value().has_targets);
}

TEST(Reports, RealRoundTripWithAndWithoutForceTorque) {
  const Report sent = sample_report();
  const Bytes plain = encode_report(sent, ReportKind::kReal);
  ASSERT_EQ(plain.size(), 87U);
  EXPECT_EQ(Bytes(plain.begin(), plain.begin() + 7), (Bytes{0x00, 0x00, 0x00, 0x57, 0x11, 0x02, 0x01}));
  const auto report = parse_report(plain, ReportKind::kReal);
  ASSERT_TRUE(report.ok()) << error_of(report);
  EXPECT_EQ(report.value().state, 1);
  EXPECT_EQ(report.value().mode, 1);
  EXPECT_EQ(report.value().cmd_num, 513);
  expect_joints_near(report.value().position_rad, sent.position_rad);
  expect_joints_near(report.value().effort, sent.effort);
  expect_pose_near(report.value().tcp_pose, sent.tcp_pose);
  EXPECT_FALSE(report.value().has_force_torque);

  const Bytes with_ft = encode_report(sent, ReportKind::kReal, true);
  ASSERT_EQ(with_ft.size(), 135U);
  const auto ft = parse_report(with_ft, ReportKind::kReal);
  ASSERT_TRUE(ft.ok());
  EXPECT_TRUE(ft.value().has_force_torque);
  EXPECT_EQ(ft.value().force_torque, sent.force_torque);
  EXPECT_EQ(Bytes(with_ft.begin() + 87, with_ft.begin() + 91), f32_bytes(1.0));
}

TEST(Reports, NormalRoundTripCarriesCodesAndMasks) {
  const Report sent = sample_report();
  const Bytes packet = encode_report(sent, ReportKind::kNormal, true);
  ASSERT_EQ(packet.size(), 145U);
  EXPECT_EQ(Bytes(packet.begin() + 87, packet.begin() + 91), (Bytes{0x3F, 0x1F, 23, 11}));
  const auto report = parse_report(packet, ReportKind::kNormal);
  ASSERT_TRUE(report.ok()) << error_of(report);
  EXPECT_TRUE(report.value().has_codes);
  EXPECT_EQ(report.value().error_code, 23);
  EXPECT_EQ(report.value().warning_code, 11);
  EXPECT_EQ(report.value().brake_mask, 0x3F);
  EXPECT_EQ(report.value().enable_mask, 0x1F);
  expect_joints_near(report.value().position_rad, sent.position_rad);
  expect_pose_near(report.value().tcp_pose, sent.tcp_pose);
  EXPECT_FALSE(report.value().has_force_torque);
  EXPECT_FALSE(report.value().has_targets);
}

TEST(Reports, NormalCarriesTheSettingsAtTheSpecsOffsets) {
  const Report sent = sample_report();
  const Bytes packet = encode_report(sent, ReportKind::kNormal);
  const auto at = [&packet](std::size_t offset) {
    return Bytes(packet.begin() + static_cast<std::ptrdiff_t>(offset),
                 packet.begin() + static_cast<std::ptrdiff_t>(offset + 4));
  };
  EXPECT_EQ(at(91), (Bytes{0x00, 0x00, 0x20, 0x41}));   // TCP offset x: 10 mm
  EXPECT_EQ(at(99), (Bytes{0x00, 0x00, 0xFA, 0x42}));   // TCP offset z: 125 mm
  EXPECT_EQ(at(111), f32_bytes(kPi / 2));               // TCP offset yaw, rad
  EXPECT_EQ(at(115), (Bytes{0x00, 0x00, 0xC0, 0x3F}));  // payload: 1.5 kg
  EXPECT_EQ(at(127), (Bytes{0x00, 0x00, 0x48, 0x42}));  // centre of mass z: 50 mm
  EXPECT_EQ(packet[131], 4);                            // collision sensitivity
  EXPECT_EQ(packet[132], 2);                            // teach sensitivity
  EXPECT_EQ(at(141), (Bytes{0x00, 0x00, 0x40, 0xBF}));  // gravity z: -0.75
  const auto report = parse_report(packet, ReportKind::kNormal);
  ASSERT_TRUE(report.ok()) << error_of(report);
  EXPECT_TRUE(report.value().has_settings);
  expect_pose_near(report.value().tcp_offset, sent.tcp_offset);
  EXPECT_EQ(report.value().payload_kg, 1.5);
  for (std::size_t i = 0; i < 3; ++i) expect_float_near(report.value().payload_centre_m[i], sent.payload_centre_m[i]);
  EXPECT_EQ(report.value().collision_sensitivity, 4);
  EXPECT_EQ(report.value().teach_sensitivity, 2);
  EXPECT_TRUE(report.value().has_gravity_direction);
  EXPECT_EQ(report.value().gravity_direction, sent.gravity_direction);
}

TEST(Reports, NormalFromOlderFirmwareHas133Bytes) {
  Bytes packet = encode_report(sample_report(), ReportKind::kNormal);
  packet.resize(133);
  packet[3] = 133;
  const auto report = parse_report(packet, ReportKind::kNormal);
  ASSERT_TRUE(report.ok()) << error_of(report);
  EXPECT_EQ(report.value().error_code, 23);
  EXPECT_TRUE(report.value().has_settings) << "everything up to the teach sensitivity";
  EXPECT_EQ(report.value().teach_sensitivity, 2);
  EXPECT_EQ(report.value().payload_kg, 1.5);
  EXPECT_FALSE(report.value().has_gravity_direction);
  EXPECT_EQ(report.value().gravity_direction, (std::array<double, 3>{}));
}

TEST(Reports, RealtimeRoundTripAndLayout) {
  const Report sent = sample_report();
  const Bytes packet = encode_report(sent, ReportKind::kRealtime);
  ASSERT_EQ(packet.size(), 784U);
  EXPECT_EQ(Bytes(packet.begin(), packet.begin() + 15),
            (Bytes{0x00, 0x00, 0x03, 0x10, 0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07, 0x08, 0x11, 0x02, 0x01}));
  EXPECT_EQ(Bytes(packet.begin() + 32, packet.begin() + 36), (Bytes{0x00, 0x00, 0x80, 0x3E}));  // target joint 1: 0.25
  EXPECT_EQ(Bytes(packet.begin() + 60, packet.begin() + 64), (Bytes{0x00, 0x00, 0x80, 0x3F}));  // its velocity: 1
  EXPECT_EQ(Bytes(packet.begin() + 84, packet.begin() + 88), f32_bytes(-3.0));     // target joint 7's velocity
  EXPECT_EQ(Bytes(packet.begin() + 88, packet.begin() + 116), Bytes(28, 0));       // target accelerations: not modelled
  EXPECT_EQ(Bytes(packet.begin() + 116, packet.begin() + 120), f32_bytes(0.5));    // actual joint 1
  EXPECT_EQ(Bytes(packet.begin() + 228, packet.begin() + 232), f32_bytes(1.5));    // estimated torque 1
  EXPECT_EQ(Bytes(packet.begin() + 472, packet.begin() + 476), f32_bytes(300.0));  // actual TCP x, mm
  EXPECT_EQ(Bytes(packet.begin() + 712, packet.begin() + 716), f32_bytes(1.0));    // F/T filtered Fx
  const auto report = parse_report(packet, ReportKind::kRealtime);
  ASSERT_TRUE(report.ok()) << error_of(report);
  EXPECT_TRUE(report.value().has_timestamp);
  EXPECT_EQ(report.value().timestamp_us, sent.timestamp_us);
  EXPECT_EQ(report.value().state, 1);
  EXPECT_EQ(report.value().cmd_num, 513);
  EXPECT_TRUE(report.value().has_velocity);
  expect_joints_near(report.value().position_rad, sent.position_rad);
  expect_joints_near(report.value().velocity_rad_s, sent.velocity_rad_s);
  EXPECT_TRUE(report.value().has_targets);
  expect_joints_near(report.value().target_position_rad, sent.target_position_rad);
  expect_joints_near(report.value().target_velocity_rad_s, sent.target_velocity_rad_s);
  expect_joints_near(report.value().effort, sent.effort);
  expect_pose_near(report.value().tcp_pose, sent.tcp_pose);
  EXPECT_TRUE(report.value().has_force_torque);
  EXPECT_EQ(report.value().force_torque, sent.force_torque);
  EXPECT_FALSE(report.value().has_codes);
  EXPECT_FALSE(report.value().has_settings);
  EXPECT_FALSE(report.value().has_gravity_direction);
}

TEST(Reports, RealtimeAcceptsTheSdks804Bytes) {
  Bytes packet = encode_report(sample_report(), ReportKind::kRealtime);
  packet.resize(804, 0);
  packet[2] = 0x03;
  packet[3] = 0x24;
  const auto report = parse_report(packet, ReportKind::kRealtime);
  ASSERT_TRUE(report.ok()) << error_of(report);
  EXPECT_EQ(report.value().cmd_num, 513);
}

TEST(Reports, RefusesSizesThatDoNotFit) {
  Bytes packet = encode_report(sample_report(), ReportKind::kReal);
  EXPECT_EQ(error_of(parse_report(packet, ReportKind::kNormal)), "normal report has 87 bytes, expected 133 or 145");
  EXPECT_EQ(error_of(parse_report(packet, ReportKind::kRealtime)), "realtime report has 87 bytes, expected 784 or 804");
  packet.push_back(0);
  EXPECT_EQ(error_of(parse_report(packet, ReportKind::kReal)),
            "real report size field says 87 bytes but the packet has 88");
  EXPECT_EQ(error_of(parse_report(Bytes{0x00, 0x00}, ReportKind::kReal)),
            "real report carries 2 bytes, expected at least 4");
}

TEST(Reports, RefusesImpossibleStatesAndModes) {
  Report report = sample_report();
  report.state = 10;
  EXPECT_EQ(error_of(parse_report(encode_report(report, ReportKind::kReal), ReportKind::kReal)),
            "real report has state 10 and mode 1, expected a state below 10 and a mode below 12");
  report.state = 9;
  EXPECT_TRUE(parse_report(encode_report(report, ReportKind::kReal), ReportKind::kReal).ok());
  report.mode = 12;
  EXPECT_FALSE(parse_report(encode_report(report, ReportKind::kRealtime), ReportKind::kRealtime).ok());
  report.mode = 11;
  EXPECT_TRUE(parse_report(encode_report(report, ReportKind::kNormal), ReportKind::kNormal).ok());
}

TEST(ReportSplitter, JoinsPiecesAndCutsSeveralPackets) {
  const Bytes real = encode_report(sample_report(), ReportKind::kReal);
  const Bytes normal = encode_report(sample_report(), ReportKind::kNormal);
  Bytes stream = real;
  stream.insert(stream.end(), normal.begin(), normal.end());
  stream.insert(stream.end(), real.begin(), real.end());
  ReportSplitter splitter;
  splitter.append(ByteView(stream).first(3));
  EXPECT_TRUE(drain(splitter).empty());
  splitter.append(ByteView(stream).subspan(3, 100));
  auto packets = drain(splitter);
  ASSERT_EQ(packets.size(), 1U);
  EXPECT_EQ(packets[0], real);
  splitter.append(ByteView(stream).subspan(103));
  packets = drain(splitter);
  ASSERT_EQ(packets.size(), 2U);
  EXPECT_EQ(packets[0], normal);
  EXPECT_EQ(packets[1], real);
}

TEST(ReportSplitter, BadSizesAreStickyUntilClear) {
  ReportSplitter splitter;
  splitter.append(Bytes{0x00, 0x00, 0x00, 0x07, 0x01, 0x02, 0x03});
  auto next = splitter.next();
  ASSERT_FALSE(next.ok());
  EXPECT_EQ(next.error().message,
            "report size field 7 is outside 8..4096: the report stream lost its framing (reconnect)");
  splitter.append(encode_report(sample_report(), ReportKind::kReal));
  EXPECT_FALSE(splitter.next().ok());
  splitter.clear();
  splitter.append(encode_report(sample_report(), ReportKind::kReal));
  EXPECT_EQ(drain(splitter).size(), 1U);

  splitter.append(Bytes{0x00, 0x00, 0x10, 0x01});  // 4097
  EXPECT_FALSE(splitter.next().ok());
  splitter.clear();
  const Bytes smallest{0x00, 0x00, 0x00, 0x08, 0xAA, 0xBB, 0xCC, 0xDD};
  splitter.append(smallest);
  const auto packets = drain(splitter);
  ASSERT_EQ(packets.size(), 1U);
  EXPECT_EQ(packets[0], smallest);
}

// ---- Error tables --------------------------------------------------------------------------

TEST(ErrorTables, ControllerErrorsAndWarnings) {
  EXPECT_EQ(controller_error_text(0), "");
  EXPECT_EQ(controller_error_text(1), "C1 emergency-stop button on the control box pressed");
  EXPECT_EQ(controller_error_text(13), "C13 servo motor 3 error");
  EXPECT_EQ(controller_error_text(60), "C60 linear speed exceeded limit in servo_j mode");
  EXPECT_EQ(controller_error_text(111), "C111 control-box external RS485 device communication error");
  EXPECT_EQ(controller_error_text(99), "C99 unknown controller error");
  EXPECT_EQ(controller_error_text(-5), "C-5 unknown controller error");
  EXPECT_EQ(controller_warning_text(0), "");
  EXPECT_EQ(controller_warning_text(13), "W13 command (register) does not exist");
  EXPECT_EQ(controller_warning_text(15), "W15 Modbus command queue full");
  EXPECT_EQ(controller_warning_text(99), "W99 unknown warning");
}

TEST(ErrorTables, ServoErrorsAndEstops) {
  EXPECT_EQ(servo_error_text(0), "");
  EXPECT_EQ(servo_error_text(11), "joint over-current");
  EXPECT_EQ(servo_error_text(58), "torque command timeout");
  EXPECT_EQ(servo_error_text(99), "servo error 99");
  EXPECT_EQ(servo_error_text(13), "servo error 13");
  for (int code = -1; code < 256; ++code) EXPECT_EQ(is_estop_error(code), code >= 1 && code <= 3) << code;
}

// ---- Models --------------------------------------------------------------------------------

TEST(Models, FoundByNameWhateverTheCase) {
  const auto xarm6 = find_model("XArm6");
  ASSERT_TRUE(xarm6.has_value());
  EXPECT_EQ(xarm6->name, "xarm6");
  EXPECT_EQ(xarm6->display, "xArm 6");
  EXPECT_EQ(xarm6->dof, 6U);
  EXPECT_EQ(xarm6->type_code, 6);
  EXPECT_EQ(find_model("LITE6")->display, "Lite 6");
  EXPECT_EQ(find_model("uf850")->display, "UFACTORY 850");
  EXPECT_EQ(find_model("xarm6-X8")->display, "xArm 6 (X8)");
  EXPECT_EQ(find_model("xarm8"), std::nullopt);
  EXPECT_EQ(find_model(""), std::nullopt);
  EXPECT_EQ(find_model("xarm6 "), std::nullopt);
}

TEST(Models, LimitsFromTheTableInRadians) {
  const auto xarm6 = find_model("xarm6").value();
  EXPECT_NEAR(xarm6.min_rad[1], -2.059488, 1e-6);
  EXPECT_NEAR(xarm6.max_rad[1], 2.094395, 1e-6);
  EXPECT_NEAR(xarm6.max_rad[2], 0.191986, 1e-6);
  EXPECT_NEAR(xarm6.min_rad[4], -1.692969, 1e-6);
  EXPECT_DOUBLE_EQ(xarm6.max_rad[0], 2 * kPi);
  EXPECT_EQ(xarm6.min_rad[6], 0.0);
  EXPECT_EQ(xarm6.max_tcp_speed_m_s, 1.0);
  const auto lite6 = find_model("lite6").value();
  EXPECT_EQ(lite6.max_tcp_speed_m_s, 0.5);
  EXPECT_DOUBLE_EQ(lite6.min_rad[2], -3.5 * kRadPerDegree);
  EXPECT_DOUBLE_EQ(lite6.max_rad[2], 300 * kRadPerDegree);
  const auto xarm7 = find_model("xarm7").value();
  EXPECT_DOUBLE_EQ(xarm7.min_rad[3], -11 * kRadPerDegree);
  EXPECT_DOUBLE_EQ(xarm7.max_rad[3], 225 * kRadPerDegree);
  EXPECT_DOUBLE_EQ(find_model("uf850")->min_rad[2], -242 * kRadPerDegree);
  EXPECT_DOUBLE_EQ(find_model("xarm7-x13")->min_rad[5], -180 * kRadPerDegree);
}

TEST(Models, ByTheControllersAxesAndType) {
  EXPECT_EQ(model_for_type(5, 5)->name, "xarm5");
  EXPECT_EQ(model_for_type(6, 6)->name, "xarm6");
  EXPECT_EQ(model_for_type(7, 7)->name, "xarm7");
  EXPECT_EQ(model_for_type(6, 5)->name, "xarm6");  // an X4 type code: the axes decide
  EXPECT_EQ(model_for_type(7, 6)->name, "xarm7");
  EXPECT_EQ(model_for_type(6, 9)->name, "lite6");
  EXPECT_EQ(model_for_type(6, 12)->name, "uf850");
  EXPECT_EQ(model_for_type(6, 8)->name, "xarm6-x8");
  EXPECT_EQ(model_for_type(7, 3)->name, "xarm7-x3");
  EXPECT_EQ(model_for_type(7, 71305)->name, "xarm7-1305");
  EXPECT_EQ(model_for_type(7, 9), std::nullopt);
  EXPECT_EQ(model_for_type(8, 7), std::nullopt);
  EXPECT_EQ(model_for_type(-6, 6), std::nullopt);
  EXPECT_EQ(model_for_type(6, 0), std::nullopt);
}

TEST(Models, EveryKnownModelIsConsistent) {
  const auto models = known_models();
  EXPECT_EQ(models.size(), 12U);
  std::set<std::string_view> names;
  for (const ArmModel& model : models) {
    EXPECT_TRUE(names.insert(model.name).second) << model.name;
    EXPECT_GE(model.dof, 5U);
    EXPECT_LE(model.dof, kMaxDof);
    EXPECT_FALSE(model.display.empty());
    EXPECT_EQ(find_model(model.name)->display, model.display);
    EXPECT_EQ(model_for_type(static_cast<int>(model.dof), model.type_code)->name, model.name);
    for (std::size_t j = 0; j < kMaxDof; ++j) {
      if (j < model.dof) {
        EXPECT_LT(model.min_rad[j], model.max_rad[j]) << model.name << " joint " << j + 1;
        EXPECT_LE(model.max_rad[j], 2 * kPi + 1e-12);
        EXPECT_GE(model.min_rad[j], -2 * kPi - 1e-12);
      } else {
        EXPECT_EQ(model.min_rad[j], 0.0);
        EXPECT_EQ(model.max_rad[j], 0.0);
      }
    }
  }
  for (const char* name : {"xarm5", "xarm6", "xarm7", "lite6", "uf850", "xarm5-1305", "xarm6-1305", "xarm6-x8",
                           "xarm6-x11", "xarm7-x3", "xarm7-1305", "xarm7-x13"}) {
    EXPECT_TRUE(names.contains(name)) << name;
  }
}

// ---- Argument checks -----------------------------------------------------------------------

TEST(ArgumentChecks, JointSelector) {
  EXPECT_TRUE(check_joint_selector(1, 6).ok());
  EXPECT_TRUE(check_joint_selector(6, 6).ok());
  EXPECT_TRUE(check_joint_selector(8, 6).ok());
  EXPECT_TRUE(check_joint_selector(7, 7).ok());
  EXPECT_EQ(error_of(check_joint_selector(7, 6)), "joint 7 is outside 1..6 (or 8 for all joints)");
  EXPECT_FALSE(check_joint_selector(0, 6).ok());
  EXPECT_FALSE(check_joint_selector(-1, 6).ok());
  EXPECT_FALSE(check_joint_selector(9, 7).ok());
  EXPECT_EQ(check_joint_selector(0, 6).error().code, ErrorCode::kInvalidArgument);
}

TEST(ArgumentChecks, TcpSpeedDependsOnTheModel) {
  const ArmModel lite6 = find_model("lite6").value();
  const ArmModel xarm6 = find_model("xarm6").value();
  EXPECT_TRUE(check_tcp_speed(0.5, lite6).ok());
  EXPECT_EQ(error_of(check_tcp_speed(0.6, lite6)), "TCP speed 0.6 m/s is outside (0, 0.5] m/s for the Lite 6");
  EXPECT_TRUE(check_tcp_speed(1.0, xarm6).ok());
  EXPECT_FALSE(check_tcp_speed(1.0000001, xarm6).ok());
  EXPECT_FALSE(check_tcp_speed(0, xarm6).ok());
  EXPECT_FALSE(check_tcp_speed(-0.1, xarm6).ok());
}

TEST(ArgumentChecks, MotionParameterRanges) {
  EXPECT_EQ(error_of(check_joint_speed(4.0)), "joint speed 4 rad/s is outside (0, 3.1416] rad/s");
  EXPECT_TRUE(check_joint_speed(kPi).ok());
  EXPECT_TRUE(check_joint_speed(1e-9).ok());
  EXPECT_FALSE(check_joint_speed(0).ok());
  EXPECT_TRUE(check_tcp_acc(50).ok());
  EXPECT_EQ(error_of(check_tcp_acc(50.5)), "TCP acceleration 50.5 m/s² is outside (0, 50] m/s²");
  EXPECT_TRUE(check_tcp_jerk(100).ok());
  EXPECT_FALSE(check_tcp_jerk(100.01).ok());
  EXPECT_TRUE(check_joint_acc(20).ok());
  EXPECT_FALSE(check_joint_acc(20.5).ok());
  EXPECT_TRUE(check_joint_jerk(500).ok());
  EXPECT_FALSE(check_joint_jerk(0).ok());
  EXPECT_TRUE(check_sleep(0).ok());
  EXPECT_TRUE(check_sleep(3600).ok());
  EXPECT_EQ(error_of(check_sleep(-0.5)), "sleep time -0.5 s is outside [0, 3600] s");
}

TEST(ArgumentChecks, NanAndInfinityAreRefused) {
  const ArmModel xarm7 = find_model("xarm7").value();
  EXPECT_EQ(error_of(check_joint_speed(kNaN)), "joint speed nan rad/s is outside (0, 3.1416] rad/s");
  EXPECT_FALSE(check_tcp_speed(kNaN, xarm7).ok());
  EXPECT_FALSE(check_tcp_acc(kNaN).ok());
  EXPECT_FALSE(check_tcp_jerk(kNaN).ok());
  EXPECT_FALSE(check_joint_acc(kNaN).ok());
  EXPECT_FALSE(check_joint_jerk(kNaN).ok());
  EXPECT_FALSE(check_sleep(kNaN).ok());
  EXPECT_FALSE(check_sleep(kInf).ok());
  EXPECT_FALSE(check_tcp_acc(kInf).ok());
  JointValues joints{};
  joints[3] = kNaN;
  EXPECT_FALSE(check_joints_within(joints, xarm7).ok());
}

TEST(ArgumentChecks, JointsWithinTheModelsLimits) {
  const ArmModel xarm6 = find_model("xarm6").value();
  JointValues joints{};
  EXPECT_TRUE(check_joints_within(joints, xarm6).ok());
  joints = xarm6.max_rad;
  EXPECT_TRUE(check_joints_within(joints, xarm6).ok());
  joints = xarm6.min_rad;
  EXPECT_TRUE(check_joints_within(joints, xarm6).ok());
  joints[6] = 100.0;  // beyond the arm's joints: not checked
  EXPECT_TRUE(check_joints_within(joints, xarm6).ok());
  joints = {};
  joints[2] = 0.5;
  EXPECT_EQ(error_of(check_joints_within(joints, xarm6)),
            "joint 3 angle 0.5 rad is outside [-3.927, 0.19199] rad for the xArm 6");
}

TEST(ArgumentChecks, JointLimitsForgiveTheWiresRounding) {
  const ArmModel xarm6 = find_model("xarm6").value();
  JointValues joints = xarm6.max_rad;
  for (std::size_t j = 0; j < xarm6.dof; ++j) joints[j] = as_float(joints[j]);
  EXPECT_TRUE(check_joints_within(joints, xarm6).ok()) << "each limit rounded to a float";
  joints = {};
  joints[2] = xarm6.max_rad[2] + 0.9e-6;
  joints[3] = xarm6.min_rad[3] - 0.9e-6;
  EXPECT_TRUE(check_joints_within(joints, xarm6).ok());
  joints[2] = xarm6.max_rad[2] + 1.1e-6;
  EXPECT_NE(error_of(check_joints_within(joints, xarm6)).find("is outside [-3.927, 0.19199] rad"), std::string::npos)
      << "the message names the limits themselves";
}

// ---- Truncated and random input ------------------------------------------------------------

/// Every decoder on `data`; none may crash or read out of bounds, whatever they return.
void decode_everything(ByteView data) {
  static_cast<void>(parse_motion_enable(data));
  static_cast<void>(parse_set_brake(data));
  static_cast<void>(parse_u8_param(12, data));
  static_cast<void>(parse_line_move(21, data));
  static_cast<void>(parse_line_move(22, data));
  static_cast<void>(parse_joint_move(data));
  static_cast<void>(parse_gohome(data));
  static_cast<void>(parse_joint_params(29, data));
  static_cast<void>(parse_pose_params(35, data));
  static_cast<void>(parse_scalar_param(31, data));
  static_cast<void>(parse_version(data));
  static_cast<void>(parse_robot_sn(data));
  static_cast<void>(parse_state(data));
  static_cast<void>(parse_cmdnum(data));
  static_cast<void>(parse_err_code(data));
  static_cast<void>(parse_pose(data));
  static_cast<void>(parse_joints(data));
  static_cast<void>(parse_limit_flag(data));
  static_cast<void>(parse_servo_dbmsg(data));
  for (const ReportKind kind : {ReportKind::kReal, ReportKind::kNormal, ReportKind::kRealtime}) {
    static_cast<void>(parse_report(data, kind));
  }
  for (const std::uint8_t reg : {std::uint8_t{13}, std::uint8_t{0xFF}}) {
    const Frame frame{.transaction_id = 1, .protocol = 2, .reg = reg, .body = Bytes(data.begin(), data.end())};
    static_cast<void>(parse_reply(frame));
    static_cast<void>(parse_motion_feedback(frame));
  }
  FrameSplitter frames;
  frames.append(data);
  while (true) {
    auto next = frames.next();
    if (!next.ok() || !next.value()) break;
    static_cast<void>(parse_reply(*next.value()));
  }
  ReportSplitter reports;
  reports.append(data);
  while (true) {
    auto next = reports.next();
    if (!next.ok() || !next.value()) break;
  }
}

std::vector<Bytes> valid_messages() {
  const Report report = sample_report();
  return {
      motion_enable_request(8, true).params,
      move_line_request({}).params,
      move_lineb_request({}).params,
      move_joint_request({}).params,
      move_gohome_request({}).params,
      servo_j_request(sample_joints()).params,
      set_tcp_offset_request(sample_pose()).params,
      set_tcp_jerk_request(1).params,
      encode_version({.axes = 6, .type = 6, .robot_sn = "XI", .control_box_sn = "AC", .firmware = "2.3.0"}),
      encode_robot_sn({.robot_sn = "XI", .control_box_sn = "AC"}),
      encode_state(kStateSleeping),
      encode_cmdnum(3),
      encode_err_code({.error = 1, .warning = 2}),
      encode_pose(sample_pose()),
      encode_joints(sample_joints()),
      encode_servo_dbmsg({}),
      encode_frame(motion_feedback_frame({})),
      motion_feedback_frame({}).body,
      encode_frame(reply_frame(1, 2, 42, 0, encode_joints(sample_joints()))),
      encode_report(report, ReportKind::kReal),
      encode_report(report, ReportKind::kReal, true),
      encode_report(report, ReportKind::kNormal),
      encode_report(report, ReportKind::kRealtime),
  };
}

TEST(Robustness, TruncatedMessagesAreRefusedNotOverread) {
  std::size_t cases = 0;
  for (const Bytes& message : valid_messages()) {
    for (std::size_t size = 0; size <= message.size(); ++size) {
      // A copy of exactly `size` bytes, so a sanitizer sees any read past it.
      const Bytes truncated(message.begin(), message.begin() + static_cast<std::ptrdiff_t>(size));
      decode_everything(truncated);
      ++cases;
    }
  }
  EXPECT_GT(cases, 1500U);
}

TEST(ToolBus, GripperFramesAreTheManualsAndRepliesAreChecked) {
  // UFACTORY xArm Gripper user manual §3.4.3: set position 0x0700 (two registers) through 124.
  const std::array<std::uint16_t, 2> target{0x0000, 0x0258};
  EXPECT_EQ(tool_modbus_write_request(kGripperId, 0x0700, target).params,
            (Bytes{0x09, 0x08, 0x10, 0x07, 0x00, 0x00, 0x02, 0x04, 0x00, 0x00, 0x02, 0x58}));
  EXPECT_EQ(tool_modbus_read_request(kGripperId, 0x0702, 2).params, (Bytes{0x09, 0x08, 0x03, 0x07, 0x02, 0x00, 0x02}));
  const auto values =
      parse_tool_modbus_read_reply(Bytes{0x09, 0x08, 0x03, 0x04, 0x00, 0x00, 0x02, 0x58}, kGripperId, 2);
  ASSERT_TRUE(values) << values.error().message;
  EXPECT_EQ(values.value(), (std::vector<std::uint16_t>{0, 600}));
  const auto exception = parse_tool_modbus_read_reply(Bytes{0x09, 0x08, 0x83, 0x02}, kGripperId, 2);
  ASSERT_FALSE(exception);
  EXPECT_EQ(exception.error().message, "tool device 8 answered Modbus exception 2 to function 3");
  const auto other =
      parse_tool_modbus_write_reply(Bytes{0x09, 0x08, 0x10, 0x01, 0x00, 0x00, 0x01}, kGripperId, 0x0700, 2);
  ASSERT_FALSE(other);
  EXPECT_EQ(other.error().message, "tool_modbus_rtu write reply echoes 1 registers at 0x0100, expected 2 at 0x0700");
  const auto parsed = parse_tool_modbus_request(tool_modbus_write_request(kGripperId, 0x0700, target).params);
  ASSERT_TRUE(parsed);
  EXPECT_EQ(parsed.value().values, (std::vector<std::uint16_t>{0, 600}));
  EXPECT_EQ(tool_register_read_request(kToolHostId, kToolBaudRateAddress).params, (Bytes{0x09, 0x0A, 0x0B}));
  EXPECT_EQ(parse_tool_register_value(Bytes{0, 0, 0, 11}).value(), 11);
}

TEST(Reports, RichPacketsCarryTheNormalFieldsThenTheModelLimitsAndServos) {
  Report report;
  report.state = kStateSleeping;
  report.error_code = 23;
  report.collision_sensitivity = 3;
  report.rich.device_type = 6;
  report.rich.axes = 6;
  report.rich.firmware = "2.3.0";
  report.rich.tcp.max_speed = 1.0;
  report.rich.joint.max_speed = 3.14;
  report.rich.servos[1] = ServoStatus{.state = 1, .error = 11};
  const Bytes packet = encode_report(report, ReportKind::kRich);
  ASSERT_EQ(packet.size(), 245U);
  EXPECT_EQ(packet[145], 6);
  EXPECT_EQ(packet[146], 6);
  EXPECT_EQ(packet[151], '2');
  EXPECT_EQ(packet[231], 1);
  EXPECT_EQ(packet[232], 11);
  const auto parsed = parse_report(packet, ReportKind::kRich);
  ASSERT_TRUE(parsed) << parsed.error().message;
  EXPECT_EQ(parsed.value().error_code, 23);
  EXPECT_EQ(parsed.value().rich.firmware, "2.3.0");
  EXPECT_NEAR(parsed.value().rich.tcp.max_speed, 1.0, 1e-6) << "mm/s on the wire";
  Bytes longer = packet;  // newer firmware appends fields
  longer.resize(587, 0);
  longer[2] = 0x02;
  longer[3] = 0x4B;
  EXPECT_TRUE(parse_report(longer, ReportKind::kRich));
  Bytes shorter(packet.begin(), packet.begin() + 145);
  shorter[3] = 145;
  const auto refused = parse_report(shorter, ReportKind::kRich);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().message, "rich report carries 145 bytes, expected at least 245");
}

TEST(Robustness, TruncatedReportsAndRepliesSayWhy) {
  const Bytes real = encode_report(sample_report(), ReportKind::kReal);
  for (std::size_t size = 0; size < real.size(); ++size) {
    EXPECT_FALSE(parse_report(ByteView(real).first(size), ReportKind::kReal).ok()) << size;
  }
  for (const ReportKind kind : {ReportKind::kNormal, ReportKind::kRealtime}) {
    const Bytes packet = encode_report(sample_report(), kind);
    for (std::size_t size = 0; size < packet.size(); ++size) {
      EXPECT_FALSE(parse_report(ByteView(packet).first(size), kind).ok()) << report_kind_name(kind) << " " << size;
    }
  }
  const Bytes joints = encode_joints(sample_joints());
  for (std::size_t size = 0; size < joints.size(); ++size) {
    EXPECT_FALSE(parse_joints(ByteView(joints).first(size)).ok()) << size;
    EXPECT_FALSE(parse_joint_params(44, ByteView(joints).first(size)).ok()) << size;
  }
  const Bytes serials = encode_robot_sn({.robot_sn = "XI1303", .control_box_sn = "AC1305"});
  for (std::size_t size = 0; size < serials.size(); ++size) {
    EXPECT_FALSE(parse_robot_sn(ByteView(serials).first(size)).ok()) << size;
  }
}

TEST(Robustness, RandomBytesNeverCrashADecoder) {
  std::mt19937 random(20240716);  // fixed: the same inputs on every run
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<std::size_t> length(0, 900);
  for (int round = 0; round < 3000; ++round) {
    Bytes data(length(random));
    for (std::uint8_t& value : data) value = static_cast<std::uint8_t>(byte(random));
    if (round % 3 == 0 && data.size() >= 4) {
      // A size field that matches, so the report parsers look past it.
      const auto size = static_cast<std::uint32_t>(data.size());
      data[0] = static_cast<std::uint8_t>(size >> 24);
      data[1] = static_cast<std::uint8_t>(size >> 16);
      data[2] = static_cast<std::uint8_t>(size >> 8);
      data[3] = static_cast<std::uint8_t>(size);
    }
    decode_everything(data);
  }
  // Random bytes at the report sizes exercise every field read.
  for (const std::size_t size : {87U, 133U, 135U, 145U, 784U, 804U}) {
    for (int round = 0; round < 50; ++round) {
      Bytes data(size);
      for (std::uint8_t& value : data) value = static_cast<std::uint8_t>(byte(random));
      data[0] = 0;
      data[1] = 0;
      data[2] = static_cast<std::uint8_t>(size >> 8);
      data[3] = static_cast<std::uint8_t>(size);
      decode_everything(data);
    }
  }
}

TEST(Robustness, FrameSplitterDeliversEveryFrameWhateverTheChunking) {
  std::mt19937 random(7);
  Bytes stream;
  for (std::uint16_t id = 1; id <= 60; ++id) {
    const Bytes frame = encode_frame(request_frame(move_joint_request({.joints_rad = sample_joints()}), id));
    const Bytes feedback = encode_frame(motion_feedback_frame({.transaction_id = id}));
    stream.insert(stream.end(), frame.begin(), frame.end());
    if (id % 5 == 0) stream.insert(stream.end(), feedback.begin(), feedback.end());
  }
  for (int round = 0; round < 30; ++round) {
    FrameSplitter splitter;
    std::vector<Frame> frames;
    for (std::size_t at = 0; at < stream.size();) {
      const std::size_t chunk =
          std::min(std::uniform_int_distribution<std::size_t>(1, 120)(random), stream.size() - at);
      splitter.append(ByteView(stream).subspan(at, chunk));
      at += chunk;
      for (Frame& frame : drain(splitter)) frames.push_back(std::move(frame));
    }
    ASSERT_EQ(frames.size(), 72U);
    EXPECT_EQ(frames.back().transaction_id, 60);
    EXPECT_TRUE(is_motion_feedback(frames.back()));
    EXPECT_EQ(splitter.buffered(), 0U);
  }
}

TEST(Robustness, ReportSplitterDeliversEveryPacketWhateverTheChunking) {
  std::mt19937 random(9);
  Bytes stream;
  for (int i = 0; i < 20; ++i) {
    Report report = sample_report();
    report.cmd_num = static_cast<std::uint16_t>(i);
    const Bytes packet = encode_report(report, i % 2 == 0 ? ReportKind::kRealtime : ReportKind::kReal);
    stream.insert(stream.end(), packet.begin(), packet.end());
  }
  for (int round = 0; round < 20; ++round) {
    ReportSplitter splitter;
    std::vector<Bytes> packets;
    for (std::size_t at = 0; at < stream.size();) {
      const std::size_t chunk =
          std::min(std::uniform_int_distribution<std::size_t>(1, 900)(random), stream.size() - at);
      splitter.append(ByteView(stream).subspan(at, chunk));
      at += chunk;
      for (Bytes& packet : drain(splitter)) packets.push_back(std::move(packet));
    }
    ASSERT_EQ(packets.size(), 20U);
    const auto last = parse_report(packets.back(), ReportKind::kReal);
    ASSERT_TRUE(last.ok()) << error_of(last);
    EXPECT_EQ(last.value().cmd_num, 19);
  }
}

TEST(Robustness, SplittersSurviveGarbage) {
  std::mt19937 random(11);
  std::uniform_int_distribution<int> byte(0, 255);
  FrameSplitter frames;
  ReportSplitter reports;
  std::size_t delivered = 0;
  std::size_t errors = 0;
  for (int round = 0; round < 3000; ++round) {
    Bytes chunk(std::uniform_int_distribution<std::size_t>(0, 64)(random));
    for (std::uint8_t& value : chunk) value = static_cast<std::uint8_t>(byte(random));
    frames.append(chunk);
    reports.append(chunk);
    while (true) {
      auto next = frames.next();
      if (!next.ok()) {
        ++errors;
        frames.clear();
        break;
      }
      if (!next.value()) break;
      EXPECT_LE(kHeaderBytes + 1 + next.value()->body.size(), kMaxFrameBytes);
      ++delivered;
    }
    while (true) {
      auto next = reports.next();
      if (!next.ok()) {
        ++errors;
        reports.clear();
        break;
      }
      if (!next.value()) break;
      EXPECT_GE(next.value()->size(), 8U);
      EXPECT_LE(next.value()->size(), kMaxReportBytes);
      ++delivered;
    }
  }
  EXPECT_GT(delivered + errors, 0U);
}

}  // namespace
}  // namespace robotd::xarm
