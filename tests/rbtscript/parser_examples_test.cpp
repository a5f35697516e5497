// The example programs and statement examples of the PAROL6 commander docs (kept once, as the
// rbtscript fuzz target's seed corpus) read into exactly the statements they spell.
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "parse_helpers.hpp"

namespace robotd::rbtscript {
namespace {

std::string read_example(const std::string& name) {
  std::ifstream file(std::string(ROBOTD_RBTSCRIPT_EXAMPLES_DIR) + "/" + name);
  EXPECT_TRUE(file) << name;
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

std::vector<StatementKind> statements_of(const std::string& name) {
  std::vector<StatementKind> kinds;
  for (auto& statement : test::parse_ok(read_example(name)).statements) kinds.push_back(std::move(statement.kind));
  return kinds;
}

JointMotion with_duration(double seconds) {
  JointMotion motion;
  motion.duration_s = seconds;
  return motion;
}

MoveCart cart(double x, double y, double z, double rx, double ry, double rz) {
  return MoveCart{Pose{x, y, z, rx, ry, rz}, {}};
}

TEST(RbtscriptExamples, JointSpaceLoop) {
  const std::vector<StatementKind> expected = {
      Begin{},
      Delay{1},
      MoveJoint{{85.078, -111.195, 143.513, -32.92, 18.084, 129.448}, with_duration(3)},
      Delay{1},
      MoveJoint{{66.129, -117.368, 136.77, 46.28, -29.588, 149.293}, {}},
      Delay{1},
      Loop{},
  };
  EXPECT_EQ(statements_of("joint_space_loop"), expected);
}

TEST(RbtscriptExamples, CartesianTrf) {
  const std::vector<StatementKind> expected = {
      Begin{},
      Delay{1},
      MoveJoint{{90.0, -90.0, 180.001, 0.0, 0.0, 180.0}, with_duration(4)},
      Delay{1},
      cart(0.0, 263.23, 161.241, -90.0, 0.0, -89.499),
      Delay{1},
      cart(81.565, 262.804, 161.047, -90.135, -0.029, -89.578),
      Delay{1},
      cart(81.649, 194.981, 160.077, -90.14, -0.043, -89.593),
      Delay{1},
      cart(83.598, 194.356, 161.493, -91.155, 1.306, -80.28),
      Delay{1},
      cart(84.56, 194.131, 162.347, -48.387, 1.261, -80.188),
      Delay{1},
      cart(82.89, 191.698, 162.369, -40.587, 26.026, -107.028),
      Delay{1},
      End{},
  };
  EXPECT_EQ(statements_of("cartesian_trf"), expected);
}

TEST(RbtscriptExamples, CartesianRelativeTrf) {
  const std::vector<StatementKind> expected = {
      Begin{},
      Delay{1},
      MoveJoint{{90.0, -90.0, 180.001, 0.0, 0.0, 180.0}, with_duration(4)},
      Delay{1},
      MoveCartRelTrf{Pose{-80, 0, 0, 0, 0, 0}, {}},
      Delay{1},
      End{},
  };
  EXPECT_EQ(statements_of("cartesian_relative_trf"), expected);
}

TEST(RbtscriptExamples, Ssg48Gripper) {
  const std::vector<StatementKind> expected = {
      Begin{},
      GripperCalibrate{},
      Delay{3},
      Gripper{100, 60, 600},
      Delay{2},
      Gripper{200, 60, 600},
      Delay{2},
      MoveJoint{{85.192, -104.451, 158.769, -1.983, -46.491, 179.899}, with_duration(6)},
      Delay{1},
      cart(4.317, 103.384, 192.319, -84.465, 1.447, -143.154),
      Gripper{100, 60, 600},
      Delay{2},
      End{},
  };
  EXPECT_EQ(statements_of("ssg48_gripper"), expected);
}

TEST(RbtscriptExamples, OutputClick) {
  const std::vector<StatementKind> expected = {
      Begin{}, Output{1, Level::kHigh}, Delay{1}, Output{1, Level::kLow}, Delay{1}, Loop{},
  };
  EXPECT_EQ(statements_of("output_click"), expected);
}

TEST(RbtscriptExamples, StatementExamples) {
  JointMotion speed_and_acceleration;
  speed_and_acceleration.speed_percent = 50;
  speed_and_acceleration.acceleration_percent = 50;
  JointMotion speed_curve_only;
  speed_curve_only.tracking = Tracking::kSpeedOnly;
  const std::vector<double> joints = {0, -90, 180, 0, 0, 180};
  const std::vector<StatementKind> expected = {
      MoveJoint{joints, with_duration(4)},
      MoveJoint{joints, speed_and_acceleration},
      MoveJoint{joints, {}},
      MoveJoint{joints, speed_curve_only},
      MoveCartRelTrf{Pose{0, 0, 0, 0, 45, 0}, {}},
      MoveCartRelTrf{Pose{0, 0, 0, 0, 0, 45}, {}},
      Delay{1.5},
      End{},
      Begin{},
      Loop{},
      Output{1, Level::kHigh},
      Output{2, Level::kLow},
      GripperCalibrate{},
      Delay{2},
      Gripper{120, 30, 500},
      Delay{2},
  };
  EXPECT_EQ(statements_of("statement_examples"), expected);
}

TEST(RbtscriptExamples, EveryArgumentSeedParses) { EXPECT_EQ(statements_of("every_argument").size(), 9U); }

}  // namespace
}  // namespace robotd::rbtscript
