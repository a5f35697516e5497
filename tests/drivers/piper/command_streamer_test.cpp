// CommandStreamer: which PiPER frames one tick of robotd's loop puts on the bus.
#include "driver/command_streamer.hpp"

#include <algorithm>
#include <map>

#include <gtest/gtest.h>

namespace robotd::piper {
namespace {

using driver::JointCommandKind;

constexpr std::int64_t kMs = 1'000'000;

PiperParams test_params() {
  auto params = parse_piper_params({{"can", {{"transport", "standin"}, {"path", "/tmp/unused.sock"}}}});
  EXPECT_TRUE(params) << params.error().message;
  return params.value();
}

driver::CommandFrame position_frame(double q, bool owned = true) {
  driver::CommandFrame frame;
  frame.joint_count = 7;
  for (std::size_t j = 0; j < 6; ++j) {
    frame.joints[j] = {.kind = JointCommandKind::kPosition, .owned = owned, .position_rad = q};
  }
  return frame;
}

std::vector<CanMessage> frames_of(const OutgoingFrames& out) {
  return {out.frames.begin(), out.frames.begin() + static_cast<std::ptrdiff_t>(out.count)};
}

std::size_t count_id(const OutgoingFrames& out, std::uint32_t id) {
  return static_cast<std::size_t>(std::count_if(out.frames.begin(),
                                                out.frames.begin() + static_cast<std::ptrdiff_t>(out.count),
                                                [&](const CanMessage& m) { return m.id == id; }));
}

template <class T>
T decoded(const CanMessage& message, const CodecOptions& options = {}) {
  const auto frame = decode(message, options);
  EXPECT_TRUE(frame.has_value());
  return std::get<T>(*frame);
}

class CommandStreamerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    params_ = test_params();
    streamer_.configure(params_, params_.codec);
  }
  OutgoingFrames plan_at(driver::CommandFrame frame, std::int64_t t_ns, bool hold_ops = false) {
    frame.tick_deadline_ns = t_ns;
    OutgoingFrames out;
    streamer_.plan(frame, arm_, hold_ops, out);
    return out;
  }
  PiperParams params_;
  CommandStreamer streamer_;
  ArmState arm_;
};

TEST_F(CommandStreamerTest, NothingGoesOutBeforeAnyJointIsCommanded) {
  driver::CommandFrame idle;
  idle.joint_count = 7;
  EXPECT_EQ(plan_at(idle, 1 * kMs).count, 0U);
}

TEST_F(CommandStreamerTest, FirstOwnedPositionTickEnablesSetsMoveJAndSendsTheTargets) {
  const OutgoingFrames out = plan_at(position_frame(0.2), 1 * kMs);
  const std::vector<CanMessage> frames = frames_of(out);
  ASSERT_EQ(frames.size(), 6U);  // enable, gripper enable, ModeCtrl, 3 × JointCtrl
  EXPECT_EQ(frames[0].id, can_id::kMotorEnable);
  EXPECT_EQ(frames[0].data[0], 7);
  EXPECT_EQ(frames[0].data[1], 0x02);
  EXPECT_EQ(frames[1].id, can_id::kGripperControl);
  EXPECT_EQ(frames[2].id, can_id::kModeControl);
  const std::array<std::uint8_t, 8> move_j{0x01, 0x01, 0x64, 0x00, 0x00, 0x00, 0x00, 0x00};
  EXPECT_TRUE(std::equal(move_j.begin(), move_j.end(), frames[2].data.begin()));
  EXPECT_EQ(frames[3].id, can_id::kJointTarget);
  EXPECT_EQ(frames[5].id, can_id::kJointTarget + 2);
  const auto pair = decoded<JointTargetPair>(frames[3]);
  EXPECT_NEAR(pair.first_rad, 0.2, 1e-4);
}

TEST_F(CommandStreamerTest, StreamsAtTheCommandRateNotTheLoopRate) {
  std::map<std::uint32_t, std::size_t> counts;
  for (int tick = 0; tick < 1000; ++tick) {  // one second of a 1 kHz loop
    for (const CanMessage& frame : frames_of(plan_at(position_frame(0.1), tick * kMs))) ++counts[frame.id];
  }
  EXPECT_EQ(counts[can_id::kJointTarget], 200U);  // command_rate_hz 200
  EXPECT_EQ(counts[can_id::kJointTarget + 2], 200U);
  EXPECT_EQ(counts[can_id::kModeControl], 10U);  // re-asserted every 100 ms
  EXPECT_EQ(counts[can_id::kMotorEnable], 10U);  // until the arm reports its joints enabled
}

TEST_F(CommandStreamerTest, EnableStopsOnceTheArmReportsItsJointsEnabled) {
  (void)plan_at(position_frame(0.1), 0);
  for (JointReport& joint : arm_.joints) joint.driver_status = 0x40;
  arm_.gripper.status_bits = 0x40;
  std::size_t enables = 0;
  for (int tick = 1; tick < 500; ++tick)
    enables += count_id(plan_at(position_frame(0.1), tick * kMs), can_id::kMotorEnable);
  EXPECT_EQ(enables, 0U);
}

TEST_F(CommandStreamerTest, ImpedanceCommandsSwitchToMitWithScaledTorque) {
  driver::CommandFrame frame = position_frame(0.0);
  frame.joints[0] = {
      .kind = JointCommandKind::kImpedance, .owned = true, .position_rad = 0.5, .kp = 10, .kd = 0.8, .torque_nm = 4.0};
  const OutgoingFrames out = plan_at(frame, 0);
  ASSERT_EQ(count_id(out, can_id::kModeControl), 1U);
  const auto* mode = std::find_if(out.frames.begin(), out.frames.end(),
                                  [](const CanMessage& m) { return m.id == can_id::kModeControl; });
  const std::array<std::uint8_t, 4> mit_mode{0x01, 0x04, 0x00, 0xAD};
  EXPECT_TRUE(std::equal(mit_mode.begin(), mit_mode.end(), mode->data.begin()));
  EXPECT_EQ(count_id(out, can_id::kJointTarget), 0U);
  for (std::uint32_t id = can_id::kMitControl; id < can_id::kMitControl + 6; ++id) EXPECT_EQ(count_id(out, id), 1U);
  const auto* joint1 = std::find_if(out.frames.begin(), out.frames.end(),
                                    [](const CanMessage& m) { return m.id == can_id::kMitControl; });
  const auto mit = decoded<MitControl>(*joint1);
  EXPECT_NEAR(mit.position_rad, 0.5, 1e-3);
  EXPECT_NEAR(mit.kp, 10, 0.2);
  EXPECT_NEAR(mit.torque, 1.0, 0.07);  // 4 N·m on J1 is 1.0 on the wire: the arm executes 4×
  const auto* joint2 = std::find_if(out.frames.begin(), out.frames.end(),
                                    [](const CanMessage& m) { return m.id == can_id::kMitControl + 1; });
  const auto position_in_mit = decoded<MitControl>(*joint2);
  EXPECT_NEAR(position_in_mit.kp, params_.joints[1].default_kp, 0.2);  // a position target uses the default gains
}

TEST_F(CommandStreamerTest, MitModeCodeFollowsTheFirmwareLayout) {
  CodecOptions newer = params_.codec;
  newer.mit_layout = MitLayout::kTorque12;
  streamer_.configure(params_, newer);
  driver::CommandFrame frame = position_frame(0.0);
  frame.joints[3].kind = JointCommandKind::kImpedance;
  const OutgoingFrames out = plan_at(frame, 0);
  const auto* mode = std::find_if(out.frames.begin(), out.frames.end(),
                                  [](const CanMessage& m) { return m.id == can_id::kModeControl; });
  ASSERT_NE(mode, out.frames.end());
  EXPECT_EQ(mode->data[1], 0x06);
}

TEST_F(CommandStreamerTest, UncommandedJointsHoldWhereTheStreamFoundThem) {
  arm_.joints[4].position_rad = 0.3;
  driver::CommandFrame frame = position_frame(0.1);
  frame.joints[4].kind = JointCommandKind::kNone;
  (void)plan_at(frame, 0);
  arm_.joints[4].position_rad = 0.25;  // sags a little: the hold target must not follow
  const OutgoingFrames out = plan_at(frame, 5 * kMs);
  const auto* pair = std::find_if(out.frames.begin(), out.frames.end(),
                                  [](const CanMessage& m) { return m.id == can_id::kJointTarget + 2; });
  ASSERT_NE(pair, out.frames.end());
  EXPECT_NEAR(decoded<JointTargetPair>(*pair).first_rad, 0.3, 1e-4);
}

TEST_F(CommandStreamerTest, EstopSendsOnlyTheStopThenResumeOnReset) {
  (void)plan_at(position_frame(0.1), 0);
  driver::CommandFrame stopped = position_frame(0.1);
  stopped.estop = true;
  const OutgoingFrames stop = plan_at(stopped, 1 * kMs);
  ASSERT_EQ(stop.count, 1U);
  EXPECT_EQ(stop.frames[0].id, can_id::kMotionControl);
  EXPECT_EQ(stop.frames[0].data[0], 0x01);
  EXPECT_EQ(plan_at(stopped, 2 * kMs).count, 0U);
  EXPECT_EQ(plan_at(stopped, 102 * kMs).count, 1U);  // repeated every 100 ms

  const OutgoingFrames resumed = plan_at(position_frame(0.1), 103 * kMs);
  ASSERT_GE(resumed.count, 1U);
  EXPECT_EQ(resumed.frames[0].id, can_id::kMotionControl);
  EXPECT_EQ(resumed.frames[0].data[0], 0x02);
  EXPECT_EQ(count_id(resumed, can_id::kModeControl), 1U);  // the arm is back in standby: mode again
  // The resume disables the motors: enable follows once the arm had time to process it.
  EXPECT_EQ(count_id(resumed, can_id::kMotorEnable), 0U);
  EXPECT_EQ(count_id(plan_at(position_frame(0.1), 204 * kMs), can_id::kMotorEnable), 1U);
}

TEST_F(CommandStreamerTest, ReleaseDisablesOnlyWhenConfigured) {
  (void)plan_at(position_frame(0.1), 0);
  EXPECT_EQ(count_id(plan_at(position_frame(0.1, /*owned=*/false), 1 * kMs), can_id::kMotorEnable), 0U);

  params_.disable_on_release = true;
  streamer_.configure(params_, params_.codec);
  (void)plan_at(position_frame(0.1), 0);
  const OutgoingFrames out = plan_at(position_frame(0.1, /*owned=*/false), 1 * kMs);
  ASSERT_EQ(count_id(out, can_id::kMotorEnable), 1U);
  EXPECT_EQ(out.frames[0].data[1], 0x01);  // disable
}

TEST_F(CommandStreamerTest, ManualEnableNeverSendsEnable) {
  params_.enable = EnablePolicy::kManual;
  streamer_.configure(params_, params_.codec);
  std::size_t enables = 0;
  for (int tick = 0; tick < 300; ++tick)
    enables += count_id(plan_at(position_frame(0.1), tick * kMs), can_id::kMotorEnable);
  EXPECT_EQ(enables, 0U);
}

TEST_F(CommandStreamerTest, HeldForAnOpStreamsNothingUntilASessionOwnsJoints) {
  EXPECT_EQ(plan_at(position_frame(0.1, /*owned=*/false), 0, /*hold_ops=*/true).count, 0U);
  EXPECT_GT(count_id(plan_at(position_frame(0.1, /*owned=*/true), 5 * kMs, /*hold_ops=*/true), can_id::kJointTarget),
            0U);
}

TEST_F(CommandStreamerTest, GripperGoesOutOnChangeAndEvery100Ms) {
  driver::CommandFrame frame = position_frame(0.1);
  frame.joints[6] = {.kind = JointCommandKind::kPosition, .owned = true, .position_rad = 0.03};
  std::size_t gripper_frames = 0;
  for (int tick = 0; tick < 1000; ++tick) {
    frame.joints[6].position_rad = tick < 500 ? 0.03 : 0.04;
    gripper_frames += count_id(plan_at(frame, tick * kMs), can_id::kGripperControl);
  }
  // 2 changes + 8 refreshes, and 10 enables (the arm never reports itself enabled here).
  EXPECT_EQ(gripper_frames, 20U);
  const OutgoingFrames late = plan_at(frame, 2000 * kMs);
  // The last gripper frame is the command (an enable companion carries the measured stroke).
  const std::vector<CanMessage> frames = frames_of(late);
  const auto gripper =
      std::find_if(frames.rbegin(), frames.rend(), [](const CanMessage& m) { return m.id == can_id::kGripperControl; });
  ASSERT_NE(gripper, frames.rend());
  EXPECT_NEAR(decoded<GripperControl>(*gripper).stroke_m, 0.04, 1e-6);
}

}  // namespace
}  // namespace robotd::piper
