// The PiPER CAN codec against the byte-level spec (../shared/protocols/piper_can.md): the SDK's
// worked examples byte for byte, decoding of hand-built feedback, round trips of every frame,
// saturation, and malformed input.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <iomanip>
#include <limits>
#include <new>
#include <numbers>
#include <optional>
#include <ostream>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include <gtest/gtest.h>

#include "codec/piper_frames.hpp"
#include "thread_allocations.hpp"

namespace robotd::piper {
namespace {

using Bytes = std::vector<std::uint8_t>;

constexpr double kPi = std::numbers::pi;
constexpr double kMilliDegree = kPi / 180000.0;  // one count of a joint angle or pose angle, in rad

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
  EXPECT_FALSE(message.extended);
  EXPECT_FALSE(message.fd);
  EXPECT_EQ(message.length, 8);
  return Wire{message.id, Bytes(message.data.begin(), message.data.begin() + message.length)};
}

CanMessage message_of(std::uint32_t id, const Bytes& bytes) { return transport::classic_frame(id, bytes); }

template <typename T>
T decoded(const CanMessage& message, const CodecOptions& options = {}) {
  const std::optional<Frame> frame = decode(message, options);
  if (!frame) {
    ADD_FAILURE() << "no frame in " << wire_of(message);
    return T{};
  }
  if (!std::holds_alternative<T>(*frame)) {
    ADD_FAILURE() << "another frame type (index " << frame->index() << ") in " << wire_of(message);
    return T{};
  }
  return std::get<T>(*frame);
}

template <typename T>
T round_trip(const T& frame, const CodecOptions& options = {}) {
  return decoded<T>(encode(frame, options), options);
}

CodecOptions torque12() { return CodecOptions{.mit_layout = MitLayout::kTorque12}; }

// --- 0x150 / 0x151: motion and mode control (§4.1, §4.2) ----------------------------------------

TEST(PiperCodecEncode, EmergencyStopAndResume) {
  EXPECT_EQ(wire_of(encode(MotionControl{.emergency_stop = EmergencyStop::kStop})),
            (Wire{0x150, {0x01, 0, 0, 0, 0, 0, 0, 0}}));
  EXPECT_EQ(wire_of(encode(MotionControl{.emergency_stop = EmergencyStop::kResume})),
            (Wire{0x150, {0x02, 0, 0, 0, 0, 0, 0, 0}}));
}

TEST(PiperCodecEncode, MotionControlPacksTrajectoryFieldsBigEndian) {
  const MotionControl frame{
      .track_ctrl = 0x07, .drag_teach_ctrl = 0x03, .trajectory_index = 9, .name_index = 0x1234, .crc16 = 0xABCD};
  EXPECT_EQ(wire_of(encode(frame)), (Wire{0x150, {0x00, 0x07, 0x03, 0x09, 0x12, 0x34, 0xAB, 0xCD}}));
}

TEST(PiperCodecEncode, ModeControlCommonPayloads) {
  const auto mode = [](MoveMode move_mode, std::uint8_t speed, bool mit = false) {
    return wire_of(encode(ModeControl{.move_mode = move_mode, .speed_percent = speed, .mit = mit}));
  };
  EXPECT_EQ(mode(MoveMode::kJ, 100), (Wire{0x151, {0x01, 0x01, 0x64, 0x00, 0, 0, 0, 0}}));
  EXPECT_EQ(mode(MoveMode::kP, 100), (Wire{0x151, {0x01, 0x00, 0x64, 0x00, 0, 0, 0, 0}}));
  EXPECT_EQ(mode(MoveMode::kL, 50), (Wire{0x151, {0x01, 0x02, 0x32, 0x00, 0, 0, 0, 0}}));
  EXPECT_EQ(mode(MoveMode::kC, 30), (Wire{0x151, {0x01, 0x03, 0x1E, 0x00, 0, 0, 0, 0}}));
  EXPECT_EQ(mode(MoveMode::kMit, 0, true), (Wire{0x151, {0x01, 0x04, 0x00, 0xAD, 0, 0, 0, 0}}));
  EXPECT_EQ(mode(MoveMode::kJ, 100, true), (Wire{0x151, {0x01, 0x01, 0x64, 0xAD, 0, 0, 0, 0}}));
}

TEST(PiperCodecEncode, ModeControlSetsInstallationPosition) {
  const ModeControl frame{.move_mode = MoveMode::kJ, .speed_percent = 0, .installation = 1};
  EXPECT_EQ(wire_of(encode(frame)), (Wire{0x151, {0x01, 0x01, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00}}));
}

TEST(PiperCodecEncode, MitModeCodeIs06WithTheTorque12Layout) {
  const ModeControl frame{.move_mode = MoveMode::kMit, .speed_percent = 0, .mit = true};
  EXPECT_EQ(wire_of(encode(frame, torque12())), (Wire{0x151, {0x01, 0x06, 0x00, 0xAD, 0, 0, 0, 0}}));
}

// MIT is 0x04 up to S-V1.8-7 (SDK 0.6.1 reads 0x06 as unknown) and 0x06 from S-V1.8-8.
TEST(PiperCodecDecode, MitModeCodeFollowsTheLayout) {
  const auto move_mode = [](std::uint8_t code, const CodecOptions& options) {
    return decoded<ModeControl>(message_of(0x151, {0x01, code, 0x00, 0xAD, 0, 0, 0, 0}), options).move_mode;
  };
  EXPECT_EQ(move_mode(0x04, {}), MoveMode::kMit);
  EXPECT_EQ(move_mode(0x06, {}), MoveMode::kUnknown);
  EXPECT_EQ(move_mode(0x06, torque12()), MoveMode::kMit);
  EXPECT_EQ(move_mode(0x04, torque12()), MoveMode::kUnknown);
  EXPECT_EQ(move_mode(0x07, {}), MoveMode::kUnknown);
  EXPECT_STREQ(move_mode_text(MoveMode::kUnknown), "unknown");
  EXPECT_EQ(decoded<ModeControl>(message_of(0x151, {0x01, 0x05, 0, 0, 0, 0, 0, 0})).move_mode, MoveMode::kCpv);
}

TEST(PiperCodecDecode, ModeControlFromAMasterArm) {
  const auto frame = decoded<ModeControl>(message_of(0x151, {0x01, 0x01, 0x64, 0xAD, 0x05, 0x02, 0, 0}));
  EXPECT_EQ(frame.ctrl_mode, ControlMode::kCanCommand);
  EXPECT_EQ(frame.move_mode, MoveMode::kJ);
  EXPECT_EQ(frame.speed_percent, 100);
  EXPECT_TRUE(frame.mit);
  EXPECT_EQ(frame.residence_time_s, 5);
  EXPECT_EQ(frame.installation, 2);
}

// --- 0x152–0x157: Cartesian and joint targets (§4.3, §4.4) ---------------------------------------

TEST(PiperCodecEncode, JointAngleIsMilliDegreesBigEndian) {
  EXPECT_EQ(wire_of(encode(JointTargetPair{.pair = 0, .first_rad = 0.2, .second_rad = -0.2})),
            (Wire{0x155, {0x00, 0x00, 0x2C, 0xC3, 0xFF, 0xFF, 0xD3, 0x3D}}));
}

TEST(PiperCodecEncode, JointTargetsGoOutAsThreePairsInBusOrder) {
  const auto frames = encode_joint_targets({0.2, -0.2, 0.0, 0.2, -0.2, 0.0});
  EXPECT_EQ(wire_of(frames[0]), (Wire{0x155, {0x00, 0x00, 0x2C, 0xC3, 0xFF, 0xFF, 0xD3, 0x3D}}));
  EXPECT_EQ(wire_of(frames[1]), (Wire{0x156, {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x2C, 0xC3}}));
  EXPECT_EQ(wire_of(frames[2]), (Wire{0x157, {0xFF, 0xFF, 0xD3, 0x3D, 0x00, 0x00, 0x00, 0x00}}));
  const auto feedback = encode_joint_feedback({0.2, -0.2, 0.0, 0.2, -0.2, 0.0});
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(feedback[i].id, 0x2A5 + i);
    EXPECT_EQ(wire_of(feedback[i]).bytes, wire_of(frames[i]).bytes);
  }
}

TEST(PiperCodecEncode, EndPoseIsMicrometresAndMilliDegrees) {
  const CartesianPose pose{.x_m = 0.1, .y_m = -0.05, .z_m = 0.2, .rx_rad = kPi / 2, .ry_rad = -kPi / 4, .rz_rad = kPi};
  const auto frames = encode_end_pose_target(pose);
  EXPECT_EQ(wire_of(frames[0]), (Wire{0x152, {0x00, 0x01, 0x86, 0xA0, 0xFF, 0xFF, 0x3C, 0xB0}}));  // 100000, −50000
  EXPECT_EQ(wire_of(frames[1]), (Wire{0x153, {0x00, 0x03, 0x0D, 0x40, 0x00, 0x01, 0x5F, 0x90}}));  // 200000, 90000
  EXPECT_EQ(wire_of(frames[2]), (Wire{0x154, {0xFF, 0xFF, 0x50, 0x38, 0x00, 0x02, 0xBF, 0x20}}));  // −45000, 180000
  const auto feedback = encode_end_pose_feedback(pose);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(feedback[i].id, 0x2A2 + i);
    EXPECT_EQ(wire_of(feedback[i]).bytes, wire_of(frames[i]).bytes);
  }
}

TEST(PiperCodecEncode, MoveCPointIndex) {
  EXPECT_EQ(wire_of(encode(MoveCPoint{.index = 2})), (Wire{0x158, {0x02, 0, 0, 0, 0, 0, 0, 0}}));
}

// --- 0x159: gripper control (§4.6) ------------------------------------------------------------------

TEST(PiperCodecEncode, GripperExamples) {
  EXPECT_EQ(wire_of(encode(GripperControl{.stroke_m = 0, .effort_nm = 1.0, .enable = GripperEnable::kEnable})),
            (Wire{0x159, {0x00, 0x00, 0x00, 0x00, 0x03, 0xE8, 0x01, 0x00}}));
  EXPECT_EQ(wire_of(encode(GripperControl{.stroke_m = 0.05, .effort_nm = 1.0, .enable = GripperEnable::kEnable})),
            (Wire{0x159, {0x00, 0x00, 0xC3, 0x50, 0x03, 0xE8, 0x01, 0x00}}));
  EXPECT_EQ(wire_of(encode(GripperControl{.effort_nm = 1.0, .enable = GripperEnable::kDisable, .set_zero = true})),
            (Wire{0x159, {0x00, 0x00, 0x00, 0x00, 0x03, 0xE8, 0x00, 0xAE}}));
}

TEST(PiperCodecDecode, GripperControlFromAMasterArm) {
  const auto frame = decoded<GripperControl>(message_of(0x159, {0x00, 0x00, 0xC3, 0x50, 0x03, 0xE8, 0x03, 0xAE}));
  EXPECT_NEAR(frame.stroke_m, 0.05, 1e-12);
  EXPECT_NEAR(frame.effort_nm, 1.0, 1e-12);
  EXPECT_EQ(frame.enable, GripperEnable::kEnableClearError);
  EXPECT_TRUE(frame.set_zero);
}

// --- 0x15A–0x15F: MIT (§4.7) -------------------------------------------------------------------------

struct MitVector {
  MitControl input;
  Bytes bytes;
};

TEST(PiperCodecMit, WorkedVectorsOfTheEightBitLayout) {
  const std::vector<MitVector> vectors{
      {{.position_rad = 0.5, .kp = 10, .kd = 0.8}, {0x85, 0x1E, 0x7F, 0xF0, 0x51, 0x94, 0x77, 0xF6}},
      {{.position_rad = 0.0, .kp = 10, .kd = 0.8}, {0x7F, 0xFF, 0x7F, 0xF0, 0x51, 0x94, 0x77, 0xFD}},
      {{.position_rad = -0.5, .kp = 10, .kd = 0.8}, {0x7A, 0xE0, 0x7F, 0xF0, 0x51, 0x94, 0x77, 0xF7}},
      {{}, {0x7F, 0xFF, 0x7F, 0xF0, 0x00, 0x7F, 0xF7, 0xF7}},
      {{.torque = 1.0}, {0x7F, 0xFF, 0x7F, 0xF0, 0x00, 0x7F, 0xF8, 0xF8}},
  };
  for (const MitVector& vector : vectors) {
    for (int joint = 1; joint <= kArmJoints; ++joint) {
      MitControl input = vector.input;
      input.joint = joint;
      EXPECT_EQ(wire_of(encode(input)), (Wire{0x159 + static_cast<std::uint32_t>(joint), vector.bytes}));
    }
  }
}

TEST(PiperCodecMit, WorkedVectorsDecodeWithinOneStep) {
  const auto frame = decoded<MitControl>(message_of(0x15F, {0x85, 0x1E, 0x7F, 0xF0, 0x51, 0x94, 0x77, 0xF6}));
  EXPECT_EQ(frame.joint, 6);
  EXPECT_NEAR(frame.position_rad, 0.5, 25.0 / 65535);
  EXPECT_NEAR(frame.velocity_rad_s, 0.0, 90.0 / 4095);
  EXPECT_NEAR(frame.kp, 10.0, 500.0 / 4095);
  EXPECT_NEAR(frame.kd, 0.8, 10.0 / 4095);
  EXPECT_NEAR(frame.torque, 0.0, 16.0 / 255);
  // The decoded values are exactly the quantised integers mapped back.
  EXPECT_DOUBLE_EQ(frame.position_rad, 34078 * 25.0 / 65535 - 12.5);
  EXPECT_DOUBLE_EQ(frame.kp, 81 * 500.0 / 4095);
}

TEST(PiperCodecMit, Torque12LayoutHasTwelveBitTorqueAndNoCrc) {
  // t = 1 N·m over ±16 in 12 bits: (1 + 16)·4095/32 = 2175.47 → 2175 = 0x87F; kd 0 → 2047 = 0x7FF.
  EXPECT_EQ(wire_of(encode(MitControl{.joint = 1, .torque = 1.0}, torque12())),
            (Wire{0x15A, {0x7F, 0xFF, 0x7F, 0xF0, 0x00, 0x7F, 0xF8, 0x7F}}));
  // p 0.5, kp 10, kd 0.8 as in the 8-bit vectors; t 0 → 2047 = 0x7FF.
  EXPECT_EQ(wire_of(encode(MitControl{.joint = 2, .position_rad = 0.5, .kp = 10, .kd = 0.8}, torque12())),
            (Wire{0x15B, {0x85, 0x1E, 0x7F, 0xF0, 0x51, 0x94, 0x77, 0xFF}}));
  EXPECT_EQ(wire_of(encode(MitControl{.torque = -16.0}, torque12())).bytes[6] & 0x0F, 0x0);
  EXPECT_EQ(wire_of(encode(MitControl{.torque = -16.0}, torque12())).bytes[7], 0x00);
  EXPECT_EQ(wire_of(encode(MitControl{.torque = 16.0}, torque12())).bytes[6] & 0x0F, 0xF);
  EXPECT_EQ(wire_of(encode(MitControl{.torque = 16.0}, torque12())).bytes[7], 0xFF);
}

TEST(PiperCodecMit, Torque12DecodesTwelveBitTorque) {
  const auto frame =
      decoded<MitControl>(message_of(0x15A, {0x7F, 0xFF, 0x7F, 0xF0, 0x00, 0x7F, 0xF8, 0x7F}), torque12());
  EXPECT_DOUBLE_EQ(frame.torque, 2175 * 32.0 / 4095 - 16.0);
  EXPECT_NEAR(frame.torque, 1.0, 32.0 / 4095);
}

TEST(PiperCodecMit, CrcMismatchIsRejected) {
  Bytes bytes{0x85, 0x1E, 0x7F, 0xF0, 0x51, 0x94, 0x77, 0xF6};
  ASSERT_TRUE(decode(message_of(0x15A, bytes)).has_value());
  bytes[7] = 0xF7;  // CRC nibble off by one
  EXPECT_FALSE(decode(message_of(0x15A, bytes)).has_value());
  bytes = {0x85, 0x1F, 0x7F, 0xF0, 0x51, 0x94, 0x77, 0xF6};  // a flipped data bit
  EXPECT_FALSE(decode(message_of(0x15A, bytes)).has_value());
  // The 12-bit layout has no CRC: the low nibble of byte 7 is torque.
  EXPECT_TRUE(decode(message_of(0x15A, bytes), torque12()).has_value());
}

TEST(PiperCodecMit, OutOfRangeValuesSaturate) {
  const auto bytes = [](const MitControl& frame, const CodecOptions& options = {}) {
    return wire_of(encode(frame, options)).bytes;
  };
  EXPECT_EQ(bytes(MitControl{.kp = -1}), bytes(MitControl{.kp = 0}));
  EXPECT_EQ(round_trip(MitControl{.kp = -1}).kp, 0.0);
  EXPECT_EQ(round_trip(MitControl{.kp = 1e6}).kp, 500.0);
  EXPECT_EQ(round_trip(MitControl{.position_rad = 100}).position_rad, 12.5);
  EXPECT_EQ(round_trip(MitControl{.position_rad = -100}).position_rad, -12.5);
  EXPECT_EQ(round_trip(MitControl{.velocity_rad_s = 1e9}).velocity_rad_s, 45.0);
  EXPECT_EQ(round_trip(MitControl{.kd = -7}).kd, -5.0);
  EXPECT_EQ(round_trip(MitControl{.torque = 9}).torque, 8.0);
  EXPECT_EQ(round_trip(MitControl{.torque = -1e9}).torque, -8.0);
  EXPECT_EQ(round_trip(MitControl{.torque = 20}, torque12()).torque, 16.0);
  EXPECT_EQ(round_trip(MitControl{.torque = -20}, torque12()).torque, -16.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(bytes(MitControl{.position_rad = nan, .kp = nan, .torque = nan}), bytes(MitControl{}));
}

TEST(PiperCodecMit, JointOutsideOneToSixIsRefused) {  // as the SDK's JointMitCtrl refuses it
  EXPECT_THROW((void)encode(MitControl{.joint = 0}), std::invalid_argument);
  try {
    (void)encode(MitControl{.joint = 7});
    ADD_FAILURE() << "MIT joint 7 was encoded";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("MIT joint 7"), std::string::npos) << e.what();
  }
  EXPECT_EQ(encode(MitControl{.joint = 6}).id, 0x15FU);
}

// --- 0x470–0x47E, 0x4AF: configuration (§6) ---------------------------------------------------------

TEST(PiperCodecEncode, MasterSlaveConfig) {
  EXPECT_EQ(wire_of(encode(MasterSlaveConfig{.linkage = 0xFC})), (Wire{0x470, {0xFC, 0, 0, 0, 0, 0, 0, 0}}));
  const MasterSlaveConfig master{
      .linkage = 0xFA, .feedback_offset = 0x10, .control_offset = 0x20, .linkage_offset = 0x10};
  EXPECT_EQ(wire_of(encode(master)), (Wire{0x470, {0xFA, 0x10, 0x20, 0x10, 0, 0, 0, 0}}));
}

TEST(PiperCodecEncode, EnableAndDisableAllMotors) {
  EXPECT_EQ(wire_of(encode(MotorEnable{.motor = kAllJoints, .enable = true})),
            (Wire{0x471, {0x07, 0x02, 0, 0, 0, 0, 0, 0}}));
  EXPECT_EQ(wire_of(encode(MotorEnable{.motor = kAllJoints, .enable = false})),
            (Wire{0x471, {0x07, 0x01, 0, 0, 0, 0, 0, 0}}));
}

TEST(PiperCodecEncode, JointLimitQueries) {
  EXPECT_EQ(wire_of(encode(JointLimitQuery{.joint = 3})), (Wire{0x472, {0x03, 0x01, 0, 0, 0, 0, 0, 0}}));
  EXPECT_EQ(wire_of(encode(JointLimitQuery{.joint = 3, .acceleration = true})),
            (Wire{0x472, {0x03, 0x02, 0, 0, 0, 0, 0, 0}}));
}

TEST(PiperCodecEncode, JointLimitSetSpeedOnly) {
  for (std::uint8_t joint = 1; joint <= kArmJoints; ++joint) {
    EXPECT_EQ(wire_of(encode(JointLimitSet{.joint = joint, .max_speed_rad_s = 3.0})),
              (Wire{0x474, {joint, 0x7F, 0xFF, 0x7F, 0xFF, 0x0B, 0xB8, 0x00}}));
  }
}

TEST(PiperCodecEncode, JointLimitSetAnglesAreDeciDegrees) {
  // SDK demo for J1: +1500 / −1500 (±150°); speed in the pyAgxArm unit (0.01 rad/s): 3 rad/s → 300.
  const JointLimitSet frame{
      .joint = 1, .max_angle_rad = 150 * kPi / 180, .min_angle_rad = -150 * kPi / 180, .max_speed_rad_s = 3.0};
  EXPECT_EQ(wire_of(encode(frame, CodecOptions{.max_speed_unit_rad_s = 0.01})),
            (Wire{0x474, {0x01, 0x05, 0xDC, 0xFA, 0x24, 0x01, 0x2C, 0x00}}));
}

// Present values use the whole field and saturate at its ends, as the SDK sends them
// (EndSpdAndAccParamSet 65535 → FF FF); only an absent value is the 0x7FFF sentinel.
TEST(PiperCodecEncode, PresentLimitsSaturateAtTheFieldEnds) {
  const auto bytes =
      wire_of(encode(JointLimitSet{.joint = 2, .max_angle_rad = 1e6, .min_angle_rad = -1e6, .max_speed_rad_s = 1e6}))
          .bytes;
  EXPECT_EQ(bytes, (Bytes{0x02, 0x7F, 0xFF, 0x80, 0x00, 0xFF, 0xFF, 0x00}));
  EXPECT_EQ(wire_of(encode(JointLimitSet{.joint = 2, .max_speed_rad_s = -1.0})).bytes[5], 0x00);
  EXPECT_EQ(wire_of(encode(EndVelAccSet{{.max_linear_velocity_m_s = 1e3}})).bytes,
            (Bytes{0xFF, 0xFF, 0x7F, 0xFF, 0x7F, 0xFF, 0x7F, 0xFF}));
  EXPECT_EQ(wire_of(encode(EndVelAccSet{{.max_linear_velocity_m_s = 65.535}})).bytes[0], 0xFF);
  EXPECT_EQ(wire_of(encode(JointConfig{.joint = 1, .apply_max_acc = true, .max_acc_rad_s2 = 1e6})).bytes,
            (Bytes{0x01, 0x00, 0xAE, 0xFF, 0xFF, 0x00, 0x00, 0x00}));
}

// The acceleration goes out whatever the flag says, as the SDK sends its max_joint_acc (500 by
// default) with acc_param_is_effective off.
TEST(PiperCodecEncode, JointConfigFields) {
  EXPECT_EQ(wire_of(encode(JointConfig{.joint = 3, .set_zero = true})),
            (Wire{0x475, {0x03, 0xAE, 0x00, 0x01, 0xF4, 0x00, 0x00, 0x00}}));
  EXPECT_EQ(wire_of(encode(JointConfig{.apply_max_acc = true, .max_acc_rad_s2 = 5.0})),  // 0.01 rad/s² → 500
            (Wire{0x475, {0x07, 0x00, 0xAE, 0x01, 0xF4, 0x00, 0x00, 0x00}}));
  EXPECT_EQ(wire_of(encode(JointConfig{.joint = 1, .max_acc_rad_s2 = 3.0})),
            (Wire{0x475, {0x01, 0x00, 0x00, 0x01, 0x2C, 0x00, 0x00, 0x00}}));
  EXPECT_EQ(wire_of(encode(JointConfig{.joint = 7, .clear_error = true})),
            (Wire{0x475, {0x07, 0x00, 0x00, 0x01, 0xF4, 0xAE, 0x00, 0x00}}));
}

TEST(PiperCodecEncode, ParamEnquiryExamples) {
  EXPECT_EQ(wire_of(encode(ParamEnquiry{.query = 2})), (Wire{0x477, {0x02, 0x00, 0x00, 0x00, 0x03, 0, 0, 0}}));
  EXPECT_EQ(wire_of(encode(ParamEnquiry{.query = 4})), (Wire{0x477, {0x04, 0x00, 0x00, 0x00, 0x03, 0, 0, 0}}));
  EXPECT_EQ(wire_of(encode(ParamEnquiry{.setting = 1, .feedback_48x = 2, .payload = 2})),
            (Wire{0x477, {0x00, 0x01, 0x02, 0xAE, 0x02, 0, 0, 0}}));
}

TEST(PiperCodecEncode, EndVelAccSetUnits) {
  const EndVelAccSet frame{{.max_linear_velocity_m_s = 1.0, .max_angular_acceleration_rad_s2 = 3.0}};
  EXPECT_EQ(wire_of(encode(frame)), (Wire{0x479, {0x03, 0xE8, 0x7F, 0xFF, 0x7F, 0xFF, 0x0B, 0xB8}}));
}

TEST(PiperCodecEncode, CrashProtectionLevels) {
  EXPECT_EQ(wire_of(encode(CrashProtectionSet{.levels = {1, 2, 3, 4, 5, 8}})), (Wire{0x47A, {1, 2, 3, 4, 5, 8, 0, 0}}));
}

TEST(PiperCodecEncode, GripperParamSetExample) {
  const GripperParamSet frame{{.teaching_range_percent = 100, .max_range_mm = 70, .teaching_friction = 1}};
  EXPECT_EQ(wire_of(encode(frame)), (Wire{0x47D, {0x64, 0x46, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00}}));
}

TEST(PiperCodecEncode, FirmwareRequest) {
  EXPECT_EQ(wire_of(firmware_request()), (Wire{0x4AF, {0x01, 0, 0, 0, 0, 0, 0, 0}}));
  EXPECT_TRUE(is_firmware_request(firmware_request()));
  EXPECT_FALSE(is_firmware_request(message_of(0x4AF, {'H', '-', 'V', '1', '.', '2', '-', '1'})));
  EXPECT_FALSE(is_firmware_request(message_of(0x4AE, {0x01, 0, 0, 0, 0, 0, 0, 0})));
  const auto chunk = decoded<FirmwareChunk>(firmware_request());
  EXPECT_EQ(chunk.length, 8);
  EXPECT_EQ(chunk.text[0], '\x01');
}

// --- feedback (§5) --------------------------------------------------------------------------------

TEST(PiperCodecDecode, ArmStatus) {
  const auto status = decoded<ArmStatus>(message_of(0x2A1, {0x01, 0x07, 0x04, 0x03, 0x01, 0x05, 0x21, 0x02}));
  EXPECT_EQ(status.ctrl_mode, ControlMode::kCanCommand);
  EXPECT_EQ(status.arm_status, 0x07);
  EXPECT_STREQ(arm_status_text(status.arm_status), "collision");
  EXPECT_EQ(status.mode_feed, MoveMode::kMit);
  EXPECT_EQ(status.teach_status, 0x03);
  EXPECT_EQ(status.motion_status, 1);
  EXPECT_EQ(status.trajectory_index, 5);
  EXPECT_EQ(status.angle_limit_bits, 0x21);  // J1 and J6 beyond their limits
  EXPECT_EQ(status.comm_error_bits, 0x02);   // J2 silent
  EXPECT_EQ(decoded<ArmStatus>(message_of(0x2A1, {0x06, 0, 0x06, 0, 0, 0, 0, 0}), torque12()).mode_feed,
            MoveMode::kMit);
  EXPECT_EQ(decoded<ArmStatus>(message_of(0x2A1, {0x06, 0, 0x06, 0, 0, 0, 0, 0})).mode_feed, MoveMode::kUnknown);
}

TEST(PiperCodecDecode, ArmStatusEncodesMitPerLayout) {
  const ArmStatus status{.ctrl_mode = ControlMode::kCanCommand, .mode_feed = MoveMode::kMit};
  EXPECT_EQ(wire_of(encode(status)).bytes[2], 0x04);
  EXPECT_EQ(wire_of(encode(status, torque12())).bytes[2], 0x06);
}

TEST(PiperCodecDecode, EndPoseFeedback) {
  const auto part = decoded<EndPoseFeedbackPart>(message_of(0x2A3, {0x00, 0x03, 0x0D, 0x40, 0xFF, 0xFE, 0xA0, 0x70}));
  EXPECT_EQ(part.part, 1);
  EXPECT_NEAR(part.first, 0.2, 1e-12);        // z, 200 000 µm
  EXPECT_NEAR(part.second, -kPi / 2, 1e-12);  // rx, −90 000 m°
}

TEST(PiperCodecDecode, JointFeedback) {
  const auto pair = decoded<JointFeedbackPair>(message_of(0x2A6, {0xFF, 0xFF, 0xD3, 0x3D, 0x00, 0x01, 0x5F, 0x90}));
  EXPECT_EQ(pair.pair, 1);
  EXPECT_NEAR(pair.first_rad, -0.2, kMilliDegree / 2);
  EXPECT_NEAR(pair.second_rad, kPi / 2, 1e-12);
}

TEST(PiperCodecDecode, GripperFeedback) {
  const auto gripper = decoded<GripperFeedback>(message_of(0x2A8, {0x00, 0x00, 0xC3, 0x50, 0xFC, 0x18, 0xC1, 0x01}));
  EXPECT_NEAR(gripper.stroke_m, 0.05, 1e-12);
  EXPECT_NEAR(gripper.effort_nm, -1.0, 1e-12);  // int16 −1000
  EXPECT_EQ(gripper.status_bits, 0xC1);         // homed, enabled, under-voltage
  EXPECT_EQ(gripper.reserved, 0x01);
  EXPECT_EQ(gripper_status_text(gripper.status_bits), "under-voltage");
}

TEST(PiperCodecDecode, HighSpeedInfo) {
  const CanMessage message = message_of(0x253, {0xFC, 0x18, 0x03, 0xE8, 0xFF, 0xFF, 0xFF, 0x9C});
  const auto info = decoded<HighSpeedInfo>(message);
  EXPECT_EQ(info.joint, 3);
  EXPECT_NEAR(info.speed_rad_s, -1.0, 1e-12);
  EXPECT_NEAR(info.current_a, 1.0, 1e-12);
  EXPECT_NEAR(info.position_rad, -0.1, 1e-12);  // −100 in the default 0.001 rad
  EXPECT_NEAR(decoded<HighSpeedInfo>(message, CodecOptions{.motor_position_unit_rad = 1.0}).position_rad, -100, 1e-12);
}

TEST(PiperCodecDecode, LowSpeedInfoWithEnableBit) {
  const auto info = decoded<LowSpeedInfo>(message_of(0x265, {0x01, 0xF4, 0xFF, 0xF6, 0xE2, 0x41, 0x01, 0x2C}));
  EXPECT_EQ(info.joint, 5);
  EXPECT_NEAR(info.voltage_v, 50.0, 1e-12);
  EXPECT_EQ(info.driver_temperature_c, -10);
  EXPECT_EQ(info.motor_temperature_c, -30);
  EXPECT_EQ(info.status_bits, 0x41);
  EXPECT_NE(info.status_bits & 0x40, 0);  // enabled
  EXPECT_EQ(driver_status_text(info.status_bits), "under-voltage");
  EXPECT_NEAR(info.bus_current_a, 0.3, 1e-12);
}

TEST(PiperCodecDecode, JointLimitReply) {
  const auto j2 = decoded<JointLimitReply>(message_of(0x473, {0x02, 0x07, 0x08, 0x00, 0x00, 0x0B, 0xB8, 0x00}));
  EXPECT_EQ(j2.joint, 2);
  EXPECT_NEAR(j2.max_angle_rad, kPi, 1e-12);  // 1800 × 0.1°
  EXPECT_EQ(j2.min_angle_rad, 0.0);
  EXPECT_NEAR(j2.max_speed_rad_s, 3.0, 1e-12);  // 3000 × 0.001 rad/s
  const CanMessage j3 = message_of(0x473, {0x03, 0x00, 0x00, 0xF9, 0x5C, 0x01, 0x2C, 0x00});
  EXPECT_NEAR(decoded<JointLimitReply>(j3).min_angle_rad, -170 * kPi / 180, 1e-12);
  EXPECT_NEAR(decoded<JointLimitReply>(j3, CodecOptions{.max_speed_unit_rad_s = 0.01}).max_speed_rad_s, 3.0, 1e-12);
}

TEST(PiperCodecDecode, JointLimitSetWithUnchangedFields) {
  const auto frame = decoded<JointLimitSet>(message_of(0x474, {0x04, 0x7F, 0xFF, 0x7F, 0xFF, 0x0B, 0xB8, 0x00}));
  EXPECT_EQ(frame.joint, 4);
  EXPECT_FALSE(frame.max_angle_rad.has_value());
  EXPECT_FALSE(frame.min_angle_rad.has_value());
  ASSERT_TRUE(frame.max_speed_rad_s.has_value());
  EXPECT_NEAR(*frame.max_speed_rad_s, 3.0, 1e-12);
}

TEST(PiperCodecDecode, SetAcks) {
  const auto zero = decoded<SetAck>(message_of(0x476, {0x75, 0x01, 0x00, 0, 0, 0, 0, 0}));
  EXPECT_EQ(zero.command, 0x75);
  EXPECT_TRUE(zero.zero_set);
  const auto point = decoded<SetAck>(message_of(0x476, {0x50, 0x00, 0x07, 0, 0, 0, 0, 0}));
  EXPECT_EQ(point.command, 0x50);
  EXPECT_FALSE(point.zero_set);
  EXPECT_EQ(point.trajectory_index, 7);
}

TEST(PiperCodecDecode, EndVelAccReply) {
  const auto reply = decoded<EndVelAccReply>(message_of(0x478, {0x03, 0xE8, 0x07, 0xD0, 0x01, 0xF4, 0x0B, 0xB8}));
  EXPECT_NEAR(reply.values.max_linear_velocity_m_s.value_or(0), 1.0, 1e-12);
  EXPECT_NEAR(reply.values.max_angular_velocity_rad_s.value_or(0), 2.0, 1e-12);
  EXPECT_NEAR(reply.values.max_linear_acceleration_m_s2.value_or(0), 0.5, 1e-12);
  EXPECT_NEAR(reply.values.max_angular_acceleration_rad_s2.value_or(0), 3.0, 1e-12);
}

TEST(PiperCodecDecode, CrashProtectionReply) {
  const auto reply = decoded<CrashProtectionReply>(message_of(0x47B, {1, 2, 3, 4, 5, 6, 0xFF, 0xFF}));
  EXPECT_EQ(reply.levels, (std::array<std::uint8_t, kArmJoints>{1, 2, 3, 4, 5, 6}));
}

TEST(PiperCodecDecode, JointAccReply) {
  const CanMessage message = message_of(0x47C, {0x04, 0x01, 0xF4, 0, 0, 0, 0, 0});
  EXPECT_EQ(decoded<JointAccReply>(message).joint, 4);
  EXPECT_NEAR(decoded<JointAccReply>(message).max_acc_rad_s2, 5.0, 1e-12);  // 500 × 0.01 rad/s²
  EXPECT_NEAR(decoded<JointAccReply>(message, CodecOptions{.max_acc_unit_rad_s2 = 0.001}).max_acc_rad_s2, 0.5, 1e-12);
}

TEST(PiperCodecDecode, GripperParamReply) {
  const auto reply = decoded<GripperParamReply>(message_of(0x47E, {0x96, 0x64, 0x05, 0, 0, 0, 0, 0}));
  EXPECT_EQ(reply.params.teaching_range_percent, 150);
  EXPECT_EQ(reply.params.max_range_mm, 100);
  EXPECT_EQ(reply.params.teaching_friction, 5);
}

TEST(PiperCodecDecode, MasterArmJointCommand) {
  const auto pair = decoded<JointTargetPair>(message_of(0x157, {0x00, 0x00, 0x2C, 0xC3, 0xFF, 0xFF, 0xD3, 0x3D}));
  EXPECT_EQ(pair.pair, 2);
  EXPECT_NEAR(pair.first_rad, 0.2, kMilliDegree / 2);
  EXPECT_NEAR(pair.second_rad, -0.2, kMilliDegree / 2);
}

// --- round trips ------------------------------------------------------------------------------------

struct Sample {
  Frame frame;
  std::uint8_t needed_bytes;  // the shortest payload that decodes
};

/// One frame of every type, with values away from zero and within range.
std::vector<Sample> every_frame_type() {
  return {
      {MotionControl{EmergencyStop::kStop, 1, 2, 3, 0x1234, 0xABCD}, 8},
      {ModeControl{ControlMode::kCanCommand, MoveMode::kL, 50, true, 4, 1}, 6},
      {EndPoseTargetPart{.part = 1, .first = 0.25, .second = 0.5}, 8},
      {JointTargetPair{.pair = 2, .first_rad = -0.3, .second_rad = 1.2}, 8},
      {MoveCPoint{.index = 2}, 1},
      {GripperControl{.stroke_m = 0.035, .effort_nm = 1.5, .enable = GripperEnable::kEnable}, 8},
      {MitControl{.joint = 3, .position_rad = 0.5, .velocity_rad_s = -1, .kp = 10, .kd = 0.8, .torque = 2}, 8},
      {MasterSlaveConfig{.linkage = 0xFC, .feedback_offset = 0x10, .control_offset = 0x20, .linkage_offset = 0x10}, 4},
      {MasterArmHomeRequest{.mode = MasterArmHome::kBothToZero}, 3},
      {MotorEnable{.motor = 3, .enable = false}, 2},
      {JointLimitQuery{.joint = 4, .acceleration = true}, 2},
      {JointLimitSet{.joint = 5, .max_angle_rad = 1.2, .max_speed_rad_s = 2.5}, 7},
      {JointConfig{.joint = 6, .set_zero = true, .max_acc_rad_s2 = 3.0, .clear_error = true}, 6},
      {ParamEnquiry{.query = 2, .setting = 1, .feedback_48x = 2, .payload = 1}, 5},
      {EndVelAccSet{{.max_linear_velocity_m_s = 0.5, .max_angular_acceleration_rad_s2 = 2.0}}, 8},
      {CrashProtectionSet{.levels = {1, 2, 3, 4, 5, 6}}, 6},
      {GripperParamSet{{.teaching_range_percent = 150, .max_range_mm = 100, .teaching_friction = 5}}, 3},
      {FirmwareChunk{.text = {'S', '-', 'V', '1', '.', '8', '-', '2'}}, 1},
      {ArmStatus{ControlMode::kCanCommand, 0x01, MoveMode::kJ, 0x02, 1, 9, 0x21, 0x12}, 8},
      {EndPoseFeedbackPart{.part = 2, .first = 0.1, .second = -0.2}, 8},
      {JointFeedbackPair{.pair = 0, .first_rad = 0.1, .second_rad = -0.1}, 8},
      {GripperFeedback{.stroke_m = 0.02, .effort_nm = -0.5, .status_bits = 0xC1, .reserved = 1}, 8},
      {HighSpeedInfo{.joint = 4, .speed_rad_s = -1.5, .current_a = 2.25, .position_rad = 0.75}, 8},
      {LowSpeedInfo{.joint = 6,
                    .voltage_v = 24.5,
                    .driver_temperature_c = 35,
                    .motor_temperature_c = -5,
                    .status_bits = 0x40,
                    .bus_current_a = 1.25},
       8},
      {JointLimitReply{.joint = 1, .max_angle_rad = 2.618, .min_angle_rad = -2.618, .max_speed_rad_s = 3.0}, 7},
      {SetAck{.command = 0x74}, 3},
      {EndVelAccReply{{.max_linear_velocity_m_s = 1,
                       .max_angular_velocity_rad_s = 2,
                       .max_linear_acceleration_m_s2 = 3,
                       .max_angular_acceleration_rad_s2 = 4}},
       8},
      {CrashProtectionReply{.levels = {0, 8, 1, 7, 2, 6}}, 6},
      {JointAccReply{.joint = 2, .max_acc_rad_s2 = 5.0}, 3},
      {GripperParamReply{{.teaching_range_percent = 100, .max_range_mm = 70, .teaching_friction = 1}}, 3},
  };
}

CanMessage encode_frame(const Frame& frame, const CodecOptions& options) {
  return std::visit([&options](const auto& alternative) { return encode(alternative, options); }, frame);
}

TEST(PiperCodecRoundTrip, SamplesCoverEveryFrameType) {
  std::set<std::size_t> types;
  for (const Sample& sample : every_frame_type()) types.insert(sample.frame.index());
  EXPECT_EQ(types.size(), std::variant_size_v<Frame>);
}

TEST(PiperCodecRoundTrip, EveryFrameTypeDecodesToItselfAndReencodesToTheSameBytes) {
  for (const CodecOptions& options : {CodecOptions{}, torque12()}) {
    for (const Sample& sample : every_frame_type()) {
      const CanMessage message = encode_frame(sample.frame, options);
      const std::optional<Frame> frame = decode(message, options);
      ASSERT_TRUE(frame.has_value()) << wire_of(message);
      EXPECT_EQ(frame->index(), sample.frame.index()) << wire_of(message);
      EXPECT_EQ(wire_of(encode_frame(*frame, options)), wire_of(message));
    }
  }
}

TEST(PiperCodecRoundTrip, AnglesAndLengthsWithinHalfACount) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> angle(-3.2, 3.2);
  std::uniform_real_distribution<double> length(-1.0, 1.0);
  for (int i = 0; i < 1000; ++i) {
    const JointTargetPair joints{.pair = i % 3, .first_rad = angle(random), .second_rad = angle(random)};
    const auto joints_back = round_trip(joints);
    EXPECT_EQ(joints_back.pair, joints.pair);
    EXPECT_NEAR(joints_back.first_rad, joints.first_rad, kMilliDegree / 2);
    EXPECT_NEAR(joints_back.second_rad, joints.second_rad, kMilliDegree / 2);
    const auto feedback_back = round_trip(JointFeedbackPair{joints.pair, joints.first_rad, joints.second_rad});
    EXPECT_NEAR(feedback_back.second_rad, joints.second_rad, kMilliDegree / 2);

    const CartesianPose pose{length(random), length(random), length(random),
                             angle(random),  angle(random),  angle(random)};
    const auto frames = encode_end_pose_target(pose);
    const auto xy = decoded<EndPoseTargetPart>(frames[0]);
    const auto zrx = decoded<EndPoseTargetPart>(frames[1]);
    const auto ryrz = decoded<EndPoseTargetPart>(frames[2]);
    EXPECT_NEAR(xy.first, pose.x_m, 0.5e-6);
    EXPECT_NEAR(xy.second, pose.y_m, 0.5e-6);
    EXPECT_NEAR(zrx.first, pose.z_m, 0.5e-6);
    EXPECT_NEAR(zrx.second, pose.rx_rad, kMilliDegree / 2);
    EXPECT_NEAR(ryrz.first, pose.ry_rad, kMilliDegree / 2);
    EXPECT_NEAR(ryrz.second, pose.rz_rad, kMilliDegree / 2);
    const auto feedback = decoded<EndPoseFeedbackPart>(encode_end_pose_feedback(pose)[1]);
    EXPECT_NEAR(feedback.second, pose.rx_rad, kMilliDegree / 2);
  }
}

TEST(PiperCodecRoundTrip, MitWithinOneStepInBothLayouts) {
  std::mt19937 random(11);
  const auto uniform = [&random](double low, double high) {
    return std::uniform_real_distribution<double>(low, high)(random);
  };
  for (int i = 0; i < 1000; ++i) {
    const MitControl frame{.joint = 1 + i % kArmJoints,
                           .position_rad = uniform(-12.5, 12.5),
                           .velocity_rad_s = uniform(-45, 45),
                           .kp = uniform(0, 500),
                           .kd = uniform(-5, 5),
                           .torque = uniform(-8, 8)};
    const auto back = round_trip(frame);
    EXPECT_EQ(back.joint, frame.joint);
    EXPECT_NEAR(back.position_rad, frame.position_rad, 25.0 / 65535);
    EXPECT_NEAR(back.velocity_rad_s, frame.velocity_rad_s, 90.0 / 4095);
    EXPECT_NEAR(back.kp, frame.kp, 500.0 / 4095);
    EXPECT_NEAR(back.kd, frame.kd, 10.0 / 4095);
    EXPECT_NEAR(back.torque, frame.torque, 16.0 / 255);
    // Truncation: decoding never overshoots the command.
    EXPECT_LE(back.kp, frame.kp);
    MitControl wide = frame;
    wide.torque = uniform(-16, 16);
    EXPECT_NEAR(round_trip(wide, torque12()).torque, wide.torque, 32.0 / 4095);
  }
}

TEST(PiperCodecRoundTrip, ScaledFieldsWithinOneCount) {
  const auto gripper = round_trip(GripperControl{
      .stroke_m = 0.0123456, .effort_nm = 2.3456, .enable = GripperEnable::kEnableClearError, .set_zero = true});
  EXPECT_NEAR(gripper.stroke_m, 0.0123456, 1e-6);
  EXPECT_NEAR(gripper.effort_nm, 2.3456, 1e-3);
  EXPECT_EQ(gripper.enable, GripperEnable::kEnableClearError);
  EXPECT_TRUE(gripper.set_zero);

  const auto gripper_feedback = round_trip(GripperFeedback{.stroke_m = -0.001, .effort_nm = -3.2109});
  EXPECT_NEAR(gripper_feedback.stroke_m, -0.001, 1e-6);
  EXPECT_NEAR(gripper_feedback.effort_nm, -3.2109, 1e-3);

  const CodecOptions options{.motor_position_unit_rad = 0.001};
  const auto high = round_trip(
      HighSpeedInfo{.joint = 2, .speed_rad_s = -2.3456, .current_a = 7.891, .position_rad = -1.2345}, options);
  EXPECT_EQ(high.joint, 2);
  EXPECT_NEAR(high.speed_rad_s, -2.3456, 1e-3);
  EXPECT_NEAR(high.current_a, 7.891, 1e-3);
  EXPECT_NEAR(high.position_rad, -1.2345, 1e-3);

  const auto low = round_trip(LowSpeedInfo{.joint = 1,
                                           .voltage_v = 24.37,
                                           .driver_temperature_c = -40,
                                           .motor_temperature_c = 85,
                                           .status_bits = 0x41,
                                           .bus_current_a = 3.21});
  EXPECT_EQ(low.joint, 1);
  EXPECT_NEAR(low.voltage_v, 24.37, 0.1);
  EXPECT_EQ(low.driver_temperature_c, -40);
  EXPECT_EQ(low.motor_temperature_c, 85);
  EXPECT_EQ(low.status_bits, 0x41);
  EXPECT_NEAR(low.bus_current_a, 3.21, 1e-3);

  constexpr double kDeciDegree = kPi / 1800;
  const CodecOptions agx{.max_speed_unit_rad_s = 0.01, .max_acc_unit_rad_s2 = 0.001};
  const auto reply = round_trip(
      JointLimitReply{.joint = 3, .max_angle_rad = 0.1234, .min_angle_rad = -2.9670, .max_speed_rad_s = 2.345}, agx);
  EXPECT_NEAR(reply.max_angle_rad, 0.1234, kDeciDegree);
  EXPECT_NEAR(reply.min_angle_rad, -2.9670, kDeciDegree);
  EXPECT_NEAR(reply.max_speed_rad_s, 2.345, 0.01);

  const auto set = round_trip(JointLimitSet{.joint = 3, .max_angle_rad = 1.745, .min_angle_rad = -1.745}, agx);
  EXPECT_NEAR(set.max_angle_rad.value_or(0), 1.745, kDeciDegree);
  EXPECT_NEAR(set.min_angle_rad.value_or(0), -1.745, kDeciDegree);
  EXPECT_FALSE(set.max_speed_rad_s.has_value());

  const auto config = round_trip(JointConfig{.joint = 2, .apply_max_acc = true, .max_acc_rad_s2 = 4.321}, agx);
  EXPECT_TRUE(config.apply_max_acc);
  EXPECT_NEAR(config.max_acc_rad_s2, 4.321, 0.001);
  EXPECT_FALSE(round_trip(JointConfig{.joint = 2}).apply_max_acc);

  EXPECT_NEAR(round_trip(JointAccReply{.joint = 1, .max_acc_rad_s2 = 1.234}).max_acc_rad_s2, 1.234, 0.01);

  const auto end = round_trip(EndVelAccSet{{.max_angular_velocity_rad_s = 1.2345}});
  EXPECT_FALSE(end.values.max_linear_velocity_m_s.has_value());
  EXPECT_NEAR(end.values.max_angular_velocity_rad_s.value_or(0), 1.2345, 1e-3);

  const auto enquiry = round_trip(ParamEnquiry{.query = 1});
  EXPECT_EQ(enquiry.query, 1);
  EXPECT_FALSE(enquiry.payload.has_value());
  EXPECT_EQ(round_trip(ParamEnquiry{.payload = 0}).payload, std::optional<std::uint8_t>{0});
}

TEST(PiperCodecRoundTrip, EnumsAndFlags) {
  const auto mode = round_trip(ModeControl{.ctrl_mode = ControlMode::kOfflineTrajectory,
                                           .move_mode = MoveMode::kMit,
                                           .speed_percent = 0,
                                           .mit = true,
                                           .residence_time_s = 255},
                               torque12());
  EXPECT_EQ(mode.ctrl_mode, ControlMode::kOfflineTrajectory);
  EXPECT_EQ(mode.move_mode, MoveMode::kMit);
  EXPECT_TRUE(mode.mit);
  EXPECT_EQ(mode.residence_time_s, 255);
  EXPECT_TRUE(round_trip(MotorEnable{.motor = 2, .enable = true}).enable);
  EXPECT_FALSE(round_trip(MotorEnable{.motor = 2, .enable = false}).enable);
  EXPECT_FALSE(round_trip(JointLimitQuery{.joint = 1}).acceleration);
  EXPECT_TRUE(round_trip(SetAck{.command = 0x75, .zero_set = true}).zero_set);
  const auto stop = round_trip(MotionControl{.emergency_stop = EmergencyStop::kResume, .drag_teach_ctrl = 7});
  EXPECT_EQ(stop.emergency_stop, EmergencyStop::kResume);
  EXPECT_EQ(stop.drag_teach_ctrl, 7);
}

// --- saturation and malformed input --------------------------------------------------------------

TEST(PiperCodecEdges, JointAngleSaturatesToTheInt32Range) {
  EXPECT_EQ(wire_of(encode(JointTargetPair{.first_rad = 1e9, .second_rad = -1e9})).bytes,
            (Bytes{0x7F, 0xFF, 0xFF, 0xFF, 0x80, 0x00, 0x00, 0x00}));
  const double infinity = std::numeric_limits<double>::infinity();
  EXPECT_EQ(wire_of(encode(JointTargetPair{.first_rad = infinity, .second_rad = -infinity})).bytes,
            (Bytes{0x7F, 0xFF, 0xFF, 0xFF, 0x80, 0x00, 0x00, 0x00}));
  EXPECT_EQ(wire_of(encode(JointTargetPair{.first_rad = std::numeric_limits<double>::quiet_NaN()})).bytes,
            (Bytes(8, 0x00)));
}

TEST(PiperCodecEdges, SixteenAndEightBitFieldsSaturate) {
  EXPECT_EQ(wire_of(encode(GripperControl{.effort_nm = -1})).bytes[4], 0x00);
  EXPECT_EQ(wire_of(encode(GripperControl{.effort_nm = 100})).bytes, (Bytes{0, 0, 0, 0, 0xFF, 0xFF, 0, 0}));
  EXPECT_EQ(wire_of(encode(GripperControl{.stroke_m = -1e6})).bytes, (Bytes{0x80, 0, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(wire_of(encode(GripperFeedback{.effort_nm = 40})).bytes, (Bytes{0, 0, 0, 0, 0x7F, 0xFF, 0, 0}));
  EXPECT_EQ(wire_of(encode(GripperFeedback{.effort_nm = -40})).bytes, (Bytes{0, 0, 0, 0, 0x80, 0x00, 0, 0}));
  const auto low = wire_of(encode(LowSpeedInfo{
      .voltage_v = -3, .driver_temperature_c = 100000, .motor_temperature_c = -1000, .bus_current_a = 1e9}));
  EXPECT_EQ(low.bytes, (Bytes{0x00, 0x00, 0x7F, 0xFF, 0x80, 0x00, 0xFF, 0xFF}));
  EXPECT_EQ(wire_of(encode(JointLimitReply{.max_angle_rad = 1e3, .min_angle_rad = -1e3})).bytes,
            (Bytes{0x01, 0x7F, 0xFF, 0x80, 0x00, 0x00, 0x00, 0x00}));
}

TEST(PiperCodecEdges, PartAndJointIndicesSaturate) {
  EXPECT_EQ(encode(JointTargetPair{.pair = -1}).id, 0x155U);
  EXPECT_EQ(encode(JointTargetPair{.pair = 3}).id, 0x157U);
  EXPECT_EQ(encode(EndPoseTargetPart{.part = 7}).id, 0x154U);
  EXPECT_EQ(encode(HighSpeedInfo{.joint = 0}).id, 0x251U);
  EXPECT_EQ(encode(LowSpeedInfo{.joint = 7}).id, 0x266U);
}

TEST(PiperCodecEdges, UnknownIdsDecodeToNothing) {
  for (const std::uint32_t id : {0x000U, 0x121U, 0x14FU, 0x160U, 0x191U, 0x250U, 0x257U, 0x260U, 0x267U, 0x2A0U, 0x2A9U,
                                 0x2AAU, 0x422U, 0x46FU, 0x47FU, 0x481U, 0x4AEU, 0x7FFU}) {
    EXPECT_FALSE(decode(message_of(id, Bytes(8, 0x00))).has_value()) << std::hex << id;
  }
}

TEST(PiperCodecEdges, ExtendedFdAndErrorFramesDecodeToNothing) {
  CanMessage message = encode(JointFeedbackPair{.first_rad = 0.1});
  ASSERT_TRUE(decode(message).has_value());
  CanMessage extended = message;
  extended.extended = true;
  EXPECT_FALSE(decode(extended).has_value());
  CanMessage fd = message;
  fd.fd = true;
  EXPECT_FALSE(decode(fd).has_value());
  CanMessage error = message;
  error.error_frame = true;
  EXPECT_FALSE(decode(error).has_value());
  EXPECT_FALSE(is_firmware_request([] {
    CanMessage request = firmware_request();
    request.extended = true;
    return request;
  }()));
}

TEST(PiperCodecEdges, TruncatedPayloadsDecodeToNothing) {
  for (const Sample& sample : every_frame_type()) {
    CanMessage message = encode_frame(sample.frame, {});
    for (std::uint8_t length = 0; length <= 8; ++length) {
      message.length = length;
      EXPECT_EQ(decode(message).has_value(), length >= sample.needed_bytes)
          << std::hex << "0x" << message.id << std::dec << " with " << int{length} << " bytes";
    }
  }
}

TEST(PiperCodecEdges, OversizedClassicPayloadsAreReadUpToWhatTheFrameNeeds) {
  CanMessage message = encode(HighSpeedInfo{.joint = 2, .speed_rad_s = 1.0});
  message.length = 64;
  std::fill(message.data.begin() + 8, message.data.end(), 0xEE);
  EXPECT_NEAR(decoded<HighSpeedInfo>(message).speed_rad_s, 1.0, 1e-12);
  message.length = 255;  // nonsense a broken transport might hand over: still read only 8 bytes
  EXPECT_EQ(decoded<HighSpeedInfo>(message).joint, 2);
  CanMessage chunk = encode(FirmwareChunk{.text = {'H', '-', 'V', '1', '.', '2', '-', '1'}});
  chunk.length = 12;
  EXPECT_EQ(decoded<FirmwareChunk>(chunk).length, 8);
}

TEST(PiperCodecEdges, RandomFramesNeverCrashAndDecodeOnlyToTheirOwnId) {
  std::vector<std::uint32_t> known_ids{0x150, 0x151, 0x158, 0x159, 0x4AF};
  for (std::uint32_t id = 0x152; id <= 0x157; ++id) known_ids.push_back(id);
  for (std::uint32_t id = 0x15A; id <= 0x15F; ++id) known_ids.push_back(id);
  for (std::uint32_t id = 0x251; id <= 0x256; ++id) known_ids.push_back(id);
  for (std::uint32_t id = 0x261; id <= 0x266; ++id) known_ids.push_back(id);
  for (std::uint32_t id = 0x2A1; id <= 0x2A8; ++id) known_ids.push_back(id);
  for (std::uint32_t id = 0x470; id <= 0x47E; ++id) known_ids.push_back(id);
  std::mt19937 random(2024);
  std::uniform_int_distribution<std::uint32_t> any_id(0x000, 0x7FF);
  std::uniform_int_distribution<std::size_t> known_id(0, known_ids.size() - 1);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<int> length(0, 9);  // 9: any length up to 255
  std::size_t frames = 0;
  for (int i = 0; i < 200'000; ++i) {
    CanMessage message;
    // Half the frames on ids the codec knows, so that its decoders see random bytes.
    message.id = i % 2 == 0 ? any_id(random) : known_ids[known_id(random)];
    const int kind = byte(random);
    message.extended = kind == 0;
    message.fd = kind == 1;
    message.error_frame = kind == 2;
    const int draw = length(random);
    message.length = static_cast<std::uint8_t>(draw == 9 ? byte(random) : draw);
    for (std::size_t b = 0; b < 8; ++b) message.data[b] = static_cast<std::uint8_t>(byte(random));
    const CodecOptions options = kind % 2 == 0 ? CodecOptions{} : torque12();
    const std::optional<Frame> frame = decode(message, options);
    if (!frame) continue;
    ++frames;
    ASSERT_EQ(encode_frame(*frame, options).id, message.id);
  }
  EXPECT_GT(frames, 10'000U);
}

TEST(PiperCodecEdges, DecodeDoesNotAllocate) {
  std::vector<CanMessage> messages;
  for (const Sample& sample : every_frame_type()) messages.push_back(encode_frame(sample.frame, {}));
  messages.push_back(message_of(0x7FF, Bytes(8, 0)));
  std::size_t decoded_frames = 0;
  const std::size_t before = testing::allocations_on_this_thread();
  for (const CanMessage& message : messages) decoded_frames += decode(message).has_value() ? 1U : 0U;
  EXPECT_EQ(testing::allocations_on_this_thread(), before);
  EXPECT_EQ(decoded_frames, messages.size() - 1);
}

// --- firmware version (§5.14) -------------------------------------------------------------------------

/// An 88-byte 0x4AF reply laid out as pyAgxArm reads it.
std::string firmware_reply(const std::string& software) {
  std::string text(88, ' ');
  const auto place = [&text](std::size_t at, const std::string& field) { text.replace(at, field.size(), field); };
  place(0, "H-V1.2-1");
  place(16, "01");
  place(32, "ARM_MC");
  place(60, software);
  place(68, "240725");
  place(76, "01");
  return text;
}

TEST(PiperFirmware, SoftwareVersionFromTheReassembledReply) {
  const std::string reply = firmware_reply("S-V1.8-2");
  std::string received;
  for (std::size_t at = 0; at < reply.size(); at += 8) {
    FirmwareChunk chunk;
    std::copy_n(reply.begin() + static_cast<std::ptrdiff_t>(at), 8, chunk.text.begin());
    const auto back = decoded<FirmwareChunk>(encode(chunk));
    received.append(back.text.data(), back.length);
  }
  EXPECT_EQ(received, reply);
  EXPECT_EQ(software_version(received), std::optional<std::string>{"S-V1.8-2"});
  EXPECT_EQ(mit_layout_for(*software_version(received)), MitLayout::kTorque8Crc);
}

// As the SDK's GetPiperFirmwareVersion: what has arrived of the 8 characters once "S-V" is there.
TEST(PiperFirmware, PartialVersionOnceTheMarkerArrives) {
  EXPECT_EQ(software_version(""), std::nullopt);
  EXPECT_EQ(software_version("H-V1.2-1 ARM_MC"), std::nullopt);
  EXPECT_EQ(software_version(firmware_reply("S-V1.8-2").substr(0, 62)), std::nullopt);
  EXPECT_EQ(software_version(firmware_reply("S-V1.8-2").substr(0, 63)), std::optional<std::string>{"S-V"});
  EXPECT_EQ(software_version(firmware_reply("S-V1.8-2").substr(0, 66)), std::optional<std::string>{"S-V1.8"});
  EXPECT_EQ(software_version(firmware_reply("S-V1.8-2").substr(0, 68)), std::optional<std::string>{"S-V1.8-2"});
}

TEST(PiperFirmware, MitLayoutChangesAtS_V1_8_8) {
  EXPECT_EQ(mit_layout_for("S-V1.6-3"), MitLayout::kTorque8Crc);
  EXPECT_EQ(mit_layout_for("S-V1.7-9"), MitLayout::kTorque8Crc);
  EXPECT_EQ(mit_layout_for("S-V1.8-2"), MitLayout::kTorque8Crc);
  EXPECT_EQ(mit_layout_for("S-V1.8-7"), MitLayout::kTorque8Crc);
  EXPECT_EQ(mit_layout_for("S-V1.8-8"), MitLayout::kTorque12);
  EXPECT_EQ(mit_layout_for("S-V1.8-9"), MitLayout::kTorque12);
  EXPECT_EQ(mit_layout_for("S-V1.8-10"), MitLayout::kTorque12);
  EXPECT_EQ(mit_layout_for("S-V1.9-0"), MitLayout::kTorque12);
  EXPECT_EQ(mit_layout_for("S-V1.10-1"), MitLayout::kTorque12);
  EXPECT_EQ(mit_layout_for("S-V1.10-"), MitLayout::kTorque12);  // the 8-character cut of S-V1.10-1
  EXPECT_EQ(mit_layout_for("S-V2.0-0"), MitLayout::kTorque12);
  EXPECT_EQ(mit_layout_for("S-V0.9-9"), MitLayout::kTorque8Crc);
}

TEST(PiperFirmware, UnparsableVersionsMeanTheOldLayout) {
  for (const char* text :
       {"", "garbage", "S-V", "S-V1", "S-V1.", "S-V1.8", "S-V1.8-", "S-Vx.y-z", "H-V1.8-8", "S-V-1.8-8", "1.8-8"}) {
    EXPECT_EQ(mit_layout_for(text), MitLayout::kTorque8Crc) << text;
  }
}

// --- status text ----------------------------------------------------------------------------------

TEST(PiperStatusText, ArmStatusCodes) {
  EXPECT_STREQ(arm_status_text(0x00), "normal");
  EXPECT_STREQ(arm_status_text(0x01), "emergency stop");
  EXPECT_STREQ(arm_status_text(0x05), "joint communication error");
  EXPECT_STREQ(arm_status_text(0x07), "collision");
  EXPECT_STREQ(arm_status_text(0x0F), "brake-resistor ntc over-temperature");
  std::set<std::string> texts;
  for (std::uint8_t code = 0; code < 16; ++code) texts.insert(arm_status_text(code));
  EXPECT_EQ(texts.size(), 16U);
  EXPECT_EQ(texts.count("unknown"), 0U);
  EXPECT_STREQ(arm_status_text(0x10), "unknown");
  EXPECT_STREQ(arm_status_text(0xFF), "unknown");
}

TEST(PiperStatusText, ModesAndTeachStatus) {
  EXPECT_STREQ(control_mode_text(ControlMode::kStandby), "standby");
  EXPECT_STREQ(control_mode_text(ControlMode::kCanCommand), "can command");
  EXPECT_STREQ(control_mode_text(ControlMode::kLinkageTeach), "linkage teach");
  EXPECT_STREQ(control_mode_text(static_cast<ControlMode>(0x08)), "unknown");
  EXPECT_STREQ(move_mode_text(MoveMode::kJ), "move j");
  EXPECT_STREQ(move_mode_text(MoveMode::kMit), "mit");
  EXPECT_STREQ(move_mode_text(static_cast<MoveMode>(0xFF)), "unknown");
  EXPECT_STREQ(teach_status_text(0x00), "off");
  EXPECT_STREQ(teach_status_text(0x07), "move to start");
  EXPECT_STREQ(teach_status_text(0x08), "unknown");
}

TEST(PiperStatusText, DriverFaultBits) {
  EXPECT_EQ(driver_status_text(0x00), "");
  EXPECT_EQ(driver_status_text(0x40), "");  // enabled is not a fault
  EXPECT_EQ(driver_status_text(0x05), "under-voltage, over-current");
  EXPECT_EQ(driver_status_text(0x10), "collision protection triggered");
  EXPECT_EQ(driver_status_text(0x80), "stall protection triggered");
  EXPECT_EQ(driver_status_text(0xFF),
            "under-voltage, motor over-temperature, over-current, driver over-temperature, "
            "collision protection triggered, driver error, stall protection triggered");
}

TEST(PiperStatusText, GripperFaultBits) {
  EXPECT_EQ(gripper_status_text(0xC0), "");  // enabled and homed are not faults
  EXPECT_EQ(gripper_status_text(0x10), "sensor fault");
  EXPECT_EQ(gripper_status_text(0x3F),
            "under-voltage, motor over-temperature, over-current, driver over-temperature, sensor fault, "
            "driver error");
}

// The argument ranges the vendor SDK refuses are named by refusal(); encode() itself saturates.
TEST(PiperCodecRefusal, NamesTheFieldTheSdkWouldRefuse) {
  EXPECT_EQ(refusal(ModeControl{}), nullptr);
  EXPECT_STREQ(refusal(ModeControl{.ctrl_mode = ControlMode::kTeach}),
               "0x151 ctrl_mode must be 0 (standby), 1 (CAN), 3 (Ethernet), 4 (Wi-Fi) or 7 (offline trajectory); "
               "teach, remote and linkage-teach are states the arm reports, not modes a host sets");
  EXPECT_NE(refusal(GripperControl{.effort_nm = 5.001}), nullptr);
  EXPECT_EQ(refusal(GripperControl{.effort_nm = 5.0}), nullptr);
  EXPECT_NE(refusal(MasterSlaveConfig{.linkage = 0xFA, .feedback_offset = 0x30}), nullptr);
  EXPECT_NE(refusal(MotorEnable{.motor = 0}), nullptr);
  EXPECT_EQ(refusal(MotorEnable{.motor = 0xFF}), nullptr);
  EXPECT_NE(refusal(JointConfig{.joint = 1, .max_acc_rad_s2 = 5.01}), nullptr);
  EXPECT_EQ(refusal(JointConfig{.joint = 1, .max_acc_rad_s2 = 327.67}), nullptr);  // 0x7FFF: unchanged
  EXPECT_NE(refusal(EndVelAccSet{.values = EndVelAcc{.max_linear_velocity_m_s = 65.536}}), nullptr);
  EXPECT_EQ(refusal(ParamEnquiry{.query = 3}), nullptr);  // the trajectory-index query
  EXPECT_NE(refusal(GripperParamSet{.params = GripperParams{.max_range_mm = 80}}), nullptr);
}

// MasterSlaveConfig offsets move the control ids (0x15x) and the feedback ids (0x2Ax), nothing
// else: to_wire() moves them on the way out, decode() takes them back, and ids at another offset
// are another arm's (not decoded), whose offset feedback_offset_of / control_offset_of name.
TEST(PiperCodecIdOffsets, ControlAndFeedbackIdsMoveAndComeBack) {
  const CodecOptions moved{.feedback_id_offset = 0x10, .control_id_offset = 0x20};
  const auto joints = encode_joint_targets({0.1, 0.2, 0.3, 0.4, 0.5, 0.6});
  EXPECT_EQ(to_wire(joints[1], moved).id, 0x176U);
  EXPECT_EQ(to_wire(encode(MitControl{.joint = 6}), moved).id, 0x17FU);
  EXPECT_EQ(to_wire(encode(ArmStatus{}), moved).id, 0x2B1U);
  EXPECT_EQ(to_wire(encode(GripperFeedback{}), moved).id, 0x2B8U);
  for (const CanMessage& unmoved : {encode(HighSpeedInfo{.joint = 1}), encode(MotorEnable{}), firmware_request(),
                                    encode(MasterArmHomeRequest{}), encode(SetAck{})}) {
    EXPECT_EQ(to_wire(unmoved, moved).id, unmoved.id);
  }
  const auto pair = decode(to_wire(joints[1], moved), moved);
  ASSERT_TRUE(pair && std::holds_alternative<JointTargetPair>(*pair));
  EXPECT_EQ(std::get<JointTargetPair>(*pair).pair, 1);
  EXPECT_NEAR(std::get<JointTargetPair>(*pair).first_rad, 0.3, 1e-5);
  ASSERT_TRUE(decode(to_wire(encode(ArmStatus{}), moved), moved));
  // At the protocol's own ids, or at the other offset, they are another arm's frames.
  EXPECT_FALSE(decode(joints[1], moved));
  EXPECT_FALSE(decode(encode(ArmStatus{}), moved));
  EXPECT_FALSE(decode(to_wire(encode(ArmStatus{}), CodecOptions{.feedback_id_offset = 0x20}), moved));
  EXPECT_FALSE(decode(to_wire(encode(ArmStatus{}), moved), CodecOptions{}));
  EXPECT_EQ(feedback_offset_of(0x2C5), std::optional<std::uint8_t>(0x20));
  EXPECT_EQ(feedback_offset_of(0x2A1), std::optional<std::uint8_t>(0x00));
  EXPECT_EQ(feedback_offset_of(0x2B9), std::nullopt);
  EXPECT_EQ(control_offset_of(0x16F), std::optional<std::uint8_t>(0x10));
  EXPECT_EQ(control_offset_of(0x180), std::nullopt);
  EXPECT_TRUE(id_offset_valid(0x20));
  EXPECT_FALSE(id_offset_valid(0x30));
}

}  // namespace
}  // namespace robotd::piper
