// What robotctl replay takes from a recording and how it checks it against a device's
// current limits, before anything moves.
#include "recording/replay_plan.hpp"

#include <filesystem>
#include <optional>

#include <gtest/gtest.h>

#include "recording/recording_reader.hpp"
#include "recording_test_files.hpp"

namespace robotctl::recording {
namespace {

using testing::position_command;
using testing::TemporaryPath;

constexpr std::int64_t kNsPerMs = 1'000'000;

// The device as robotd describes it now: the recorded arm, with `position_max` and `velocity_max`.
robotd::DeviceInfo current_arm(double position_max = 1.0, double velocity_max = 1.0) {
  robotd::DeviceInfo device;
  device.name = "arm";
  device.joint_names = {"shoulder", "elbow"};
  device.position_min = {-position_max, -position_max};
  device.position_max = {position_max, position_max};
  device.velocity_max = {velocity_max, velocity_max};
  return device;
}

class ReplayPlanTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto created = RecordingWriter::create(path_.str(), testing::arm_description());
    ASSERT_TRUE(created) << created.error().message;
    writer_.emplace(std::move(created.value()));
  }

  void command(std::int64_t time_ns, const ControlCommandRecord& record) {
    testing::append(*writer_, RecordKind::kControlCommand, time_ns, record);
  }

  // Motor 0 from 0 to `end_rad` in 10 ms steps over one second; motor 1 stays at 0.
  void ramp(double end_rad) {
    for (int i = 0; i <= 100; ++i) {
      command(i * (10 * kNsPerMs), position_command({0, 1}, {static_cast<float>(end_rad * i / 100.0), 0.0F}));
    }
  }

  robotd::Result<ReplayPlan> plan(const std::vector<std::int32_t>& motor_ids = {}, const std::string& device = "arm") {
    EXPECT_TRUE(writer_->finish(2000 * kNsPerMs));
    auto reader = RecordingReader::open(path_.str());
    if (!reader) return reader.error();
    return read_replay_plan(reader.value(), device, motor_ids);
  }

  TemporaryPath path_;
  std::optional<RecordingWriter> writer_;
};

TEST_F(ReplayPlanTest, PositionCommandsOfTheDeviceBecomeStepsAtTheirRecordedTimes) {
  command(5 * kNsPerMs, position_command({0, 1}, {0.1F, 0.2F}));
  command(15 * kNsPerMs, position_command({1}, {0.3F}));
  const auto replay = plan();
  ASSERT_TRUE(replay) << replay.error().message;
  ASSERT_EQ(replay.value().steps.size(), 2U);
  EXPECT_EQ(replay.value().steps[1].time_ns, 15 * kNsPerMs);
  EXPECT_EQ(replay.value().steps[1].motor_ids, (std::vector<std::int32_t>{1}));
  EXPECT_EQ(replay.value().motor_ids, (std::vector<std::int32_t>{0, 1}));
  EXPECT_EQ(replay.value().start_rad, (std::vector<double>{0.1F, 0.2F}));
  EXPECT_DOUBLE_EQ(replay.value().recorded_duration_s(), 0.010);
  EXPECT_EQ(replay.value().ending, "");
}

TEST_F(ReplayPlanTest, KeepalivesAreCountedNotReplayed) {
  command(1 * kNsPerMs, position_command({0}, {0.1F}));
  command(2 * kNsPerMs, position_command({}, {}));
  const auto replay = plan();
  ASSERT_TRUE(replay);
  EXPECT_EQ(replay.value().steps.size(), 1U);
  EXPECT_EQ(replay.value().keepalives, 1U);
}

TEST_F(ReplayPlanTest, MotorsOptionKeepsOnlyThoseMotors) {
  command(1 * kNsPerMs, position_command({0, 1}, {0.1F, 0.2F}));
  const auto replay = plan({1});
  ASSERT_TRUE(replay);
  EXPECT_EQ(replay.value().motor_ids, (std::vector<std::int32_t>{1}));
  EXPECT_EQ(replay.value().steps.at(0).positions, (std::vector<float>{0.2F}));
}

TEST_F(ReplayPlanTest, MotorTheRecordingNeverCommandsIsRefused) {
  command(1 * kNsPerMs, position_command({0}, {0.1F}));
  const auto replay = plan({0, 1});
  ASSERT_FALSE(replay);
  EXPECT_NE(replay.error().message.find("no position command for motor 1"), std::string::npos)
      << replay.error().message;
}

TEST_F(ReplayPlanTest, TorqueCommandsAreRefusedSayingReplayIsPositionOnly) {
  command(1 * kNsPerMs, position_command({0}, {0.1F}));
  ControlCommandRecord mixed = position_command({0}, {0.1F});
  mixed.values.torques = {0.5F};
  command(250 * kNsPerMs, mixed);
  const auto replay = plan();
  ASSERT_FALSE(replay);
  EXPECT_NE(replay.error().message.find("1 commands for 'arm' carry torques"), std::string::npos)
      << replay.error().message;
  EXPECT_NE(replay.error().message.find("t=0.250 s"), std::string::npos) << replay.error().message;
  EXPECT_NE(replay.error().message.find("position commands only"), std::string::npos);
}

TEST_F(ReplayPlanTest, DeviceTheRecordingDoesNotHaveIsRefusedListingWhatItHas) {
  command(1 * kNsPerMs, position_command({0}, {0.1F}));
  const auto replay = plan({}, "gripper");
  ASSERT_FALSE(replay);
  EXPECT_NE(replay.error().message.find("recorded no device 'gripper' (it recorded 'arm')"), std::string::npos)
      << replay.error().message;
}

TEST_F(ReplayPlanTest, RecordingWithoutCommandsIsRefused) {
  testing::append(*writer_, RecordKind::kJointState, 1, JointStateRecord{0, 0, {0.0, 0.0}, {}, {}});
  const auto replay = plan();
  ASSERT_FALSE(replay);
  EXPECT_NE(replay.error().message.find("has no position commands for 'arm'"), std::string::npos)
      << replay.error().message;
}

TEST_F(ReplayPlanTest, CommandsOfOtherDevicesAreLeftOut) {
  command(1 * kNsPerMs, position_command({0}, {0.1F}));
  ControlCommandRecord unknown = position_command({0}, {0.9F});
  unknown.device = kUnknownDevice;
  command(2 * kNsPerMs, unknown);
  const auto replay = plan();
  ASSERT_TRUE(replay);
  EXPECT_EQ(replay.value().steps.size(), 1U);
}

TEST_F(ReplayPlanTest, CommandWithoutOnePositionPerMotorIsRefused) {
  command(1 * kNsPerMs, position_command({0, 1}, {0.1F}));
  const auto replay = plan();
  ASSERT_FALSE(replay);
  EXPECT_NE(replay.error().message.find("has 1 positions for 2 motor ids"), std::string::npos)
      << replay.error().message;
}

TEST_F(ReplayPlanTest, RampWithinTheLimitsPassesAndReportsPeakVelocity) {
  ramp(0.5);  // 0.5 rad/s
  const auto replay = plan();
  ASSERT_TRUE(replay);
  const ReplayCheck check = check_replay(replay.value(), current_arm(), 1.0);
  EXPECT_TRUE(check.violations.empty()) << check.violations.at(0);
  EXPECT_DOUBLE_EQ(check.duration_s, 1.0);
  ASSERT_EQ(check.motors.size(), 2U);
  EXPECT_EQ(check.motors[0].joint, "shoulder");
  EXPECT_NEAR(check.motors[0].peak_velocity_rad_s, 0.5, 1e-3);
  EXPECT_NEAR(check.motors[0].max_rad, 0.5, 1e-6);
  EXPECT_DOUBLE_EQ(check.motors[0].velocity_limit_rad_s, 1.0);
}

TEST_F(ReplayPlanTest, SpeedScalesDurationAndVelocity) {
  ramp(0.5);
  const auto replay = plan();
  ASSERT_TRUE(replay);
  const ReplayCheck check = check_replay(replay.value(), current_arm(), 4.0);
  EXPECT_DOUBLE_EQ(check.duration_s, 0.25);
  EXPECT_NEAR(check.motors[0].peak_velocity_rad_s, 2.0, 4e-3);
  ASSERT_EQ(check.violations.size(), 1U);
  EXPECT_NE(check.violations[0].find("motor 0 (shoulder): velocity"), std::string::npos) << check.violations[0];
  EXPECT_NE(check.violations[0].find("beyond its velocity_max 1.000 rad/s"), std::string::npos) << check.violations[0];
}

TEST_F(ReplayPlanTest, PositionBeyondTheLimitIsOneViolationPerRunWithTheWorstValue) {
  ramp(0.5);
  command(1100 * kNsPerMs, position_command({0}, {1.2F}));
  command(1200 * kNsPerMs, position_command({0}, {1.4F}));
  command(1300 * kNsPerMs, position_command({0}, {0.9F}));
  const auto replay = plan();
  ASSERT_TRUE(replay);
  const ReplayCheck check = check_replay(replay.value(), current_arm(1.0, 10.0), 1.0);
  ASSERT_EQ(check.violations.size(), 1U) << check.violations.at(1);
  const std::string& violation = check.violations[0];
  EXPECT_NE(violation.find("motor 0 (shoulder): position 1.200 rad is beyond its maximum 1.000 rad at t=1.100 s"),
            std::string::npos)
      << violation;
  EXPECT_NE(violation.find("worst 1.400 rad at t=1.200 s; 2 commands until t=1.200 s"), std::string::npos) << violation;
}

TEST_F(ReplayPlanTest, PositionBelowTheMinimumIsAViolation) {
  command(1 * kNsPerMs, position_command({1}, {-2.0F}));
  const auto replay = plan();
  ASSERT_TRUE(replay);
  const ReplayCheck check = check_replay(replay.value(), current_arm(), 1.0);
  ASSERT_EQ(check.violations.size(), 1U);
  EXPECT_NE(check.violations[0].find("motor 1 (elbow): position -2.000 rad is beyond its minimum -1.000 rad"),
            std::string::npos)
      << check.violations[0];
}

TEST_F(ReplayPlanTest, JitterOfSingleCommandsIsNotSpeed) {
  // 0.5 rad/s, but two commands arrived 0.1 ms apart: over one such pair it would look like 50 rad/s.
  for (int i = 0; i <= 100; ++i) {
    const std::int64_t jitter_ns = i == 50 ? 9'900'000 : 0;
    command(i * (10 * kNsPerMs) - jitter_ns, position_command({0}, {static_cast<float>(0.005 * i)}));
  }
  const auto replay = plan();
  ASSERT_TRUE(replay);
  const ReplayCheck check = check_replay(replay.value(), current_arm(), 1.0);
  EXPECT_TRUE(check.violations.empty()) << check.violations.at(0);
  EXPECT_LT(check.motors[0].peak_velocity_rad_s, 0.8);
}

ControlCommandRecord stamped(std::int64_t stamp_ns, float position_rad) {
  ControlCommandRecord command = position_command({0}, {position_rad});
  command.stamp_ns = stamp_ns;
  return command;
}

TEST_F(ReplayPlanTest, SendersStampsPaceTheReplayWhenEveryCommandHasThem) {
  // Sent every 10 ms at 0.5 rad/s, received in bursts of five by a busy recorder.
  constexpr std::int64_t kSentAt = 1'700'000'000'000'000'000;
  for (int i = 0; i <= 100; ++i) {
    command((i / 5) * (50 * kNsPerMs), stamped(kSentAt + i * (10 * kNsPerMs), static_cast<float>(0.005 * i)));
  }
  const auto replay = plan();
  ASSERT_TRUE(replay);
  EXPECT_EQ(replay.value().pace_clock, PaceClock::kSenderStamps);
  EXPECT_EQ(replay.value().steps[7].pace_ns, 70 * kNsPerMs);
  EXPECT_EQ(replay.value().steps[7].time_ns, 50 * kNsPerMs);
  EXPECT_DOUBLE_EQ(replay.value().recorded_duration_s(), 1.0);
  const ReplayCheck check = check_replay(replay.value(), current_arm(), 1.0);
  EXPECT_NEAR(check.motors[0].peak_velocity_rad_s, 0.5, 1e-3);
}

TEST_F(ReplayPlanTest, StampsThatGoBackLeaveTheReceiveTimesAsThePace) {
  command(10 * kNsPerMs, stamped(2'000 * kNsPerMs, 0.1F));
  command(20 * kNsPerMs, stamped(1'000 * kNsPerMs, 0.2F));  // another sender, whose clock is behind
  const auto replay = plan();
  ASSERT_TRUE(replay);
  EXPECT_EQ(replay.value().pace_clock, PaceClock::kReceiveTimes);
  EXPECT_EQ(replay.value().steps[1].pace_ns, 10 * kNsPerMs);
}

TEST_F(ReplayPlanTest, OtherJointCountNamesAndMissingMotorsAreViolations) {
  command(1 * kNsPerMs, position_command({0, 1}, {0.0F, 0.0F}));
  const auto replay = plan();
  ASSERT_TRUE(replay);
  robotd::DeviceInfo one_joint;
  one_joint.name = "arm";
  one_joint.joint_names = {"wrist"};
  one_joint.position_min = {-1};
  one_joint.position_max = {1};
  const ReplayCheck check = check_replay(replay.value(), one_joint, 1.0);
  ASSERT_EQ(check.violations.size(), 3U);
  EXPECT_EQ(check.violations[0], "'arm' has 1 joints on robotd; the recording's had 2");
  EXPECT_EQ(check.violations[1], "joint 0 is 'shoulder' in the recording and 'wrist' on robotd");
  EXPECT_EQ(check.violations[2], "motor 1 does not exist on 'arm' (it has motors 0..0)");
}

TEST_F(ReplayPlanTest, TruncatedRecordingIsPlannedUpToItsLastCompleteRecordAndSaysSo) {
  command(1 * kNsPerMs, position_command({0}, {0.1F}));
  command(2 * kNsPerMs, position_command({0}, {0.2F}));
  ASSERT_TRUE(writer_->flush());
  std::filesystem::resize_file(path_.str(), testing::file_size(path_.str()) - 3);
  auto reader = RecordingReader::open(path_.str());
  ASSERT_TRUE(reader);
  const auto replay = read_replay_plan(reader.value(), "arm", {});
  ASSERT_TRUE(replay) << replay.error().message;
  EXPECT_EQ(replay.value().steps.size(), 1U);
  EXPECT_NE(replay.value().ending.find("cut short"), std::string::npos) << replay.value().ending;
}

}  // namespace
}  // namespace robotctl::recording
