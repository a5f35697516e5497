// Joint and Cartesian moves on a session (robotd/motion/session_moves.hpp) through a real robotd:
// the simulated arm stands in for a PiPER (kinematic_model "piper"), so the moves are planned on
// the PiPER's model and the sim arm's limits. Where the arm ends is checked with the model's
// forward kinematics of the measured joints.
#include "robotd/motion/session_moves.hpp"

#include <atomic>
#include <chrono>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "robotd_fixture.hpp"
#include "robotd_process.hpp"

namespace robotd::testing {
namespace {

using namespace std::chrono_literals;

constexpr double kJointToleranceRad = 0.003;  // the moves' 0.1° arrival, and the sim's settling
constexpr double kMovePositionToleranceM = 1e-3;
// A PiPER posture clear of its singularities (the wrist is bent): the Cartesian moves start here.
/// A posture well clear of the PiPER model's singularities.
std::vector<double> bent() { return {0.2, 1.0, -1.0, 0.1, 0.6, 0.1}; }

class SessionMovesTest : public RobotdTest {
 protected:
  void SetUp() override {
    nlohmann::json params = sim_arm_params();
    params["kinematic_model"] = "piper";
    start_robotd(sim_arm_config(domain_.id(), params));
    session_.emplace(acquire_device("arm"));
    model_ = kinematics::find_arm_model("piper");
    ASSERT_NE(model_, nullptr);
  }
  void TearDown() override {
    session_.reset();
    RobotdTest::TearDown();
  }

  Eigen::Isometry3d tool_pose_now() {
    const std::vector<double> q = joint_state().position;
    kinematics::ArmJoints joints{};
    for (std::size_t j = 0; j < q.size(); ++j) joints[j] = q[j];
    return kinematics::tool_pose(*model_, joints);
  }
  void expect_joints_at(const std::vector<double>& target) {
    const std::vector<double> q = joint_state().position;
    ASSERT_EQ(q.size(), target.size());
    for (std::size_t j = 0; j < q.size(); ++j) EXPECT_NEAR(q[j], target[j], kJointToleranceRad) << "joint " << j;
  }
  void move_to_bent() {
    const auto report = motion::move_joints(client(), *session_, bent(), {.duration_s = 1.0});
    ASSERT_TRUE(report) << report.error().message;
    ASSERT_EQ(report.value().end, motion::StreamEnd::kCompleted);
  }

  std::optional<Session> session_;
  const kinematics::ArmModel* model_ = nullptr;
};

TEST_F(SessionMovesTest, AJointMoveEndsAtItsTarget) {
  const auto report =
      motion::move_joints(client(), *session_, bent(), {.speed_percent = 50, .acceleration_percent = 50});
  ASSERT_TRUE(report) << report.error().message;
  EXPECT_EQ(report.value().end, motion::StreamEnd::kCompleted);
  EXPECT_EQ(report.value().fraction_done, 1.0);
  EXPECT_NE(report.value().summary.find("arrived"), std::string::npos) << report.value().summary;
  expect_joints_at(bent());
}

TEST_F(SessionMovesTest, APoseMoveAndAStraightLineBringTheToolToTheirGoals) {
  move_to_bent();
  const Eigen::Isometry3d start = tool_pose_now();
  Eigen::Isometry3d shifted = start;
  shifted.translation() += Eigen::Vector3d(0.03, -0.02, 0.01);

  const auto pose_move =
      motion::move_cartesian(client(), *session_, kinematics::pose_of(model_->euler, shifted), {.duration_s = 1.0});
  ASSERT_TRUE(pose_move) << pose_move.error().message;
  EXPECT_EQ(pose_move.value().end, motion::StreamEnd::kCompleted);
  EXPECT_LT((tool_pose_now().translation() - shifted.translation()).norm(), kMovePositionToleranceM);

  const auto line =
      motion::move_cartesian(client(), *session_, kinematics::pose_of(model_->euler, start),
                             {.duration_s = 1.0, .shape = motion::Shape::kTrapezoid}, motion::CartesianPath::kLine);
  ASSERT_TRUE(line) << line.error().message;
  EXPECT_EQ(line.value().end, motion::StreamEnd::kCompleted);
  EXPECT_LT((tool_pose_now().translation() - start.translation()).norm(), kMovePositionToleranceM);
  expect_joints_at(bent());  // IK seeded along the line stays on the branch it started on
}

TEST_F(SessionMovesTest, AGoalOutOfReachIsRefusedBeforeAnythingMoves) {
  move_to_bent();
  kinematics::EulerPose far;
  far.position_m = {2.0, 0, 0.3};  // the PiPER reaches about 0.65 m
  const auto report = motion::move_cartesian(client(), *session_, far);
  ASSERT_FALSE(report);
  EXPECT_EQ(report.error().code, ErrorCode::kInvalidArgument);
  expect_joints_at(bent());
}

TEST_F(SessionMovesTest, ATargetOfTheWrongSizeSaysHowManyJointsTheDeviceHas) {
  const auto report = motion::move_joints(client(), *session_, {0.1, 0.2});
  ASSERT_FALSE(report);
  EXPECT_EQ(report.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(report.error().message.find("2 joint value(s); device 'arm' has 6 joints"), std::string::npos)
      << report.error().message;
}

TEST_F(SessionMovesTest, ASessionOnSomeJointsOnlyIsRefused) {
  session_.reset();
  Session some = acquire_device("arm", {0, 1});
  const auto report = motion::move_joints(client(), some, bent());
  ASSERT_FALSE(report);
  EXPECT_EQ(report.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(report.error().message.find("the arm's joints of device 'arm'"), std::string::npos)
      << report.error().message;
}

TEST_F(SessionMovesTest, AStopFlagAlreadySetEndsTheMoveWithTheArmHeld) {
  const std::vector<double> start = joint_state().position;
  const std::atomic<bool> stop{true};
  const auto report = motion::move_joints(client(), *session_, bent(), {}, &stop);
  ASSERT_TRUE(report) << report.error().message;
  EXPECT_EQ(report.value().end, motion::StreamEnd::kStopped);
  expect_joints_at(start);
}

}  // namespace
}  // namespace robotd::testing
