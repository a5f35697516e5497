// The arm state the driver assembles from feedback: frames with impossible values are dropped,
// as the SDK's abnormal-data filter drops them, and counted.
#include "driver/arm_state.hpp"

#include <gtest/gtest.h>

#include "codec/piper_frames.hpp"

namespace robotd::piper {
namespace {

TEST(PiperArmState, ImpossibleJointFeedbackIsDroppedAndCounted) {
  ArmState state;
  constexpr double kRadPerMilliDeg = 3.141592653589793 / 180000.0;
  apply_frame(state, JointFeedbackPair{.pair = 0, .first_rad = 0.5, .second_rad = -0.25}, 1);
  EXPECT_FALSE(apply_frame(state, JointFeedbackPair{.pair = 0, .first_rad = 3000001 * kRadPerMilliDeg}, 2));
  EXPECT_EQ(state.implausible_frames, 1U);
  EXPECT_DOUBLE_EQ(state.joints[0].position_rad, 0.5);  // the previous value stays, as in the SDK
  EXPECT_DOUBLE_EQ(state.joints[1].position_rad, -0.25);
  EXPECT_EQ(state.last_joints_ns, 1);

  apply_frame(state, JointFeedbackPair{.pair = 0, .first_rad = 3000000 * kRadPerMilliDeg}, 3);  // the limit itself
  EXPECT_EQ(state.implausible_frames, 1U);
  EXPECT_EQ(state.last_joints_ns, 3);
}

TEST(PiperArmState, ImpossiblePoseAndGripperAreDropped) {
  ArmState state;
  apply_frame(state, EndPoseFeedbackPart{.part = 0, .first = 0.2, .second = 0.1}, 1);
  apply_frame(state, EndPoseFeedbackPart{.part = 0, .first = 1.000001, .second = 0.1}, 2);  // beyond 1 m
  apply_frame(state, EndPoseFeedbackPart{.part = 2, .first = 6.31, .second = 0}, 3);        // beyond 361°
  apply_frame(state, GripperFeedback{.stroke_m = 0.150001}, 4);                             // beyond 150 mm
  EXPECT_EQ(state.implausible_frames, 3U);
  EXPECT_DOUBLE_EQ(state.end_pose.x_m, 0.2);
  EXPECT_DOUBLE_EQ(state.end_pose.ry_rad, 0.0);
  EXPECT_FALSE(state.gripper_seen);
}

}  // namespace
}  // namespace robotd::piper
