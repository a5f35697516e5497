// Pose, line and tool-frame moves on the arm models: a pose move ends on its goal, a line's
// every sample is on the line where its profile puts it, the line keeps to the joint limits and
// speeds and stops before a singularity saying where, a tool-frame move moves along the tool's
// own axes, and an unreachable goal is a clear error.
#include "robotd/motion/cartesian_move.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <stdexcept>
#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include "robotd/kinematics/arm_model.hpp"
#include "robotd/motion/path_profile.hpp"

namespace robotd::motion {
namespace {

using kinematics::ArmJoints;
using kinematics::ArmModel;

constexpr double kLineDt = 0.01;
constexpr double kDegree = std::numbers::pi / 180.0;

const ArmModel& model(std::string_view name) {
  const ArmModel* found = kinematics::find_arm_model(name);
  if (found == nullptr) throw std::invalid_argument("no arm model " + std::string(name));
  return *found;
}

/// The model's own position limits, 1.5 rad/s and 5 rad/s² on every joint.
JointLimits limits_of(const ArmModel& arm) {
  JointLimits limits;
  for (std::size_t j = 0; j < arm.dof; ++j) {
    limits.min_rad.push_back(arm.min_rad[j]);
    limits.max_rad.push_back(arm.max_rad[j]);
    limits.max_speed_rad_s.push_back(1.5);
    limits.max_acceleration_rad_s2.push_back(5.0);
  }
  return limits;
}

Joints degrees(std::initializer_list<double> values) {
  Joints q;
  for (const double value : values) q.push_back(value * kDegree);
  return q;
}

ArmJoints arm(const Joints& q) {
  ArmJoints joints{};
  std::copy(q.begin(), q.end(), joints.begin());
  return joints;
}

Eigen::Isometry3d pose_at(const ArmModel& model, const Joints& q) { return kinematics::tool_pose(model, arm(q)); }

double angle_between(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle();
}

/// A regular PAROL6 posture, well inside its limits and away from its singularities.
Joints parol6_working() { return degrees({10, -60, 200, 20, -30, 100}); }

/// `pose` moved by `offset` (m) in the base frame and turned by `turn` about `axis` (base frame).
Eigen::Isometry3d moved(const Eigen::Isometry3d& pose, const Eigen::Vector3d& offset, double turn,
                        const Eigen::Vector3d& axis) {
  Eigen::Isometry3d result = pose;
  result.translation() += offset;
  result.linear() = Eigen::AngleAxisd(turn, axis.normalized()).toRotationMatrix() * pose.linear();
  return result;
}

/// Every sample's tool pose is where the profile puts it on the line from `start` to `goal`.
void expect_on_the_line(const ArmModel& arm, const Trajectory& trajectory, const Eigen::Isometry3d& start,
                        const Eigen::Isometry3d& goal) {
  const PathProfile profile = PathProfile::over(trajectory.shape, trajectory.duration_s);
  const Eigen::Quaterniond from(start.linear());
  const Eigen::Quaterniond to(goal.linear());
  for (std::size_t k = 0; k < trajectory.positions.size(); ++k) {
    const double s = profile.position(static_cast<double>(k) * kLineDt);
    const Eigen::Isometry3d tool = pose_at(arm, trajectory.positions[k]);
    const Eigen::Vector3d expected = start.translation() + s * (goal.translation() - start.translation());
    EXPECT_LT((tool.translation() - expected).norm(), 1e-6) << "sample " << k;
    Eigen::Isometry3d expected_pose = Eigen::Isometry3d::Identity();
    expected_pose.linear() = from.slerp(s, to).toRotationMatrix();
    EXPECT_LT(angle_between(tool, expected_pose), 1e-5) << "sample " << k;
  }
}

TEST(PoseMove, SolvesTheGoalThenMovesByTheJointRules) {
  const ArmModel& parol6 = model("parol6");
  const Joints from = parol6_working();
  const Eigen::Isometry3d goal = pose_at(parol6, degrees({20, -50, 190, 10, -40, 110}));
  const Result<Trajectory> planned =
      plan_pose_move(parol6, from, goal, {.duration_s = 2.0}, limits_of(parol6), kLineDt);
  ASSERT_TRUE(planned.ok()) << planned.error().message;
  EXPECT_EQ(planned.value().shape, Shape::kPolynomial);  // t alone: "poly"
  EXPECT_EQ(planned.value().positions.size(), 201U);
  EXPECT_EQ(planned.value().positions.front(), from);
  const Eigen::Isometry3d reached = pose_at(parol6, planned.value().positions.back());
  EXPECT_LT((reached.translation() - goal.translation()).norm(), 1e-4);
  EXPECT_LT(angle_between(reached, goal), 1e-3);
  EXPECT_EQ(planned.value().how.rfind("IK, then quintic polynomial", 0), 0U) << planned.value().how;
}

TEST(PoseMove, VAndAMakeTheLeadingJointTrapezoid) {
  const ArmModel& parol6 = model("parol6");
  const Eigen::Isometry3d goal = pose_at(parol6, degrees({20, -50, 190, 10, -40, 110}));
  const Result<Trajectory> planned =
      plan_pose_move(parol6, parol6_working(), goal, {.speed_percent = 30.0, .acceleration_percent = 50.0},
                     limits_of(parol6), kLineDt);
  ASSERT_TRUE(planned.ok()) << planned.error().message;
  EXPECT_EQ(planned.value().shape, Shape::kTrapezoid);
  EXPECT_EQ(planned.value().how.rfind("IK, then trapezoid, leading joint", 0), 0U) << planned.value().how;
  double fastest = 0;  // the leading joint's share of its 1.5 rad/s
  for (const Joints& velocity : planned.value().velocities) {
    for (const double v : velocity) fastest = std::max(fastest, std::abs(v) / 1.5);
  }
  EXPECT_LE(fastest, 0.3 + 1e-12);
  EXPECT_GT(fastest, 0.29);
}

TEST(PoseMove, AnUnreachablePoseIsAClearError) {
  const ArmModel& parol6 = model("parol6");
  Eigen::Isometry3d far = pose_at(parol6, parol6_working());
  far.translation() = Eigen::Vector3d(1.5, 0.0, 0.3);  // the PAROL6 reaches about 0.45 m
  const Result<Trajectory> planned = plan_pose_move(parol6, parol6_working(), far, {}, limits_of(parol6), kLineDt);
  ASSERT_FALSE(planned.ok());
  EXPECT_EQ(
      planned.error().message.rfind("pose move: no joint solution within the joint limits reaches the goal pose", 0),
      0U)
      << planned.error().message;
}

TEST(LineMove, EverySampleIsOnTheLineWhereTheProfilePutsIt) {
  const ArmModel& parol6 = model("parol6");
  const Joints from = parol6_working();
  const Eigen::Isometry3d start = pose_at(parol6, from);
  const Eigen::Isometry3d goal = moved(start, {0.03, -0.02, 0.015}, 15 * kDegree, {1, 0, 0});
  for (const Shape shape : {Shape::kPolynomial, Shape::kTrapezoid}) {
    const Result<Trajectory> planned =
        plan_line_move(parol6, from, goal, {.duration_s = 2.0, .shape = shape}, limits_of(parol6), kLineDt);
    ASSERT_TRUE(planned.ok()) << planned.error().message;
    EXPECT_EQ(planned.value().shape, shape);
    EXPECT_EQ(planned.value().positions.size(), 201U);
    EXPECT_EQ(planned.value().positions.front(), from);
    expect_on_the_line(parol6, planned.value(), start, goal);
    EXPECT_EQ(planned.value().velocities.front(), Joints(6, 0.0));
    EXPECT_EQ(planned.value().velocities.back(), Joints(6, 0.0));
  }
}

TEST(LineMove, WithoutTTheToolCruisesAtItsSpeedOnAThirdsTrapezoid) {
  const ArmModel& parol6 = model("parol6");
  const Joints from = parol6_working();
  const Eigen::Isometry3d start = pose_at(parol6, from);
  const Eigen::Isometry3d goal = moved(start, {0.0, 0.0, 0.06}, 0.0, {0, 0, 1});
  const Result<Trajectory> planned = plan_line_move(parol6, from, goal, {}, limits_of(parol6), kLineDt);
  ASSERT_TRUE(planned.ok()) << planned.error().message;
  EXPECT_EQ(planned.value().shape, Shape::kTrapezoid);
  // 60 mm cruising at 50 mm/s in the middle third: 1.5 · 1.2 s.
  EXPECT_NEAR(planned.value().duration_s, 1.8, 1e-9);
  expect_on_the_line(parol6, planned.value(), start, goal);
  const std::size_t middle = planned.value().positions.size() / 2;
  const double speed = (pose_at(parol6, planned.value().positions[middle + 1]).translation() -
                        pose_at(parol6, planned.value().positions[middle]).translation())
                           .norm() /
                       kLineDt;
  EXPECT_NEAR(speed, kDefaultLinearSpeedMS, 1e-6);
}

TEST(LineMove, PlansArmsOfSevenJoints) {
  const ArmModel& xarm7 = model("xarm7");
  const Joints from = degrees({0, 20, 10, 60, 5, 40, 0});
  const Eigen::Isometry3d start = pose_at(xarm7, from);
  const Eigen::Isometry3d goal = moved(start, {-0.05, 0.04, -0.03}, 10 * kDegree, {0, 1, 0});
  const Result<Trajectory> planned = plan_line_move(xarm7, from, goal, {.duration_s = 2.0}, limits_of(xarm7), kLineDt);
  ASSERT_TRUE(planned.ok()) << planned.error().message;
  EXPECT_EQ(planned.value().positions.back().size(), 7U);
  expect_on_the_line(xarm7, planned.value(), start, goal);
}

TEST(LineMove, StopsBeforeASingularitySayingHowFarAlong) {
  // The PAROL6's wrist lines J4 up with J6 at J5 = 0. From J5 = 20° to the pose at J5 = −20° with
  // J4 turned 5°, the line passes next to J5 = 0, where J4 would have to spin.
  const ArmModel& parol6 = model("parol6");
  const Joints from = degrees({0, -60, 150, 0, 20, 180});
  const Eigen::Isometry3d goal = pose_at(parol6, degrees({0, -60, 150, 5, -20, 180}));
  const Result<Trajectory> planned =
      plan_line_move(parol6, from, goal, {.duration_s = 2.0}, limits_of(parol6), kLineDt);
  ASSERT_FALSE(planned.ok());
  const std::string& message = planned.error().message;
  EXPECT_NE(message.find("line move: stops before a singularity: J"), std::string::npos) << message;
  EXPECT_NE(message.find(" would turn at "), std::string::npos) << message;
  EXPECT_NE(message.find("% along the line ("), std::string::npos) << message;
  EXPECT_NE(message.find(" mm"), std::string::npos) << message;
  EXPECT_NE(message.find("it is clear up to"), std::string::npos) << message;
}

TEST(LineMove, StopsCloseToASingularityEvenWhenNoJointMustSpinButMayLeaveOneItStartsAt) {
  // J5 from 20° to −20° passes the PAROL6's wrist singularity (J5 = 0): the line stops close to
  // it, as the commander's MoveCart does; from J5 = 0 away from it, it goes.
  const ArmModel& parol6 = model("parol6");
  const Joints from = degrees({0, -60, 150, 0, 20, 180});
  const Joints through = degrees({0, -60, 150, 0, -20, 180});
  const Result<Trajectory> stopped =
      plan_line_move(parol6, from, pose_at(parol6, through), {.duration_s = 2.0}, limits_of(parol6), kLineDt);
  ASSERT_FALSE(stopped.ok());
  EXPECT_NE(stopped.error().message.find("line move: stops before a singularity "), std::string::npos)
      << stopped.error().message;
  const Joints singular = degrees({0, -60, 150, 0, 0, 180});
  EXPECT_LT(kinematics::smallest_singular_value(parol6, arm(singular)), 1e-9);
  const Result<Trajectory> away =
      plan_line_move(parol6, singular, pose_at(parol6, from), {.duration_s = 2.0}, limits_of(parol6), kLineDt);
  EXPECT_TRUE(away.ok()) << away.error().message;
  // Without the margin the line goes through.
  const Result<Trajectory> unguarded = plan_line_move(parol6, from, pose_at(parol6, through), {.duration_s = 2.0},
                                                      limits_of(parol6), kLineDt, {.min_singular_value = 0.0});
  EXPECT_TRUE(unguarded.ok()) << unguarded.error().message;
}

TEST(LineMove, KeepsToTheJointLimitsOnEverySample) {
  const ArmModel& parol6 = model("parol6");
  const Joints from = parol6_working();
  const Eigen::Isometry3d start = pose_at(parol6, from);
  const Eigen::Isometry3d goal = moved(start, {0.0, 0.05, 0.0}, 0.0, {0, 0, 1});
  // Where J1 must go along the line, and a limit that cuts the line half way.
  const Result<Trajectory> free = plan_line_move(parol6, from, goal, {.duration_s = 2.0}, limits_of(parol6), kLineDt);
  ASSERT_TRUE(free.ok()) << free.error().message;
  const double j1_goal = free.value().positions.back()[0];
  ASSERT_GT(std::abs(j1_goal - from[0]), 5 * kDegree);
  JointLimits narrow = limits_of(parol6);
  (j1_goal > from[0] ? narrow.max_rad[0] : narrow.min_rad[0]) = (from[0] + j1_goal) / 2;
  const Result<Trajectory> planned = plan_line_move(parol6, from, goal, {.duration_s = 2.0}, narrow, kLineDt);
  ASSERT_FALSE(planned.ok());
  EXPECT_NE(planned.error().message.find("line move: no joint solution"), std::string::npos) << planned.error().message;
  EXPECT_NE(planned.error().message.find("J1 would need"), std::string::npos) << planned.error().message;
  EXPECT_NE(planned.error().message.find("outside its limits"), std::string::npos) << planned.error().message;
}

TEST(LineMove, RefusesAJointFasterThanItsMaximum) {
  const ArmModel& parol6 = model("parol6");
  const Joints from = parol6_working();
  const Eigen::Isometry3d goal = moved(pose_at(parol6, from), {0.0, 0.1, 0.0}, 0.0, {0, 0, 1});
  const Result<Trajectory> planned =
      plan_line_move(parol6, from, goal, {.duration_s = 0.1}, limits_of(parol6), kLineDt);
  ASSERT_FALSE(planned.ok());
  EXPECT_NE(planned.error().message.find("rad/s (max 1.5)"), std::string::npos) << planned.error().message;
  EXPECT_NE(planned.error().message.find("a longer t would do"), std::string::npos) << planned.error().message;
}

TEST(LineMove, RefusesBadArguments) {
  const ArmModel& parol6 = model("parol6");
  const Joints from = parol6_working();
  const Eigen::Isometry3d goal = pose_at(parol6, from);
  EXPECT_EQ(plan_line_move(parol6, from, goal, {.speed_percent = 50.0}, limits_of(parol6), kLineDt).error().message,
            "line move: a straight line takes t (or its tool speed), not v or a");
  EXPECT_EQ(plan_line_move(parol6, Joints(5, 0.0), goal, {}, limits_of(parol6), kLineDt).error().message,
            "line move: the start has 5 values, expected one per joint (6)");
  EXPECT_EQ(plan_line_move(parol6, from, goal, {}, limits_of(model("xarm7")), kLineDt).error().message,
            "line move: the joint limit min_rad has 7 values, expected one per joint (6)");
  EXPECT_EQ(
      plan_line_move(parol6, from, goal, {}, limits_of(parol6), kLineDt, {.linear_speed_m_s = 0.0}).error().message,
      "line move: the line's tool speed and turning speed must be positive, got 0 m/s and 0.436 rad/s");
  const Result<Trajectory> there = plan_line_move(parol6, from, goal, {}, limits_of(parol6), kLineDt);
  ASSERT_TRUE(there.ok()) << there.error().message;
  EXPECT_EQ(there.value().positions.size(), 1U);
}

TEST(ToolRelativeMove, APureToolXMoveGoesAlongTheToolsXAxis) {
  const ArmModel& parol6 = model("parol6");
  const Joints from = parol6_working();
  const Eigen::Isometry3d start = pose_at(parol6, from);
  const Eigen::Isometry3d delta(Eigen::Translation3d(-0.03, 0.0, 0.0));
  const Result<Trajectory> planned =
      plan_tool_relative_move(parol6, from, delta, {.duration_s = 1.5}, limits_of(parol6), kLineDt);
  ASSERT_TRUE(planned.ok()) << planned.error().message;
  const Eigen::Vector3d tool_x = start.linear().col(0);
  for (const Joints& q : planned.value().positions) {
    const Eigen::Isometry3d tool = pose_at(parol6, q);
    const Eigen::Vector3d moved_by = tool.translation() - start.translation();
    EXPECT_LT((moved_by - moved_by.dot(tool_x) * tool_x).norm(), 1e-6);  // nothing across the tool's x
    EXPECT_LT(angle_between(tool, start), 1e-5);                         // no turn
  }
  const Eigen::Vector3d end = pose_at(parol6, planned.value().positions.back()).translation();
  EXPECT_NEAR((end - start.translation()).dot(tool_x), -0.03, 1e-6);
}

TEST(ToolRelativeMove, ATurnAboutTheToolsZKeepsTheToolPoint) {
  const ArmModel& parol6 = model("parol6");
  const Joints from = parol6_working();
  const Eigen::Isometry3d start = pose_at(parol6, from);
  const Eigen::Isometry3d delta(Eigen::AngleAxisd(20 * kDegree, Eigen::Vector3d::UnitZ()));
  const Result<Trajectory> planned =
      plan_tool_relative_move(parol6, from, delta, {.duration_s = 2.0}, limits_of(parol6), kLineDt);
  ASSERT_TRUE(planned.ok()) << planned.error().message;
  const Eigen::Isometry3d end = pose_at(parol6, planned.value().positions.back());
  EXPECT_LT((end.translation() - start.translation()).norm(), 1e-6);
  EXPECT_LT((end.linear() - start.linear() * delta.linear()).norm(), 1e-5);
}

}  // namespace
}  // namespace robotd::motion
