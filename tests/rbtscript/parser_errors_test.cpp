// Malformed scripts: each error names its line and column, what was found there and what the
// language expects; one pass lists the errors of every line.
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "parse_helpers.hpp"

namespace robotd::rbtscript {
namespace {

using test::only_error;

struct BadLine {
  std::string_view text;
  std::size_t column;
  std::string_view found;
  std::string_view expected_part;  // a part of what the error expects
};

void expect_errors(const std::vector<BadLine>& cases) {
  for (const auto& bad : cases) {
    SCOPED_TRACE(bad.text);
    const ParseError error = only_error(bad.text);
    EXPECT_EQ(error.location, (SourceLocation{1, bad.column}));
    EXPECT_EQ(error.found, bad.found);
    EXPECT_NE(error.expected.find(bad.expected_part), std::string::npos) << error.expected;
  }
}

TEST(RbtscriptErrors, UnknownStatementListsTheStatements) {
  const ParseError error = only_error("MoveJ(1,2,3)");
  EXPECT_EQ(error.location, (SourceLocation{1, 1}));
  EXPECT_EQ(error.found, "'MoveJ'");
  EXPECT_EQ(error.expected,
            "a statement: MoveJoint, MovePose, MoveCart, MoveCartRelTRF, Delay, Begin, End, Loop, Output, "
            "Gripper_cal, Gripper");
  expect_errors({{"SpeedJoint()", 1, "'SpeedJoint'", "a statement: MoveJoint"},
                 {"  42", 3, "'42'", "a statement: MoveJoint"},
                 {"(1)", 1, "'('", "a statement: MoveJoint"}});
}

TEST(RbtscriptErrors, StatementNamesAreCaseSensitive) {
  expect_errors({{"movejoint(1)", 1, "'movejoint'", "MoveJoint (statement names are case-sensitive)"},
                 {"gripper_CAL()", 1, "'gripper_CAL'", "Gripper_cal (statement names are case-sensitive)"}});
}

TEST(RbtscriptErrors, MalformedCalls) {
  expect_errors({
      {"Begin", 6, "end of line", "'(' after Begin"},
      {"Delay 1", 7, "'1'", "'(' after Delay"},
      {"Delay(1", 8, "end of line", "',' or ')'"},
      {"Delay(1 2)", 9, "'2'", "',' or ')'"},
      {"MoveJoint(1,,2)", 13, "','", "an argument"},
      {"Delay(1,)", 9, "')'", "an argument"},
      {"MoveJoint(1,t=)", 15, "')'", "a value after 't='"},
      {"Begin() End()", 9, "'End'", "one statement per line"},
      {"Begin() extra // comment", 9, "'extra'", "the end of the line or a // comment"},
  });
}

TEST(RbtscriptErrors, WhatIsNotAToken) {
  expect_errors({
      {"MoveJoint(1;2)", 12, "';'", "a number, a word"},
      {"Delay(1) # not a comment", 10, "'#'", "a // comment"},
      {"Delay(1) / 2", 10, "'/'", "a // comment"},
      {"Delay(\x01)", 7, "byte 0x01", "a number"},
      {"MoveJoint(1,\"poly)", 19, "end of line", "the closing '\"' of the string at column 13"},
      {"MoveJoint(1.2.3)", 11, "'1.2.3'", "a number such as"},
      {"MoveJoint(12abc)", 11, "'12abc'", "a number such as"},
      {"MoveJoint(-)", 11, "'-'", "a number such as"},
      {"MoveJoint(1e400)", 11, "'1e400'", "a number of a sensible size"},
      {"MoveJoint(-inf)", 11, "'-inf'", "a number such as"},
  });
}

TEST(RbtscriptErrors, MissingAndExtraMoveValues) {
  expect_errors({
      {"MoveJoint()", 11, "')'", "1 to 7 joint values in degrees"},
      {"MoveJoint(t=4)", 11, "'t=4'", "1 to 7 joint values in degrees"},
      {"MoveJoint(1,2,3,4,5,6,7,8)", 25, "'8'", "MoveJoint takes at most 7 joint values"},
      {"MovePose(1,2,3,4)", 17, "')'", "6 pose values: x, y, z in mm, then Rx, Ry, Rz in degrees"},
      {"MovePose(1,2,3,4,5,v=50)", 20, "'v=50'", "6 pose values"},
      {"MoveCart(1,2,3,4,5,6,7)", 22, "'7'", "')' or one of the optional arguments t=, func, speed"},
      {"MoveCartRelTRF(1,2,3,4,5)", 25, "')'", "6 pose values"},
  });
}

TEST(RbtscriptErrors, WrongArgumentTypes) {
  expect_errors({
      {"MoveJoint(1,abc)", 13, "'abc'", "')' or one of the optional arguments v=, a=, t=, func, speed"},
      {"MoveJoint(1,\"fast\")", 13, "'\"fast\"'", "one of the optional arguments"},
      {"MoveJoint(1,x=5)", 13, "'x=5'", "one of the optional arguments v=, a=, t=, func, speed"},
      {"MoveJoint(1,v=fast)", 15, "'fast'", "a number greater than 0 and at most 100"},
      {"MoveJoint(1,t=\"4\")", 15, "'\"4\"'", "a number of seconds greater than 0"},
      {"Delay(x)", 7, "'x'", "the delay in seconds"},
      {"Delay(t=1)", 7, "'t=1'", "the delay in seconds"},
  });
}

TEST(RbtscriptErrors, OptionalArgumentsInTheDefinedOrderOnce) {
  expect_errors({
      {"MoveJoint(1,t=2,v=50)", 17, "'v=50'", "in the order v=, a=, t=, func, speed, so v= before t="},
      {"MoveJoint(1,a=20,v=50)", 18, "'v=50'", "so v= before a="},
      {"MoveJoint(1,speed,t=2)", 19, "'t=2'", "so t= before speed"},
      {"MoveJoint(1,trap,t=2)", 18, "'t=2'", "so t= before func"},
      {"MoveJoint(1,t=2,t=3)", 17, "'t=3'", "t= is given twice"},
      {"MoveCart(1,2,3,4,5,6,speed,speed)", 28, "'speed'", "speed is given twice"},
  });
}

TEST(RbtscriptErrors, OptionsAStatementDoesNotTake) {
  expect_errors({
      {"MoveCart(1,2,3,4,5,6,v=50)", 22, "'v=50'", "(MoveCart takes exactly 6 pose values, and no v or a)"},
      {"MoveCartRelTRF(1,2,3,4,5,6,a=5)", 28, "'a=5'", "MoveCartRelTRF takes exactly 6 pose values, and no v or a"},
      {"MoveJoint(1,speed=1)", 13, "'speed=1'", "the bare word speed, without a value"},
  });
}

TEST(RbtscriptErrors, FuncIsPolyOrTrap) {
  expect_errors({
      {"MoveJoint(1,func=cubic)", 18, "'cubic'", "poly or trap"},
      {"MoveJoint(1,func=\"Poly\")", 18, "'\"Poly\"'", "poly or trap"},
      {"MoveJoint(1,func=2)", 18, "'2'", "poly or trap"},
  });
}

TEST(RbtscriptErrors, SpeedAccelerationAndDurationRanges) {
  expect_errors({
      {"MoveJoint(1,v=0)", 15, "'0'", "v: percent of the leading joint's maximum speed"},
      {"MoveJoint(1,v=100.5)", 15, "'100.5'", "greater than 0 and at most 100"},
      {"MovePose(1,2,3,4,5,6,a=-5)", 24, "'-5'", "a: percent of the leading joint's maximum acceleration"},
      {"MoveJoint(1,a=101)", 15, "'101'", "at most 100"},
      {"MoveJoint(1,t=0)", 15, "'0'", "a number of seconds greater than 0"},
      {"MoveCart(1,2,3,4,5,6,t=-1)", 24, "'-1'", "greater than 0"},
      {"Delay(-0.5)", 7, "'-0.5'", "a number of at least 0"},
  });
  EXPECT_EQ(test::only_statement<MoveJoint>("MoveJoint(1,v=100,a=100)").motion.speed_percent, 100.0);
}

TEST(RbtscriptErrors, OutputArguments) {
  expect_errors({
      {"Output()", 8, "')'", "the output number, a whole number of at least 1"},
      {"Output(0,HIGH)", 8, "'0'", "a whole number of at least 1"},
      {"Output(1.5,HIGH)", 8, "'1.5'", "a whole number of at least 1"},
      {"Output(HIGH,1)", 8, "'HIGH'", "the output number"},
      {"Output(1)", 9, "')'", "',' and then HIGH or LOW"},
      {"Output(1,high)", 10, "'high'", "HIGH or LOW"},
      {"Output(1,1)", 10, "'1'", "HIGH or LOW"},
      {"Output(1,HIGH,2)", 15, "'2'", "')': Output takes an output number and HIGH or LOW"},
  });
}

TEST(RbtscriptErrors, GripperArgumentsAndRanges) {
  expect_errors({
      {"Gripper(256,0,0)", 9, "'256'", "the gripper position, a whole number from 0 (open) to 255 (closed)"},
      {"Gripper(-1,0,0)", 9, "'-1'", "the gripper position"},
      {"Gripper(0,256,0)", 11, "'256'", "the gripper speed, a whole number from 0 to 255"},
      {"Gripper(0,0,1301)", 13, "'1301'", "the gripper current in mA, a whole number from 0 to 1300"},
      {"Gripper(1.5,0,0)", 9, "'1.5'", "a whole number"},
      {"Gripper(99999999999,0,0)", 9, "'99999999999'", "the gripper position"},
      {"Gripper(1,2)", 12, "')'", "the gripper current in mA"},
      {"Gripper(1,2,3,4)", 15, "'4'", "')': Gripper takes position, speed and current"},
  });
}

TEST(RbtscriptErrors, StatementsWithoutArgumentsTakeNone) {
  expect_errors({
      {"Begin(1)", 7, "'1'", "')': Begin takes no arguments"},
      {"End(now)", 5, "'now'", "')': End takes no arguments"},
      {"Loop(3)", 6, "'3'", "')': Loop takes no arguments"},
      {"Gripper_cal(1)", 13, "'1'", "')': Gripper_cal takes no arguments"},
      {"Delay(1,2)", 9, "'2'", "')': Delay takes one value"},
  });
}

TEST(RbtscriptErrors, EveryLineWithAnErrorIsListedInLineOrder) {
  const auto result = parse_program(
      "Begin()\n"
      "MoveJ(1)\n"
      "Delay(1)\n"
      "Delay(-1) // negative\n"
      "Gripper(1,2,3000) Delay(1)\n"
      "End()\n");
  EXPECT_FALSE(result.program.has_value());
  ASSERT_EQ(result.errors.size(), 3U);
  EXPECT_EQ(result.errors[0].location, (SourceLocation{2, 1}));
  EXPECT_EQ(result.errors[1].location, (SourceLocation{4, 7}));
  // One error per line: the leftmost.
  EXPECT_EQ(result.errors[2].location, (SourceLocation{5, 13}));
  EXPECT_EQ(result.errors[2].found, "'3000'");
}

TEST(RbtscriptErrors, MessageNamesLineColumnFoundAndExpected) {
  const auto result = parse_program("Begin()\n  MovePose(1,2,3)\n");
  ASSERT_EQ(result.errors.size(), 1U);
  EXPECT_EQ(result.errors[0].message(),
            "line 2, column 17: found ')', expected 6 pose values: x, y, z in mm, then Rx, Ry, Rz in degrees");
}

}  // namespace
}  // namespace robotd::rbtscript
