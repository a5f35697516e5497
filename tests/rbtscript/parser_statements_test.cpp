// Every RBTscript statement, with each argument form the language has, read into its struct.
#include <gtest/gtest.h>

#include "parse_helpers.hpp"

namespace robotd::rbtscript {
namespace {

using test::only_statement;
using test::parse_ok;

TEST(RbtscriptStatements, MoveJointWithoutOptionsLeavesThemUnset) {
  const auto move = only_statement<MoveJoint>("MoveJoint(0,-90,180,0,0,180)");
  EXPECT_EQ(move.joints_deg, (std::vector<double>{0, -90, 180, 0, 0, 180}));
  EXPECT_EQ(move.motion, JointMotion{});
  EXPECT_EQ(move.motion.tracking, Tracking::kPosition);
}

TEST(RbtscriptStatements, MoveJointDuration) {
  const auto move = only_statement<MoveJoint>("MoveJoint(0,-90,180,0,0,180,t=4)");
  EXPECT_EQ(move.motion.duration_s, 4.0);
  EXPECT_FALSE(move.motion.speed_percent || move.motion.acceleration_percent || move.motion.profile);
}

TEST(RbtscriptStatements, MoveJointSpeedAndAcceleration) {
  const auto move = only_statement<MoveJoint>("MoveJoint(0,-90,180,0,0,180,v=50,a=25)");
  EXPECT_EQ(move.motion.speed_percent, 50.0);
  EXPECT_EQ(move.motion.acceleration_percent, 25.0);
  EXPECT_FALSE(move.motion.duration_s);
}

TEST(RbtscriptStatements, MoveJointSpeedFlagTracksTheSpeedCurveOnly) {
  const auto move = only_statement<MoveJoint>("MoveJoint(0,-90,180,0,0,180,speed)");
  EXPECT_EQ(move.motion.tracking, Tracking::kSpeedOnly);
}

TEST(RbtscriptStatements, MoveJointEveryOptionInOrder) {
  const auto move = only_statement<MoveJoint>("MoveJoint(1,2,3,4,5,6,v=40,a=30,t=2,func=trap,speed)");
  EXPECT_EQ(move.motion, (JointMotion{40.0, 30.0, 2.0, Profile::kTrapezoid, Tracking::kSpeedOnly}));
}

TEST(RbtscriptStatements, MoveJointTakesOneToSevenJointValues) {
  EXPECT_EQ(only_statement<MoveJoint>("MoveJoint(12.5)").joints_deg, std::vector<double>{12.5});
  EXPECT_EQ(only_statement<MoveJoint>("MoveJoint(1,2,3,4,5,6,7)").joints_deg,
            (std::vector<double>{1, 2, 3, 4, 5, 6, 7}));
}

TEST(RbtscriptStatements, FuncIsPolyOrTrapBareOrQuotedWithOrWithoutItsName) {
  for (const auto& [text, profile] : std::vector<std::pair<std::string_view, Profile>>{
           {"MoveJoint(1,t=1,func=poly)", Profile::kPolynomial},
           {"MoveJoint(1,t=1,func=\"poly\")", Profile::kPolynomial},
           {"MoveJoint(1,t=1,poly)", Profile::kPolynomial},
           {"MoveJoint(1,t=1,\"trap\")", Profile::kTrapezoid},
           {"MoveJoint(1,t=1,trap)", Profile::kTrapezoid},
           {"MoveJoint(1,t=1,func = trap)", Profile::kTrapezoid},
       }) {
    SCOPED_TRACE(text);
    EXPECT_EQ(only_statement<MoveJoint>(text).motion.profile, profile);
  }
}

TEST(RbtscriptStatements, NumbersInEveryWrittenForm) {
  EXPECT_EQ(only_statement<MoveJoint>("MoveJoint(-1e1, +2.5, .5, 3., 0, -0.25, 1E2)").joints_deg,
            (std::vector<double>{-10, 2.5, 0.5, 3, 0, -0.25, 100}));
}

TEST(RbtscriptStatements, MovePoseWithEveryOption) {
  const auto move = only_statement<MovePose>("MovePose(200, 0, 300, 180, -5.5, 90, v=40, a=30, t=2, poly, speed)");
  EXPECT_EQ(move.pose, (Pose{200, 0, 300, 180, -5.5, 90}));
  EXPECT_EQ(move.motion, (JointMotion{40.0, 30.0, 2.0, Profile::kPolynomial, Tracking::kSpeedOnly}));
}

TEST(RbtscriptStatements, MovePoseWithoutOptions) {
  const auto move = only_statement<MovePose>("MovePose(1,2,3,4,5,6)");
  EXPECT_EQ(move.pose, (Pose{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(move.motion, JointMotion{});
}

TEST(RbtscriptStatements, MoveCartWithDurationFuncAndSpeed) {
  const auto move = only_statement<MoveCart>("MoveCart(0.0,263.23,161.241,-90.0,0.0,-89.499,t=3,func=trap,speed)");
  EXPECT_EQ(move.pose, (Pose{0.0, 263.23, 161.241, -90.0, 0.0, -89.499}));
  EXPECT_EQ(move.motion, (CartesianMotion{3.0, Profile::kTrapezoid, Tracking::kSpeedOnly}));
}

TEST(RbtscriptStatements, MoveCartRelTrfWithoutOptions) {
  const auto move = only_statement<MoveCartRelTrf>("MoveCartRelTRF(-80,0,0,0,0,0)");
  EXPECT_EQ(move.delta, (Pose{-80, 0, 0, 0, 0, 0}));
  EXPECT_EQ(move.motion, CartesianMotion{});
}

TEST(RbtscriptStatements, MoveCartRelTrfWithDuration) {
  EXPECT_EQ(only_statement<MoveCartRelTrf>("MoveCartRelTRF(0, 0, 0, 0, 45, 0, t=1.5)").motion.duration_s, 1.5);
}

TEST(RbtscriptStatements, Delay) {
  EXPECT_EQ(only_statement<Delay>("Delay(1.5)").seconds, 1.5);
  EXPECT_EQ(only_statement<Delay>("Delay(0)").seconds, 0.0);
}

TEST(RbtscriptStatements, StatementsWithoutArguments) {
  only_statement<Begin>("Begin()");
  only_statement<End>("End()");
  only_statement<Loop>("Loop( )");
  only_statement<GripperCalibrate>("Gripper_cal()");
}

TEST(RbtscriptStatements, OutputNumberAndLevel) {
  EXPECT_EQ(only_statement<Output>("Output(1,HIGH)"), (Output{1, Level::kHigh}));
  EXPECT_EQ(only_statement<Output>("Output(2, LOW)"), (Output{2, Level::kLow}));
  // Which outputs exist is the device's business: the language only wants a positive number.
  EXPECT_EQ(only_statement<Output>("Output(17, HIGH)"), (Output{17, Level::kHigh}));
}

TEST(RbtscriptStatements, GripperPositionSpeedCurrent) {
  EXPECT_EQ(only_statement<Gripper>("Gripper(120,30,500)"), (Gripper{120, 30, 500}));
  EXPECT_EQ(only_statement<Gripper>("Gripper(0,0,0)"), (Gripper{0, 0, 0}));
  EXPECT_EQ(only_statement<Gripper>("Gripper(255, 255, 1300)"), (Gripper{255, 255, 1300}));
}

TEST(RbtscriptStatements, CommentsBlankLinesAndWhitespaceAreSkipped) {
  const Program program = parse_ok(
      "// a comment line\n"
      "\n"
      "   \t\n"
      "  Delay( 1 )   // a trailing comment, Begin() in it is not a statement\n"
      "Delay(2)//no space\r\n"
      "\tEnd()\r\n");
  ASSERT_EQ(program.statements.size(), 3U);
  EXPECT_EQ(program.statements[0].kind, StatementKind{Delay{1}});
  EXPECT_EQ(program.statements[1].kind, StatementKind{Delay{2}});
  EXPECT_EQ(program.statements[2].kind, StatementKind{End{}});
}

TEST(RbtscriptStatements, EachStatementKeepsItsLocationAndText) {
  const Program program = parse_ok("Begin()\n\n   MoveJoint(1, 2,  t=4)   // go\n\tEnd()");
  ASSERT_EQ(program.statements.size(), 3U);
  EXPECT_EQ(program.statements[0].location, (SourceLocation{1, 1}));
  EXPECT_EQ(program.statements[0].text, "Begin()");
  EXPECT_EQ(program.statements[1].location, (SourceLocation{3, 4}));
  EXPECT_EQ(program.statements[1].text, "MoveJoint(1, 2,  t=4)");
  EXPECT_EQ(program.statements[2].location, (SourceLocation{4, 2}));
  EXPECT_EQ(program.statements[2].text, "End()");
}

TEST(RbtscriptStatements, AnEmptyScriptIsAnEmptyProgram) {
  EXPECT_TRUE(parse_ok("").statements.empty());
  EXPECT_TRUE(parse_ok("// nothing\n\n").statements.empty());
}

}  // namespace
}  // namespace robotd::rbtscript
