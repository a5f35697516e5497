// FramePlanner: which frame the driver sends the PAROL6 board in one exchange.
#include "driver/frame_planner.hpp"

#include <gtest/gtest.h>

#include "codec/joint_units.hpp"

namespace robotd::parol6 {
namespace {

using driver::JointCommandKind;

RobotFrame homed_board_at_standby() {
  RobotFrame board;
  board.homed = 0xFF;
  board.io = 0x0F;  // E-stop released
  for (int j = 0; j < kJoints; ++j) {
    board.position_steps[static_cast<std::size_t>(j)] = joint_units()[static_cast<std::size_t>(j)].standby_steps;
  }
  return board;
}

driver::CommandFrame session_targets(double q1, bool owned = true) {
  driver::CommandFrame command;
  command.joint_count = kJoints;
  const RobotFrame board = homed_board_at_standby();
  for (int j = 0; j < kJoints; ++j) {
    const auto index = static_cast<std::size_t>(j);
    command.joints[index] = {.kind = JointCommandKind::kPosition,
                             .owned = owned,
                             .position_rad = steps_to_rad(j, board.position_steps[index])};
  }
  command.joints[0].position_rad = q1;
  return command;
}

class FramePlannerTest : public ::testing::Test {
 protected:
  HostFrame plan(const driver::CommandFrame& command, OneShot one_shot = OneShot::kNone,
                 const StepTarget* trajectory = nullptr) {
    PlannerInput input;
    input.command = &command;
    input.board = &board_;
    input.one_shot = one_shot;
    input.trajectory = trajectory;
    input.peripherals.out1 = true;
    input.peripherals.gripper_position = 128;
    return planner_.plan(input);
  }
  FramePlanner planner_{0.01};
  RobotFrame board_ = homed_board_at_standby();
};

TEST_F(FramePlannerTest, NoSessionIsIdleAtTheMeasuredPositionWithPeripherals) {
  driver::CommandFrame nobody;
  nobody.joint_count = kJoints;
  const HostFrame frame = plan(nobody);
  EXPECT_EQ(frame.command, command::kIdle);
  EXPECT_EQ(frame.position_steps, board_.position_steps);
  EXPECT_EQ(frame.speed_steps_s, (std::array<std::int32_t, kJoints>{}));
  EXPECT_EQ(frame.io, io::kOut1);
  EXPECT_EQ(frame.gripper_position, 128);
}

TEST_F(FramePlannerTest, SessionTargetsGoOutOnePeriodAheadWithTheirSpeed) {
  const double q0 = steps_to_rad(0, board_.position_steps[0]);
  (void)plan(session_targets(q0));
  const double v = 0.5;  // rad/s: the target moves 5 mrad per exchange
  const HostFrame frame = plan(session_targets(q0 + v * 0.01));
  EXPECT_EQ(frame.command, command::kGoToPosition);
  EXPECT_EQ(frame.position_steps[0], rad_to_steps(0, q0 + 2 * v * 0.01));
  EXPECT_EQ(frame.speed_steps_s[0], rad_per_s_to_steps_per_s(0, v));
  EXPECT_EQ(frame.speed_steps_s[1], 0);
  EXPECT_TRUE(planner_.streaming_session());
}

TEST_F(FramePlannerTest, SessionCommandsWaitForHoming) {
  board_.homed = 0x03;
  const HostFrame frame = plan(session_targets(1.0));
  EXPECT_EQ(frame.command, command::kIdle) << "an unhomed arm's positions mean nothing";
  EXPECT_FALSE(planner_.streaming_session());
}

TEST_F(FramePlannerTest, EstopDisablesEveryFrameThenEnablesOnceOnReset) {
  driver::CommandFrame command = session_targets(1.0);
  command.estop = true;
  for (int i = 0; i < 3; ++i) {
    const HostFrame frame = plan(command);
    EXPECT_EQ(frame.command, command::kDisable);
    EXPECT_NE(frame.gripper_command & gripper_command::kEstop, 0);
  }
  command.estop = false;
  EXPECT_EQ(plan(command).command, command::kEnable);
  EXPECT_EQ(plan(command).command, command::kGoToPosition);
}

TEST_F(FramePlannerTest, TheBoardsEstopInputDisablesToo) {
  board_.io = 0x07;  // E-stop bit 0: pressed
  EXPECT_EQ(plan(session_targets(1.0)).command, command::kDisable);
}

TEST_F(FramePlannerTest, HomeGoesOutTenTimesThenIdleLetsItRun) {
  driver::CommandFrame nobody;
  nobody.joint_count = kJoints;
  EXPECT_EQ(plan(nobody, OneShot::kHome).command, command::kHome);
  for (int i = 0; i < 9; ++i) EXPECT_EQ(plan(nobody).command, command::kHome) << i;
  EXPECT_EQ(plan(nobody).command, command::kIdle);
}

TEST_F(FramePlannerTest, OneShotsGoOutOnce) {
  driver::CommandFrame nobody;
  nobody.joint_count = kJoints;
  EXPECT_EQ(plan(nobody, OneShot::kEnable).command, command::kEnable);
  EXPECT_EQ(plan(nobody).command, command::kIdle);
  EXPECT_EQ(plan(nobody, OneShot::kClearError).command, command::kClearError);
  EXPECT_EQ(plan(nobody, OneShot::kDisable).command, command::kDisable);
}

TEST_F(FramePlannerTest, ATrajectorySampleGoesOutAsItIs) {
  driver::CommandFrame nobody;
  nobody.joint_count = kJoints;
  StepTarget sample;
  sample.position_steps = {1, 2, 3, 4, 5, 6};
  sample.speed_steps_s = {10, 20, 30, 40, 50, 60};
  const HostFrame frame = plan(nobody, OneShot::kNone, &sample);
  EXPECT_EQ(frame.command, command::kGoToPosition);
  EXPECT_EQ(frame.position_steps, sample.position_steps);
  EXPECT_EQ(frame.speed_steps_s, sample.speed_steps_s);
}

TEST_F(FramePlannerTest, NeverJogs) {
  // Whatever robotd asks, the frame left on the board must not keep the motors turning.
  driver::CommandFrame command = session_targets(1.0);
  for (int i = 0; i < 100; ++i) {
    command.joints[0].position_rad += 0.01;
    EXPECT_NE(plan(command).command, command::kJog);
  }
}

}  // namespace
}  // namespace robotd::parol6
