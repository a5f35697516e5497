// The RealMan JSON codec against the protocol spec (../shared/protocols/realman_json.md) and the
// vendor's gripper and hand doc: the spec's worked examples, unit conversions and rounding, the
// "\r\n" line splitter, every request's fields, the reply table, the three error shapes, the UDP
// push, the error and model tables, and a fuzz loop showing no decoder throws on any input.
#include "codec/realman_codec.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace robotd::realman {
namespace {

using nlohmann::json;

constexpr double kPi = std::numbers::pi;
constexpr double kRadPerDegree = kPi / 180.0;

Message message_from(std::string_view line) {
  auto parsed = parse_message(line);
  EXPECT_TRUE(parsed.ok()) << (parsed.ok() ? "" : parsed.error().message);
  return parsed.ok() ? parsed.value() : Message{};
}

/// Every complete line the splitter has.
std::vector<std::string> drain(LineSplitter& splitter) {
  std::vector<std::string> lines;
  while (auto line = splitter.next()) lines.push_back(*line);
  return lines;
}

// The §6.2 example datagram with its abbreviated arrays filled in with plausible values.
constexpr std::string_view kPushExample =
    R"({"arm_current_status":"idle","err":[0],"joint_status":{)"
    R"("joint_current":[120000,850000,430000,51000,22000,3000],"joint_en_flag":[1,1,1,1,1,1],)"
    R"("joint_err_code":[0,0,0,0,0,0],"joint_position":[13434,-69764,2926,-4742,-45721,-223],)"
    R"("joint_temperature":[35200,36100,34800,33000,32500,31900],)"
    R"("joint_voltage":[48000,48100,47900,48000,48050,47950]},)"
    R"("state":"realtime_arm_joint_state","waypoint":{"euler":[3142,-1571,12],"position":[578568,127709,345856],)"
    R"("quat":[500000,-500000,500000,-500000]}})"
    "\r\n";

// ---- Units ---------------------------------------------------------------------------------

TEST(Units, JointAnglesAreMillidegrees) {
  EXPECT_EQ(millidegrees_from_rad(kPi / 2), 90000);
  EXPECT_EQ(millidegrees_from_rad(-kPi / 2), -90000);
  EXPECT_EQ(millidegrees_from_rad(0.0), 0);
  EXPECT_DOUBLE_EQ(rad_from_millidegrees(90000), kPi / 2);
  EXPECT_DOUBLE_EQ(rad_from_millidegrees(-180000), -kPi);
}

TEST(Units, EncodingRoundsToTheNearestMillidegree) {
  EXPECT_EQ(millidegrees_from_rad(0.0004 * kRadPerDegree), 0);
  EXPECT_EQ(millidegrees_from_rad(0.0006 * kRadPerDegree), 1);
  EXPECT_EQ(millidegrees_from_rad(-0.0006 * kRadPerDegree), -1);
  EXPECT_EQ(millidegrees_from_rad(29.9996 * kRadPerDegree), 30000);
  EXPECT_EQ(millidegrees_from_rad(-29.9996 * kRadPerDegree), -30000);
}

TEST(Units, PositionsAreMicrometresAndEulerAnglesMilliradians) {
  EXPECT_EQ(micrometres_from_m(0.3), 300000);
  EXPECT_EQ(micrometres_from_m(-0.0000006), -1);
  EXPECT_DOUBLE_EQ(m_from_micrometres(578568), 0.578568);
  EXPECT_EQ(milliradians_from_rad(3.142), 3142);
  EXPECT_EQ(milliradians_from_rad(-0.0004), 0);
  EXPECT_DOUBLE_EQ(rad_from_milliradians(-1571), -1.571);
}

TEST(Units, ValuesBeyondInt64SaturateInsteadOfOverflowing) {
  constexpr auto kMax = std::numeric_limits<std::int64_t>::max();
  constexpr auto kMin = std::numeric_limits<std::int64_t>::min();
  EXPECT_EQ(millidegrees_from_rad(1e300), kMax);
  EXPECT_EQ(millidegrees_from_rad(-1e300), kMin);
  EXPECT_EQ(micrometres_from_m(std::numeric_limits<double>::infinity()), kMax);
  EXPECT_EQ(milliradians_from_rad(std::numeric_limits<double>::quiet_NaN()), kMax);
  EXPECT_TRUE(std::isfinite(rad_from_millidegrees(kMax)));
  EXPECT_TRUE(std::isfinite(m_from_micrometres(kMin)));
}

TEST(Units, MillidegreesSurviveARoundTrip) {
  for (const std::int64_t millidegrees : {-360000LL, -178000LL, -1LL, 0LL, 1LL, 13434LL, 359999LL, 3600000000LL}) {
    EXPECT_EQ(millidegrees_from_rad(rad_from_millidegrees(millidegrees)), millidegrees);
  }
}

// ---- Framing -------------------------------------------------------------------------------

TEST(Frame, IsCompactJsonEndedByCrLf) {
  const std::string framed = frame(json::parse(R"({"command": "get_joint_degree"})"));
  EXPECT_EQ(framed, "{\"command\":\"get_joint_degree\"}\r\n");
}

TEST(Frame, ReplacesBytesThatAreNotUtf8InsteadOfThrowing) {
  RealtimePushConfig config;
  config.ip = "192.168.1.\xff";
  std::string framed;
  EXPECT_NO_THROW(framed = frame(set_realtime_push_request(config)));
  EXPECT_TRUE(framed.ends_with("\r\n"));
}

TEST(LineSplitter, SplitsSeveralMessagesInOneChunk) {
  LineSplitter splitter;
  splitter.append("{\"a\":1}\r\n{\"b\":2}\r\n{\"c\"");
  EXPECT_EQ(drain(splitter), (std::vector<std::string>{"{\"a\":1}", "{\"b\":2}"}));
  splitter.append(":3}\r\n");
  EXPECT_EQ(drain(splitter), (std::vector<std::string>{"{\"c\":3}"}));
}

TEST(LineSplitter, JoinsATerminatorSplitBetweenChunks) {
  LineSplitter splitter;
  splitter.append("{\"a\":1}\r");
  EXPECT_EQ(splitter.next(), std::nullopt);
  splitter.append("\n");
  EXPECT_EQ(splitter.next(), "{\"a\":1}");
}

TEST(LineSplitter, KeepsABareLineFeedInsideTheMessage) {
  LineSplitter splitter;
  splitter.append("{\n\t\"command\": \"movej\",\n\t\"v\": 30\n}\r\n");
  const auto line = splitter.next();
  ASSERT_TRUE(line.has_value());
  EXPECT_EQ(*line, "{\n\t\"command\": \"movej\",\n\t\"v\": 30\n}");
  EXPECT_EQ(message_from(*line).key, "movej");
}

TEST(LineSplitter, SkipsEmptyLines) {
  LineSplitter splitter;
  splitter.append("\r\n\r\n{}\r\n\r\n");
  EXPECT_EQ(drain(splitter), (std::vector<std::string>{"{}"}));
}

TEST(LineSplitter, DeliversOneByteAtATime) {
  LineSplitter splitter;
  const std::string stream = "{\"a\":1}\r\n\r\n{\"b\":\n2}\r\n";
  std::vector<std::string> lines;
  for (const char c : stream) {
    splitter.append(std::string_view(&c, 1));
    while (auto line = splitter.next()) lines.push_back(*line);
  }
  EXPECT_EQ(lines, (std::vector<std::string>{"{\"a\":1}", "{\"b\":\n2}"}));
}

TEST(LineSplitter, AcceptsALineOfExactlyTheLimit) {
  LineSplitter splitter(8);
  splitter.append("12345678\r");
  splitter.append("\n");
  EXPECT_EQ(splitter.next(), "12345678");
  EXPECT_EQ(splitter.oversized(), 0U);
}

TEST(LineSplitter, DropsACompleteOversizedLineAndCountsIt) {
  LineSplitter splitter(8);
  splitter.append("123456789\r\nok\r\n");
  EXPECT_EQ(drain(splitter), (std::vector<std::string>{"ok"}));
  EXPECT_EQ(splitter.oversized(), 1U);
}

TEST(LineSplitter, DropsALineThatOutgrowsTheLimitBeforeItsTerminator) {
  LineSplitter splitter(8);
  splitter.append("first\r\n1234");
  splitter.append("56789");  // now 9 bytes without a terminator
  EXPECT_EQ(splitter.oversized(), 1U);
  splitter.append("more bytes of the same line");
  splitter.append("\r\nnext\r\n");
  EXPECT_EQ(drain(splitter), (std::vector<std::string>{"first", "next"}));
  EXPECT_EQ(splitter.oversized(), 1U);
}

TEST(LineSplitter, FindsTheEndOfADroppedLineSplitBetweenChunks) {
  LineSplitter splitter(4);
  splitter.append("abcdefgh\r");
  splitter.append("\nok\r\n");
  EXPECT_EQ(drain(splitter), (std::vector<std::string>{"ok"}));
  EXPECT_EQ(splitter.oversized(), 1U);
}

TEST(LineSplitter, ALoneCarriageReturnDoesNotEndADroppedLine) {
  LineSplitter splitter(4);
  splitter.append("abcdefgh\r");
  splitter.append("x\r\nok\r\n");
  EXPECT_EQ(drain(splitter), (std::vector<std::string>{"ok"}));
}

TEST(LineSplitter, ClearForgetsAPartialLineButKeepsTheCount) {
  LineSplitter splitter(4);
  splitter.append("abcdefgh");
  splitter.clear();
  splitter.append("ok\r\n{\"x\"");
  splitter.clear();
  splitter.append("{}\r\n");
  EXPECT_EQ(drain(splitter), (std::vector<std::string>{"{}"}));
  EXPECT_EQ(splitter.oversized(), 1U);
}

// ---- Requests ------------------------------------------------------------------------------

TEST(Requests, MovejMatchesTheSpecExample) {
  const std::array<double, 6> joints{0, 15 * kRadPerDegree, -30 * kRadPerDegree, 0, 45 * kRadPerDegree, 0};
  const json message = movej_request(joints, PlannedMove{.speed_percent = 30, .blend_percent = 0});
  EXPECT_EQ(
      message,
      json::parse(R"({"command":"movej","joint":[0,15000,-30000,0,45000,0],"v":30,"r":0,"trajectory_connect":0})"));
}

TEST(Requests, MovejSendsOneAnglePerJointOfA7DofArm) {
  const std::array<double, 7> joints{-kPi, -1.0, -0.5, 0, 0.5, 1.0, 2 * kPi};
  const json message =
      movej_request(joints, PlannedMove{.speed_percent = 100, .blend_percent = 50, .trajectory_connect = true});
  EXPECT_EQ(message["joint"], json::parse("[-180000,-57296,-28648,0,28648,57296,360000]"));
  EXPECT_EQ(message["v"], 100);
  EXPECT_EQ(message["r"], 50);
  EXPECT_EQ(message["trajectory_connect"], 1);
}

TEST(Requests, CartesianMovesSendMicrometresAndMilliradians) {
  const EulerPose pose{.position_m = {0.3, -0.1274, 0.5}, .euler_rad = {3.142, 0, -1.5708}};
  const json expected_pose = json::parse("[300000,-127400,500000,3142,0,-1571]");
  const json movel = movel_request(pose, PlannedMove{.speed_percent = 20});
  EXPECT_EQ(movel,
            json({{"command", "movel"}, {"pose", expected_pose}, {"v", 20}, {"r", 0}, {"trajectory_connect", 0}}));
  const json movej_p = movej_p_request(pose, PlannedMove{.speed_percent = 20});
  EXPECT_EQ(movej_p["command"], "movej_p");
  EXPECT_EQ(movej_p["pose"], expected_pose);
}

TEST(Requests, MovejCanfdCarriesFollowAndOnlyTheOptionalFieldsThatAreSet) {
  const std::array<double, 6> joints{0, 0, kPi / 2, 0, 0, 0};
  EXPECT_EQ(movej_canfd_request(joints, PassThrough{}),
            json::parse(R"({"command":"movej_canfd","joint":[0,0,90000,0,0,0],"follow":true})"));
  const PassThrough filtered{.follow = false, .trajectory_mode = 2, .radio = 500};
  EXPECT_EQ(movej_canfd_request(joints, filtered),
            json::parse(R"({"command":"movej_canfd","joint":[0,0,90000,0,0,0],"follow":false,)"
                        R"("trajectory_mode":2,"radio":500})"));
}

TEST(Requests, StateAndEnableCommandsUseTheSpecFields) {
  EXPECT_EQ(plain_request("get_current_arm_state"), json::parse(R"({"command":"get_current_arm_state"})"));
  EXPECT_EQ(set_joint_en_state_request(3, true),
            json::parse(R"({"command":"set_joint_en_state","joint_en_state":[3,1]})"));
  EXPECT_EQ(set_joint_en_state_request(7, false),
            json::parse(R"({"command":"set_joint_en_state","joint_en_state":[7,0]})"));
  EXPECT_EQ(set_joint_clear_err_request(2), json::parse(R"({"command":"set_joint_clear_err","joint_clear_err":2})"));
  EXPECT_EQ(set_arm_power_request(true), json::parse(R"({"command":"set_arm_power","arm_power":1})"));
  EXPECT_EQ(set_arm_power_request(false), json::parse(R"({"command":"set_arm_power","arm_power":0})"));
}

TEST(Requests, SetRealtimePushNamesTheTargetAndTheCustomFields) {
  RealtimePushConfig config;
  config.cycle = 2;
  config.ip = "192.168.1.100";
  config.joint_speed = true;
  EXPECT_EQ(set_realtime_push_request(config),
            json::parse(R"({"command":"set_realtime_push","cycle":2,"enable":true,"port":8089,"ip":"192.168.1.100",)"
                        R"("custom":{"joint_speed":true,"arm_current_status":true,"hand":false}})"));
}

TEST(Requests, GripperCommandsMatchTheVendorExamples) {
  EXPECT_EQ(set_gripper_route_request(70, 500), json::parse(R"({"command":"set_gripper_route","min":70,"max":500})"));
  EXPECT_EQ(set_gripper_release_request(500, true),
            json::parse(R"({"command":"set_gripper_release","speed":500,"block":true})"));
  EXPECT_EQ(set_gripper_pick_request(500, 200, true),
            json::parse(R"({"command":"set_gripper_pick","speed":500,"force":200,"block":true})"));
  EXPECT_EQ(set_gripper_pick_on_request(500, 200, true),
            json::parse(R"({"command":"set_gripper_pick_on","speed":500,"force":200,"block":true})"));
  EXPECT_EQ(set_gripper_position_request(500, true),
            json::parse(R"({"command":"set_gripper_position","position":500,"block":true})"));
  EXPECT_EQ(set_gripper_release_request(1, false)["block"], false);
}

TEST(Requests, HandCommandsMatchTheVendorExamples) {
  EXPECT_EQ(set_hand_posture_request(1, true),
            json::parse(R"({"command":"set_hand_posture","posture_num":1,"block":true})"));
  EXPECT_EQ(set_hand_seq_request(1, true), json::parse(R"({"command":"set_hand_seq","seq_num":1,"block":true})"));
  EXPECT_EQ(set_hand_angle_request({-1, 100, 200, 300, 400, 500}, true),
            json::parse(R"({"command":"set_hand_angle","hand_angle":[-1,100,200,300,400,500],"block":true})"));
  EXPECT_EQ(set_hand_speed_request(500), json::parse(R"({"command":"set_hand_speed","hand_speed":500})"));
  EXPECT_EQ(set_hand_force_request(500), json::parse(R"({"command":"set_hand_force","hand_force":500})"));
}

TEST(Requests, EveryRequestHasAReplyShape) {
  const std::array<double, 6> joints{};
  const std::vector<json> requests{movej_request(joints, {}),
                                   movel_request({}, {}),
                                   movej_p_request({}, {}),
                                   movej_canfd_request(joints, {}),
                                   set_joint_en_state_request(1, true),
                                   set_joint_clear_err_request(1),
                                   set_arm_power_request(true),
                                   set_realtime_push_request({}),
                                   set_gripper_route_request(0, 1000),
                                   set_gripper_release_request(1, false),
                                   set_gripper_pick_request(1, 50, false),
                                   set_gripper_pick_on_request(1, 50, false),
                                   set_gripper_position_request(1, false),
                                   set_hand_posture_request(1, false),
                                   set_hand_seq_request(1, false),
                                   set_hand_angle_request({}, false),
                                   set_hand_speed_request(1),
                                   set_hand_force_request(1)};
  for (const json& request : requests) {
    EXPECT_TRUE(reply_shape(request["command"].get<std::string>()).has_value()) << request.dump();
  }
}

TEST(Requests, ARequestSurvivesTheWireRoundTrip) {
  const std::array<double, 6> joints{0.1, -0.2, 0.3, -1.23456, 2.5, -3.0};
  LineSplitter splitter;
  splitter.append(frame(movej_request(joints, {})));
  const auto line = splitter.next();
  ASSERT_TRUE(line.has_value());
  const Message message = message_from(*line);
  EXPECT_EQ(message.kind, MessageKind::kReply);
  EXPECT_EQ(message.key, "movej");
  for (std::size_t j = 0; j < joints.size(); ++j) {
    EXPECT_NEAR(rad_from_millidegrees(message.body["joint"][j].get<std::int64_t>()), joints[j], 0.0005 * kRadPerDegree);
  }
}

// ---- Argument checks -----------------------------------------------------------------------

TEST(ArgumentChecks, NameTheArgumentItsValueAndTheRange) {
  const auto checked = check_gripper_speed(0);
  ASSERT_FALSE(checked.ok());
  EXPECT_EQ(checked.error().code, ErrorCode::kInvalidArgument);
  EXPECT_EQ(checked.error().message, "speed 0 is out of range: the gripper's speed is 1..1000 (dimensionless)");
}

TEST(ArgumentChecks, AcceptTheBoundsAndRefuseJustBeyond) {
  EXPECT_TRUE(check_speed_percent(1).ok());
  EXPECT_TRUE(check_speed_percent(100).ok());
  EXPECT_FALSE(check_speed_percent(0).ok());
  EXPECT_FALSE(check_speed_percent(101).ok());
  EXPECT_TRUE(check_blend_percent(0).ok());
  EXPECT_FALSE(check_blend_percent(-1).ok());
  EXPECT_FALSE(check_blend_percent(101).ok());
  EXPECT_TRUE(check_gripper_speed(1000).ok());
  EXPECT_FALSE(check_gripper_speed(1001).ok());
  EXPECT_TRUE(check_gripper_force(50).ok());
  EXPECT_FALSE(check_gripper_force(49).ok());
  EXPECT_TRUE(check_gripper_position(1).ok());
  EXPECT_FALSE(check_gripper_position(0).ok());
  EXPECT_TRUE(check_hand_speed(1).ok());
  EXPECT_FALSE(check_hand_speed(1001).ok());
  EXPECT_TRUE(check_hand_force(1000).ok());
  EXPECT_FALSE(check_hand_force(0).ok());
  EXPECT_TRUE(check_hand_preset("posture", 40).ok());
  EXPECT_FALSE(check_hand_preset("posture", 41).ok());
}

TEST(ArgumentChecks, GripperRouteNeedsBothLimitsInRangeAndInOrder) {
  EXPECT_TRUE(check_gripper_route(0, 1000).ok());
  EXPECT_TRUE(check_gripper_route(500, 500).ok());
  EXPECT_NE(check_gripper_route(-1, 10).error().message.find("min -1"), std::string::npos);
  EXPECT_NE(check_gripper_route(0, 1001).error().message.find("max 1001"), std::string::npos);
  EXPECT_EQ(check_gripper_route(600, 500).error().message,
            "min 600 is above max 500: the gripper's route needs min <= max");
}

TEST(ArgumentChecks, HandPresetUsesTheCallersName) {
  EXPECT_EQ(check_hand_preset("sequence", 0).error().message.rfind("sequence 0 is out of range", 0), 0U);
}

TEST(ArgumentChecks, HandAnglesAllowMinusOneToKeepAFinger) {
  EXPECT_TRUE(check_hand_angles({-1, 0, 1000, -1, 500, 1}).ok());
  const auto checked = check_hand_angles({0, 0, 1001, 0, 0, 0});
  ASSERT_FALSE(checked.ok());
  EXPECT_EQ(checked.error().message.rfind("angle 3 (middle finger) 1001 is out of range", 0), 0U);
  EXPECT_FALSE(check_hand_angles({-2, 0, 0, 0, 0, 0}).ok());
}

// ---- Reply shapes --------------------------------------------------------------------------

TEST(ReplyShape, PlannedMotionsAreAcceptedNowAndCompleteLater) {
  for (const char* command :
       {"movej", "movel", "movej_p", "movec", "moves", "set_joint_step", "set_pos_step", "set_ort_step"}) {
    const auto shape = reply_shape(command);
    ASSERT_TRUE(shape.has_value()) << command;
    EXPECT_EQ(shape->keys, std::vector<std::string>{command});
    EXPECT_EQ(shape->result_field, "receive_state");
    EXPECT_TRUE(shape->has_reply);
    EXPECT_TRUE(shape->completes_later);
  }
}

TEST(ReplyShape, PassThroughAndFollowStreamsGetNoReply) {
  for (const char* command : {"movej_canfd", "movep_canfd", "movej_follow", "movep_follow"}) {
    const auto shape = reply_shape(command);
    ASSERT_TRUE(shape.has_value()) << command;
    EXPECT_FALSE(shape->has_reply);
  }
}

TEST(ReplyShape, SettersAndStopsAnswerWithTheirOwnNameAndAResultField) {
  const std::vector<std::pair<std::string, std::string>> table{
      {"set_arm_stop", "arm_stop"},
      {"set_arm_slow_stop", "arm_slow_stop"},
      {"set_arm_pause", "arm_pause"},
      {"set_arm_continue", "arm_continue"},
      {"set_delete_current_trajectory", "delete_current_trajectory"},
      {"set_arm_delete_trajectory", "arm_delete_trajectory"},
      {"set_arm_emergency_stop", "arm_emergency_stop"},
      {"set_arm_power", "arm_power"},
      {"set_joint_en_state", "joint_en_state"},
      {"set_joint_clear_err", "joint_clear_err"},
      {"clear_system_err", "clear_state"},
      {"set_init_pose", "init_pose"},
      {"set_realtime_push", "state"},
      {"set_gripper_route", "state"},
      {"set_hand_angle", "set_state"},
      {"set_hand_force", "set_state"}};
  for (const auto& [command, result_field] : table) {
    const auto shape = reply_shape(command);
    ASSERT_TRUE(shape.has_value()) << command;
    EXPECT_EQ(shape->keys, std::vector<std::string>{command});
    EXPECT_EQ(shape->result_field, result_field) << command;
    EXPECT_FALSE(shape->completes_later);
  }
}

TEST(ReplyShape, GripperMovesAcceptTheGenericAndTheSpecificName) {
  const auto shape = reply_shape("set_gripper_pick");
  ASSERT_TRUE(shape.has_value());
  EXPECT_EQ(shape->keys, (std::vector<std::string>{"set_gripper", "set_gripper_pick"}));
  EXPECT_EQ(shape->result_field, "state");
}

TEST(ReplyShape, QueriesAreAnsweredByTheirStateName) {
  const std::vector<std::pair<std::string, std::string>> table{{"get_current_arm_state", "current_arm_state"},
                                                               {"get_joint_degree", "joint_degree"},
                                                               {"get_current_joint_voltage", "current_joint_voltage"},
                                                               {"get_init_pose", "arm_init_pose"},
                                                               {"get_joint_max_pos", "joint_max_pos"},
                                                               {"get_arm_software_version", "arm_software_version"},
                                                               {"get_arm_software_info", "arm_software_info"},
                                                               {"get_realtime_push", "get_realtime_push"},
                                                               {"get_gripper_state", "get_gripper_state"}};
  for (const auto& [command, key] : table) {
    const auto shape = reply_shape(command);
    ASSERT_TRUE(shape.has_value()) << command;
    EXPECT_EQ(shape->keys, std::vector<std::string>{key});
    EXPECT_EQ(shape->result_field, "");
    EXPECT_TRUE(shape->has_reply);
  }
}

TEST(ReplyShape, UnknownCommandsHaveNone) {
  EXPECT_FALSE(reply_shape("set_joint_enable").has_value());
  EXPECT_FALSE(reply_shape("").has_value());
  EXPECT_FALSE(reply_shape("MOVEJ").has_value());
}

// ---- Messages ------------------------------------------------------------------------------

TEST(ParseMessage, ASetterReplyIsNamedByItsCommand) {
  const Message message = message_from(R"({"command":"movej","receive_state":true})");
  EXPECT_EQ(message.kind, MessageKind::kReply);
  EXPECT_EQ(message.key, "movej");
}

TEST(ParseMessage, AQueryReplyIsNamedByItsState) {
  const Message message = message_from(R"({"state":"joint_degree","joint":[0,0,0,0,0,0]})");
  EXPECT_EQ(message.kind, MessageKind::kReply);
  EXPECT_EQ(message.key, "joint_degree");
}

TEST(ParseMessage, ABooleanStateDoesNotNameTheMessage) {
  const Message message = message_from("{\n    \"command\": \"set_gripper\",\n    \"state\": true\n}");
  EXPECT_EQ(message.kind, MessageKind::kReply);
  EXPECT_EQ(message.key, "set_gripper");
}

TEST(ParseMessage, RecognisesTheTrajectoryEventAndThePush) {
  EXPECT_EQ(message_from(R"({"state":"current_trajectory_state","trajectory_state":true,"device":0})").kind,
            MessageKind::kTrajectoryEvent);
  EXPECT_EQ(message_from(kPushExample.substr(0, kPushExample.size() - 2)).kind, MessageKind::kRealtimePush);
}

TEST(ParseMessage, AnObjectWithoutANameIsOther) {
  const Message message = message_from(R"({"state":true,"command":7,"x":1})");
  EXPECT_EQ(message.kind, MessageKind::kOther);
  EXPECT_EQ(message.key, "");
  EXPECT_EQ(message_from("{}").kind, MessageKind::kOther);
}

TEST(ParseMessage, RefusesTextThatIsNotJsonQuotingIt) {
  const auto parsed = parse_message(R"({"command":"movej","receive_state":tr)");
  ASSERT_FALSE(parsed.ok());
  EXPECT_EQ(parsed.error().code, ErrorCode::kInvalidArgument);
  EXPECT_EQ(parsed.error().message, R"(not JSON: {"command":"movej","receive_state":tr)");
  EXPECT_FALSE(parse_message("").ok());
  EXPECT_FALSE(parse_message("{} {}").ok());
}

TEST(ParseMessage, RefusesJsonThatIsNotAnObject) {
  for (const char* line : {"[1,2]", "\"movej\"", "42", "null", "true"}) {
    const auto parsed = parse_message(line);
    ASSERT_FALSE(parsed.ok()) << line;
    EXPECT_EQ(parsed.error().message.rfind("JSON but not an object: ", 0), 0U) << parsed.error().message;
  }
}

TEST(ParseMessage, ShowsUnprintableBytesEscapedAndLongTextShortened) {
  const auto parsed = parse_message("\x01\xff" + std::string(100, 'x'));
  ASSERT_FALSE(parsed.ok());
  EXPECT_EQ(parsed.error().message.rfind("not JSON: \\x01\\xFFxxx", 0), 0U) << parsed.error().message;
  EXPECT_TRUE(parsed.error().message.ends_with("..."));
}

// ---- Reply success -------------------------------------------------------------------------

TEST(ReplySuccess, TrueIsSuccessAndFalseIsARefusal) {
  const auto shape = *reply_shape("movej");
  EXPECT_TRUE(reply_success(message_from(R"({"command":"movej","receive_state":true})"), shape, "movej").ok());
  const auto refused = reply_success(message_from(R"({"command":"movej","receive_state":false})"), shape, "movej");
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().code, ErrorCode::kRefused);
  EXPECT_EQ(refused.error().message, "the controller refused movej");
}

TEST(ReplySuccess, PassesOnTheReasonOfARefusal) {
  const auto shape = *reply_shape("set_arm_power");
  const auto refused =
      reply_success(message_from(R"({"command":"set_arm_power","arm_power":false,"error":"arm is in e-stop"})"), shape,
                    "set_arm_power");
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().message, "the controller refused set_arm_power: arm is in e-stop");
}

TEST(ReplySuccess, AcceptsZeroAndOne) {
  const auto shape = *reply_shape("set_joint_en_state");
  EXPECT_TRUE(reply_success(message_from(R"({"command":"set_joint_en_state","joint_en_state":1})"), shape, "x").ok());
  EXPECT_EQ(
      reply_success(message_from(R"({"command":"set_joint_en_state","joint_en_state":0})"), shape, "x").error().code,
      ErrorCode::kRefused);
}

TEST(ReplySuccess, GripperReplyFromTheVendorDoc) {
  const auto shape = *reply_shape("set_gripper_release");
  EXPECT_TRUE(reply_success(message_from("{\n    \"command\": \"set_gripper\",\n    \"state\": true\n}"), shape,
                            "set_gripper_release")
                  .ok());
  EXPECT_FALSE(
      reply_success(message_from(R"({"command":"set_gripper","state":false})"), shape, "set_gripper_release").ok());
}

TEST(ReplySuccess, AMissingOrMistypedFieldIsMalformed) {
  const auto shape = *reply_shape("clear_system_err");
  const auto missing = reply_success(message_from(R"({"command":"clear_system_err"})"), shape, "clear_system_err");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().code, ErrorCode::kInvalidArgument);
  EXPECT_EQ(missing.error().message, "the reply to clear_system_err: \"clear_state\": missing");
  for (const char* value : {"\"true\"", "2", "null", "[true]", "1.0"}) {
    const auto mistyped =
        reply_success(message_from(std::string(R"({"command":"clear_system_err","clear_state":)") + value + "}"), shape,
                      "clear_system_err");
    ASSERT_FALSE(mistyped.ok()) << value;
    EXPECT_EQ(mistyped.error().code, ErrorCode::kInvalidArgument) << value;
    EXPECT_EQ(mistyped.error().message,
              std::string(R"(the reply to clear_system_err: "clear_state": expected a bool (or 0/1), got )") + value);
  }
}

// ---- Trajectory events ---------------------------------------------------------------------

TEST(TrajectoryEvent, TheSpecExample) {
  const auto event = parse_trajectory_event(message_from(
      R"({"state":"current_trajectory_state","trajectory_state":true,"device":0,"trajectory_connect":0})"));
  ASSERT_TRUE(event.ok());
  EXPECT_TRUE(event.value().reached);
  EXPECT_EQ(event.value().device, Device::kArm);
  EXPECT_FALSE(event.value().more_segments);
}

TEST(TrajectoryEvent, GripperAndHandEventsFromTheVendorDocHaveNoTrajectoryConnect) {
  const auto gripper = parse_trajectory_event(
      message_from(R"({"state":"current_trajectory_state","trajectory_state":true,"device":1})"));
  ASSERT_TRUE(gripper.ok());
  EXPECT_EQ(gripper.value().device, Device::kGripper);
  EXPECT_FALSE(gripper.value().more_segments);
  const auto hand = parse_trajectory_event(message_from(
      "{\n    \"state\": \"current_trajectory_state\",\n    \"trajectory_state\": true,\n    \"device\": 2\n}"));
  ASSERT_TRUE(hand.ok());
  EXPECT_EQ(hand.value().device, Device::kHand);
}

TEST(TrajectoryEvent, ReportsFailureAndMoreSegments) {
  const auto failed = parse_trajectory_event(
      message_from(R"({"state":"current_trajectory_state","trajectory_state":false,"device":0})"));
  ASSERT_TRUE(failed.ok());
  EXPECT_FALSE(failed.value().reached);
  const auto segment = parse_trajectory_event(message_from(
      R"({"state":"current_trajectory_state","trajectory_state":true,"device":0,"trajectory_connect":1})"));
  ASSERT_TRUE(segment.ok());
  EXPECT_TRUE(segment.value().more_segments);
}

TEST(TrajectoryEvent, RefusesAnUnknownDeviceOrAMissingResult) {
  const auto unknown = parse_trajectory_event(
      message_from(R"({"state":"current_trajectory_state","trajectory_state":true,"device":5})"));
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.error().message, "current_trajectory_state: \"device\": expected an integer in 0..4, got 5");
  const auto missing = parse_trajectory_event(message_from(R"({"state":"current_trajectory_state","device":0})"));
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().message, "current_trajectory_state: \"trajectory_state\": missing");
}

// ---- Controller errors ---------------------------------------------------------------------

TEST(CollectErrors, ReadsAllThreeShapesAndDropsZeros) {
  EXPECT_TRUE(collect_errors(json::parse(R"({"err":[0]})")).empty());
  EXPECT_EQ(collect_errors(json::parse(R"({"err":[4097,0,4098]})")), (std::vector<std::uint16_t>{0x1001, 0x1002}));
  EXPECT_TRUE(collect_errors(json::parse(R"({"err":0})")).empty());
  EXPECT_EQ(collect_errors(json::parse(R"({"err":4109})")), (std::vector<std::uint16_t>{0x100D}));
  EXPECT_EQ(collect_errors(json::parse(R"({"arm_err":4098,"sys_err":20483})")),
            (std::vector<std::uint16_t>{0x1002, 0x5003}));
  EXPECT_TRUE(collect_errors(json::parse(R"({"arm_err":0,"sys_err":0})")).empty());
}

TEST(CollectErrors, ListsACodeOnce) {
  EXPECT_EQ(collect_errors(json::parse(R"({"err":[4097,4097],"arm_err":4097})")), (std::vector<std::uint16_t>{0x1001}));
}

TEST(CollectErrors, SkipsWhatIsNoErrorCode) {
  EXPECT_TRUE(collect_errors(json::parse("[4097]")).empty());
  EXPECT_TRUE(collect_errors(json::parse(R"({"joint":[1]})")).empty());
  EXPECT_EQ(collect_errors(json::parse(R"({"err":["4097",-1,70000,1.5,null,4099]})")),
            (std::vector<std::uint16_t>{0x1003}));
}

// ---- Arm state -----------------------------------------------------------------------------

TEST(ArmState, ReadsJointsPoseAndAnErrorList) {
  const auto state = parse_current_arm_state(
      message_from(R"({"state":"current_arm_state","arm_state":{"joint":[0,90000,-45000,0,-1,360000],)"
                   R"("pose":[300000,0,-100000,3142,0,-1571],"err":[0]}})"));
  ASSERT_TRUE(state.ok()) << state.error().message;
  EXPECT_EQ(state.value().dof, 6U);
  EXPECT_DOUBLE_EQ(state.value().joints_rad[1], kPi / 2);
  EXPECT_DOUBLE_EQ(state.value().joints_rad[2], -kPi / 4);
  EXPECT_DOUBLE_EQ(state.value().joints_rad[5], 2 * kPi);
  ASSERT_TRUE(state.value().has_pose);
  EXPECT_DOUBLE_EQ(state.value().pose.position_m[0], 0.3);
  EXPECT_DOUBLE_EQ(state.value().pose.position_m[2], -0.1);
  EXPECT_DOUBLE_EQ(state.value().pose.euler_rad[0], 3.142);
  EXPECT_DOUBLE_EQ(state.value().pose.euler_rad[2], -1.571);
  EXPECT_TRUE(state.value().errors.empty());
}

TEST(ArmState, ReadsTheOlderAndTheScalarErrorShapes) {
  const auto legacy = parse_current_arm_state(
      message_from(R"({"state":"current_arm_state","arm_state":{"joint":[0,0,0,0,0,0],"pose":[0,0,0,0,0,0],)"
                   R"("arm_err":4098,"sys_err":0}})"));
  ASSERT_TRUE(legacy.ok());
  EXPECT_EQ(legacy.value().errors, std::vector<std::uint16_t>{0x1002});
  const auto scalar = parse_current_arm_state(message_from(
      R"({"state":"current_arm_state","arm_state":{"joint":[0,0,0,0,0,0],"pose":[0,0,0,0,0,0],"err":0}})"));
  ASSERT_TRUE(scalar.ok());
  EXPECT_TRUE(scalar.value().errors.empty());
}

TEST(ArmState, TakesItsDofFromTheJointArray) {
  const auto seven = parse_current_arm_state(
      message_from(R"({"state":"current_arm_state","arm_state":{"joint":[1,2,3,4,5,6,7],"err":[4109]}})"));
  ASSERT_TRUE(seven.ok());
  EXPECT_EQ(seven.value().dof, 7U);
  EXPECT_FALSE(seven.value().has_pose);
  EXPECT_EQ(seven.value().errors, std::vector<std::uint16_t>{0x100D});
  const auto eight = parse_current_arm_state(
      message_from(R"({"state":"current_arm_state","arm_state":{"joint":[1,2,3,4,5,6,7,8],"err":[0]}})"));
  ASSERT_FALSE(eight.ok());
  EXPECT_EQ(eight.error().message,
            "current_arm_state reply: \"arm_state.joint\": expected an array of 1..7 integers, got 8 entries");
  EXPECT_FALSE(
      parse_current_arm_state(message_from(R"({"state":"current_arm_state","arm_state":{"joint":[],"err":[0]}})"))
          .ok());
}

TEST(ArmState, RefusesMalformedReplies) {
  const std::vector<std::pair<std::string, std::string>> cases{
      {R"({"state":"current_arm_state"})", "\"arm_state\": missing"},
      {R"({"state":"current_arm_state","arm_state":[1]})", "\"arm_state\": expected an object, got an array"},
      {R"({"state":"current_arm_state","arm_state":{"joint":[0,"x"],"err":[0]}})",
       "\"arm_state.joint\": entry 1: expected an integer, got \"x\""},
      {R"({"state":"current_arm_state","arm_state":{"joint":[0,1.5],"err":[0]}})",
       "\"arm_state.joint\": entry 1: expected an integer, got 1.5"},
      {R"({"state":"current_arm_state","arm_state":{"joint":[0],"pose":[1,2,3],"err":[0]}})",
       "\"arm_state.pose\": expected an array of 6 integers, got 3 entries"},
      {R"({"state":"current_arm_state","arm_state":{"joint":[0]}})",
       "\"arm_state\": no error field (\"err\", or \"arm_err\" and \"sys_err\")"},
      {R"({"state":"current_arm_state","arm_state":{"joint":[0],"err":[65536]}})",
       "\"arm_state.err\": expected error codes 0..65535, got 65536"},
      {R"({"state":"current_arm_state","arm_state":{"joint":[0],"sys_err":"none"}})",
       "\"arm_state.sys_err\": expected error codes 0..65535, got \"none\""},
  };
  for (const auto& [line, problem] : cases) {
    const auto state = parse_current_arm_state(message_from(line));
    ASSERT_FALSE(state.ok()) << line;
    EXPECT_EQ(state.error().code, ErrorCode::kInvalidArgument);
    EXPECT_EQ(state.error().message, "current_arm_state reply: " + problem) << line;
  }
}

// ---- Real-time push ------------------------------------------------------------------------

TEST(RealtimePush, TheSpecExampleInRobotdUnits) {
  const auto push = parse_realtime_push(kPushExample);
  ASSERT_TRUE(push.ok()) << push.error().message;
  const RealtimePush& p = push.value();
  EXPECT_EQ(p.dof, 6U);
  EXPECT_DOUBLE_EQ(p.position_rad[0], 13.434 * kRadPerDegree);
  EXPECT_DOUBLE_EQ(p.position_rad[1], -69.764 * kRadPerDegree);
  EXPECT_DOUBLE_EQ(p.position_rad[5], -0.223 * kRadPerDegree);
  EXPECT_DOUBLE_EQ(p.current_a[1], 0.85);
  EXPECT_DOUBLE_EQ(p.voltage_v[0], 48.0);
  EXPECT_DOUBLE_EQ(p.temperature_c[0], 35.2);
  EXPECT_TRUE(p.enabled[5]);
  EXPECT_FALSE(p.enabled[6]);
  EXPECT_EQ(p.joint_errors[0], 0);
  EXPECT_TRUE(p.errors.empty());
  EXPECT_FALSE(p.has_speed);
  ASSERT_TRUE(p.has_pose);
  EXPECT_DOUBLE_EQ(p.position_m[0], 0.578568);
  EXPECT_DOUBLE_EQ(p.position_m[2], 0.345856);
  EXPECT_DOUBLE_EQ(p.euler_rad[0], 3.142);
  EXPECT_DOUBLE_EQ(p.euler_rad[1], -1.571);
  EXPECT_EQ(p.quaternion_wxyz, (std::array<double, 4>{0.5, -0.5, 0.5, -0.5}));
  EXPECT_EQ(p.arm_status, "idle");
}

TEST(RealtimePush, TheTrailingCrLfIsOptional) {
  EXPECT_TRUE(parse_realtime_push(kPushExample.substr(0, kPushExample.size() - 2)).ok());
}

/// The example with one part replaced: `from` by `to`.
std::string push_with(std::string_view from, std::string_view to) {
  std::string text(kPushExample);
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(RealtimePush, JointSpeedInEachOfTheCandidateUnits) {
  const std::string text = push_with(R"("joint_voltage")", R"("joint_speed":[1000,-500,0,0,0,0],"joint_voltage")");
  const auto centi_degrees = parse_realtime_push(text, SpeedUnit::kCentiDegreesPerSecond);
  ASSERT_TRUE(centi_degrees.ok()) << centi_degrees.error().message;
  EXPECT_TRUE(centi_degrees.value().has_speed);
  EXPECT_NEAR(centi_degrees.value().speed_rad_s[0], 10 * kRadPerDegree, 1e-12);
  EXPECT_NEAR(centi_degrees.value().speed_rad_s[1], -5 * kRadPerDegree, 1e-12);
  EXPECT_NEAR(parse_realtime_push(text, SpeedUnit::kCentiRpm).value().speed_rad_s[0], 60 * kRadPerDegree, 1e-12);
  EXPECT_NEAR(parse_realtime_push(text, SpeedUnit::kFiftiethDegreesPerSecond).value().speed_rad_s[0],
              20 * kRadPerDegree, 1e-12);
}

TEST(RealtimePush, ReadsTheOlderErrorFieldsAndJointErrorBits) {
  const std::string text = push_with(R"("err":[0])", R"("arm_err":4097,"sys_err":20488)");
  const std::string with_bits =
      push_with(R"("joint_err_code":[0,0,0,0,0,0])", R"("joint_err_code":[0,61440,40,0,0,0])");
  const auto legacy = parse_realtime_push(text);
  ASSERT_TRUE(legacy.ok()) << legacy.error().message;
  EXPECT_EQ(legacy.value().errors, (std::vector<std::uint16_t>{0x1001, 0x5008}));
  const auto bits = parse_realtime_push(with_bits);
  ASSERT_TRUE(bits.ok());
  EXPECT_EQ(bits.value().joint_errors[1], 0xF000);
  EXPECT_EQ(bits.value().joint_errors[2], 0x0028);
}

TEST(RealtimePush, ASevenJointArmWithoutWaypointOrStatus) {
  const std::string text =
      R"({"state":"realtime_arm_joint_state","err":[4109],"joint_status":{)"
      R"("joint_position":[1,2,3,4,5,6,-7],"joint_current":[0,0,0,0,0,0,1000],"joint_voltage":[0,0,0,0,0,0,0],)"
      R"("joint_temperature":[0,0,0,0,0,0,0],"joint_en_flag":[true,true,true,true,true,true,false],)"
      R"("joint_err_code":[0,0,0,0,0,0,1]}})";
  const auto push = parse_realtime_push(text);
  ASSERT_TRUE(push.ok()) << push.error().message;
  EXPECT_EQ(push.value().dof, 7U);
  EXPECT_DOUBLE_EQ(push.value().position_rad[6], -0.007 * kRadPerDegree);
  EXPECT_DOUBLE_EQ(push.value().current_a[6], 0.001);
  EXPECT_FALSE(push.value().enabled[6]);
  EXPECT_EQ(push.value().joint_errors[6], 1);
  EXPECT_EQ(push.value().errors, std::vector<std::uint16_t>{0x100D});
  EXPECT_FALSE(push.value().has_pose);
  EXPECT_EQ(push.value().arm_status, "");
}

TEST(RealtimePush, RefusesMalformedDatagramsSayingWhatIsWrong) {
  const std::vector<std::pair<std::string, std::string>> cases{
      {push_with(R"("joint_current":[120000,850000,430000,51000,22000,3000])", R"("joint_current":[1,2,3,4,5])"),
       "\"joint_status.joint_current\": expected an array of at least 6 integers, got 5 entries"},
      {push_with(R"("joint_position":[13434,-69764,2926,-4742,-45721,-223])", R"("joint_position":[1,2,3,4,5,6,7,8])"),
       "\"joint_status.joint_position\": expected an array of 1..7 integers, got 8 entries"},
      {push_with(R"("joint_en_flag":[1,1,1,1,1,1])", R"("joint_en_flag":[1,1,2,1,1,1])"),
       "\"joint_status.joint_en_flag\": entry 2: expected a bool (or 0/1), got 2"},
      {push_with(R"("joint_err_code":[0,0,0,0,0,0])", R"("joint_err_code":[0,0,0,0,0,-1])"),
       "\"joint_status.joint_err_code\": entry 5: expected an integer in 0..65535, got -1"},
      {push_with(R"("quat":[500000,-500000,500000,-500000])", R"("quat":[1,0,0])"),
       "\"waypoint.quat\": expected an array of 4 integers, got 3 entries"},
      {push_with(R"("arm_current_status":"idle")", R"("arm_current_status":3)"),
       "\"arm_current_status\": expected a string, got a number"},
      {push_with(R"("err":[0],)", ""), "the message: no error field (\"err\", or \"arm_err\" and \"sys_err\")"},
      {push_with(R"("joint_status":{)", R"("joint_status":7,"x":{)"),
       "\"joint_status\": expected an object, got a number"},
  };
  for (const auto& [text, problem] : cases) {
    const auto push = parse_realtime_push(text);
    ASSERT_FALSE(push.ok()) << text;
    EXPECT_EQ(push.error().code, ErrorCode::kInvalidArgument);
    EXPECT_EQ(push.error().message, "realtime push: " + problem) << text;
  }
}

TEST(RealtimePush, RefusesOtherMessagesAndNonJson) {
  EXPECT_EQ(parse_realtime_push(R"({"state":"current_arm_state"})").error().message,
            "realtime push: \"state\" is \"current_arm_state\", expected \"realtime_arm_joint_state\"");
  EXPECT_EQ(parse_realtime_push("{}").error().message, "realtime push: \"state\": missing");
  EXPECT_EQ(parse_realtime_push("[]").error().message, "realtime push: JSON but not an object: []");
  EXPECT_EQ(parse_realtime_push(kPushExample.substr(0, 40)).error().message.rfind("realtime push: not JSON: ", 0), 0U);
  EXPECT_FALSE(parse_realtime_push("").ok());
  EXPECT_FALSE(parse_realtime_push("\r\n").ok());
}

// ---- Gripper and software info -------------------------------------------------------------

TEST(GripperState, TheVendorExample) {
  const auto state = parse_gripper_state(message_from(
      "{\n    \"command\": \"get_gripper_state\",\n    \"enable\": 1,\n    \"status\": 1,\n    \"error\": 0,\n"
      "    \"mode\": 1,\n    \"current_force\": 100,\n    \"temperature\": 40,\n    \"actpos\": 150\n}"));
  ASSERT_TRUE(state.ok()) << state.error().message;
  EXPECT_TRUE(state.value().enabled);
  EXPECT_TRUE(state.value().online);
  EXPECT_EQ(state.value().error_bits, 0);
  EXPECT_EQ(state.value().mode, 1);
  EXPECT_EQ(state.value().force_g, 100);
  EXPECT_EQ(state.value().temperature_c, 40);
  EXPECT_EQ(state.value().opening, 150);
}

TEST(GripperState, RefusesAMissingField) {
  const auto state = parse_gripper_state(
      message_from(R"({"command":"get_gripper_state","enable":1,"status":0,"error":0,"mode":1,"temperature":40})"));
  ASSERT_FALSE(state.ok());
  EXPECT_EQ(state.error().message, "get_gripper_state reply: \"current_force\": missing");
}

TEST(SoftwareInfo, Gen4NamesTheControllerVersionAtTheTop) {
  const auto info = parse_software_info(
      message_from(R"({"command":"arm_software_info","Product_version":"RM75-6F","robot_controller_version":"4.0",)"
                   R"("ctrl_info":{"build_time":"2024","version":"1.6.5"}})"));
  ASSERT_TRUE(info.ok()) << info.error().message;
  EXPECT_EQ(info.value().product_version, "RM75-6F");
  EXPECT_EQ(info.value().controller_version, "4.0");
}

TEST(SoftwareInfo, Gen3NamesItInsideCtrlInfo) {
  const auto info = parse_software_info(
      message_from(R"({"command":"arm_software_info","Product_version":"RM65-B","ctrl_info":{"version":"1.6.5"}})"));
  ASSERT_TRUE(info.ok());
  EXPECT_EQ(info.value().controller_version, "1.6.5");
  const auto none = parse_software_info(message_from(R"({"command":"arm_software_info","Product_version":"RM65-B"})"));
  ASSERT_TRUE(none.ok());
  EXPECT_EQ(none.value().controller_version, "");
}

TEST(SoftwareInfo, Gen2ShowsThePlanVersionInHex) {
  const auto info = parse_software_info(
      message_from(R"({"state":"arm_software_version","Product_version":"RM65-B","Plan_version":7012610})"));
  ASSERT_TRUE(info.ok()) << info.error().message;
  EXPECT_EQ(info.value().product_version, "RM65-B");
  EXPECT_EQ(info.value().controller_version, "0x6B0102");
}

TEST(SoftwareInfo, RefusesOtherRepliesAndMissingFields) {
  EXPECT_FALSE(parse_software_info(message_from(R"({"state":"joint_degree","joint":[0]})")).ok());
  EXPECT_EQ(
      parse_software_info(message_from(R"({"command":"arm_software_info","Product_version":65})")).error().message,
      "arm_software_info reply: \"Product_version\": expected a string, got a number");
  EXPECT_FALSE(
      parse_software_info(message_from(R"({"state":"arm_software_version","Product_version":"RM65-B"})")).ok());
}

// ---- Error tables --------------------------------------------------------------------------

TEST(ErrorTables, SystemErrorsInTheSpecWords) {
  EXPECT_EQ(system_error_text(0x1002), "0x1002 target angle beyond joint limit");
  EXPECT_EQ(system_error_text(0x100D), "0x100D collision detected");
  EXPECT_EQ(system_error_text(0x5003), "0x5003 controller over-temperature");
  EXPECT_EQ(system_error_text(0x5001), "0x5001 reserved (older ROS header: base tipped)");
  EXPECT_EQ(system_error_text(0x1234), "0x1234 unknown controller error");
  EXPECT_EQ(system_error_text(0x0000), "0x0000 OK");
}

TEST(ErrorTables, SeverityFollowsTheWebNoteAndControllerHardwareIsSevere) {
  for (const int code : {0x1001, 0x1004, 0x1005, 0x1006, 0x1008, 0x5003, 0x5009}) {
    EXPECT_TRUE(system_error_is_severe(static_cast<std::uint16_t>(code))) << code;
  }
  for (const int code : {0x1002, 0x1003, 0x1007, 0x100D, 0x2001, 0x0000, 0x1234}) {
    EXPECT_FALSE(system_error_is_severe(static_cast<std::uint16_t>(code))) << code;
  }
}

TEST(ErrorTables, JointErrorBitsAndTheFrameLossValue) {
  EXPECT_EQ(joint_error_text(0x0028), "over-temperature, encoder error");
  EXPECT_EQ(joint_error_text(0x0001), "FOC error");
  EXPECT_EQ(joint_error_text(0x8000), "multi-turn count lost");
  EXPECT_EQ(joint_error_text(0xF000), "communication frame loss");
  EXPECT_EQ(joint_error_text(0x7000), "current detection error, brake release failed, position command step warning");
  EXPECT_EQ(joint_error_text(0), "");
}

TEST(ErrorTables, GripperErrorBitsAndModes) {
  EXPECT_EQ(gripper_error_text(0x03), "stall, over-temperature");
  EXPECT_EQ(gripper_error_text(0x1C), "over-current, driver error, internal communication error");
  EXPECT_EQ(gripper_error_text(0x20), "reserved bit 5");
  EXPECT_EQ(gripper_error_text(0), "");
  EXPECT_EQ(gripper_mode_text(1), "fully open, idle");
  EXPECT_EQ(gripper_mode_text(6), "stopped by force while closing");
  EXPECT_EQ(gripper_mode_text(0), "unknown mode 0");
  EXPECT_EQ(gripper_mode_text(9), "unknown mode 9");
}

// ---- Models --------------------------------------------------------------------------------

TEST(Models, FoundByTheModelPartOfTheProductVersion) {
  const auto rm65 = find_model("RM65-B");
  ASSERT_TRUE(rm65.has_value());
  EXPECT_EQ(rm65->name, "RM65");
  EXPECT_EQ(rm65->dof, 6U);
  EXPECT_DOUBLE_EQ(rm65->max_rad[1], 130 * kRadPerDegree);
  EXPECT_DOUBLE_EQ(rm65->min_rad[5], -2 * kPi);
  EXPECT_EQ(find_model("RM75-6F")->dof, 7U);
  EXPECT_EQ(find_model("RM65")->name, "RM65");
  EXPECT_EQ(find_model("RML63-B")->name, "RML63");
}

TEST(Models, AsymmetricRangesFromTheDocText) {
  const auto gen72 = find_model("GEN72-B");
  ASSERT_TRUE(gen72.has_value());
  EXPECT_EQ(gen72->dof, 7U);
  EXPECT_DOUBLE_EQ(gen72->min_rad[3], -170 * kRadPerDegree);
  EXPECT_DOUBLE_EQ(gen72->max_rad[3], 55 * kRadPerDegree);
  EXPECT_DOUBLE_EQ(gen72->min_rad[5], -90 * kRadPerDegree);
  EXPECT_DOUBLE_EQ(gen72->max_rad[5], 120 * kRadPerDegree);
  const auto eco65 = find_model("ECO65-6F");
  ASSERT_TRUE(eco65.has_value());
  EXPECT_DOUBLE_EQ(eco65->max_rad[1], 135 * kRadPerDegree);
  EXPECT_DOUBLE_EQ(eco65->min_rad[2], -160 * kRadPerDegree);
  EXPECT_DOUBLE_EQ(find_model("RML63")->max_rad[2], 145 * kRadPerDegree);
}

TEST(Models, UnknownModelsAreNotFound) {
  EXPECT_FALSE(find_model("ECO63-B").has_value());
  EXPECT_FALSE(find_model("").has_value());
  EXPECT_FALSE(find_model("rm65-b").has_value());
  EXPECT_FALSE(find_model("RM6").has_value());
}

TEST(Models, EveryKnownModelHasOrderedLimitsForItsJoints) {
  EXPECT_EQ(known_models().size(), 5U);
  for (const ArmModel& model : known_models()) {
    ASSERT_LE(model.dof, kMaxDof);
    for (std::size_t j = 0; j < model.dof; ++j) EXPECT_LT(model.min_rad[j], model.max_rad[j]) << model.name << j;
    EXPECT_EQ(find_model(std::string(model.name) + "-B")->name, model.name);
  }
}

// ---- No decoder throws ---------------------------------------------------------------------

/// Runs every decoder on a line, as the driver might on anything the controller sends.
void decode_everything(const std::string& line) {
  (void)parse_realtime_push(line);
  (void)parse_realtime_push(line, SpeedUnit::kCentiRpm);
  const auto message = parse_message(line);
  if (!message.ok()) return;
  Message reply = message.value();
  (void)collect_errors(reply.body);
  (void)parse_trajectory_event(reply);
  (void)parse_current_arm_state(reply);
  (void)parse_gripper_state(reply);
  for (const char* key : {"arm_software_info", "arm_software_version"}) {
    reply.key = key;
    (void)parse_software_info(reply);
  }
  for (const char* command : {"movej", "set_gripper_pick", "set_hand_angle", "set_realtime_push"}) {
    (void)reply_success(reply, *reply_shape(command), command);
  }
}

/// A copy of `value` with one node (chosen by `pick`) replaced by `replacement`.
json replace_one_node(const json& value, std::size_t& pick, const json& replacement) {
  if (pick-- == 0) return replacement;
  json out = value;
  if (value.is_object()) {
    for (auto& [key, child] : out.items()) child = replace_one_node(value[key], pick, replacement);
  } else if (value.is_array()) {
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = replace_one_node(value[i], pick, replacement);
  }
  return out;
}

TEST(Fuzz, NoDecoderThrowsOnMutatedMessages) {
  const std::vector<std::string> seeds{
      std::string(kPushExample.substr(0, kPushExample.size() - 2)),
      R"({"state":"current_arm_state","arm_state":{"joint":[0,90000,-45000,0,-1,360000],"pose":[1,2,3,4,5,6],"err":[0]}})",
      R"({"state":"current_arm_state","arm_state":{"joint":[0,0,0,0,0,0,0],"arm_err":4098,"sys_err":0}})",
      R"({"state":"current_trajectory_state","trajectory_state":true,"device":0,"trajectory_connect":1})",
      R"({"command":"get_gripper_state","enable":1,"status":1,"error":0,"mode":1,"current_force":100,"temperature":40,"actpos":150})",
      R"({"command":"arm_software_info","Product_version":"RM75-6F","robot_controller_version":"4.0","ctrl_info":{"version":"1"}})",
      R"({"state":"arm_software_version","Product_version":"RM65-B","Plan_version":7012610})",
      R"({"command":"set_gripper","state":true})",
      R"({"command":"movej","receive_state":false,"error":"x"})",
  };
  const std::vector<json> replacements{json(nullptr),
                                       json(true),
                                       json(-1),
                                       json(1.5),
                                       json("text"),
                                       json::array(),
                                       json::object(),
                                       json(std::numeric_limits<std::uint64_t>::max()),
                                       json(std::numeric_limits<std::int64_t>::min()),
                                       json::parse("[1e308,-1e308]"),
                                       json::parse(R"({"err":[4097]})")};
  std::mt19937 random(20240615);  // fixed: the same inputs on every run
  std::size_t cases = 0;
  for (const std::string& seed : seeds) {
    const json parsed = json::parse(seed);
    // Type confusion: every node replaced by every kind of value.
    for (std::size_t node = 0; node < 64; ++node) {
      for (const json& replacement : replacements) {
        std::size_t pick = node;
        const std::string mutated = replace_one_node(parsed, pick, replacement).dump();
        ASSERT_NO_THROW(decode_everything(mutated)) << mutated;
        ++cases;
      }
    }
    // Byte damage: truncation, flipped, inserted and deleted bytes.
    for (int round = 0; round < 300; ++round) {
      std::string mutated = seed;
      std::uniform_int_distribution<std::size_t> position(0, mutated.size() - 1);
      std::uniform_int_distribution<int> byte(0, 255);
      switch (round % 4) {
        case 0:
          mutated.resize(position(random));
          break;
        case 1:
          mutated[position(random)] = static_cast<char>(byte(random));
          break;
        case 2:
          mutated.insert(position(random), 1, static_cast<char>(byte(random)));
          break;
        default:
          mutated.erase(position(random), 1 + position(random) % 8);
          break;
      }
      ASSERT_NO_THROW(decode_everything(mutated)) << mutated;
      ++cases;
    }
  }
  EXPECT_GT(cases, 5000U);
}

TEST(Fuzz, LineSplitterDeliversEveryMessageWhateverTheChunking) {
  std::mt19937 random(7);
  std::string stream;
  for (int i = 0; i < 50; ++i) stream += frame(json{{"command", "movej"}, {"n", i}}) + (i % 7 == 0 ? "\r\n" : "");
  for (int round = 0; round < 50; ++round) {
    LineSplitter splitter(64);
    std::vector<std::string> lines;
    for (std::size_t at = 0; at < stream.size();) {
      const std::size_t chunk = std::uniform_int_distribution<std::size_t>(1, 40)(random);
      splitter.append(std::string_view(stream).substr(at, chunk));
      at += chunk;
      while (auto line = splitter.next()) lines.push_back(*line);
    }
    ASSERT_EQ(lines.size(), 50U);
    EXPECT_EQ(message_from(lines[49]).body["n"], 49);
    EXPECT_EQ(splitter.oversized(), 0U);
  }
}

TEST(Fuzz, LineSplitterSurvivesGarbage) {
  std::mt19937 random(11);
  std::uniform_int_distribution<int> byte(0, 255);
  LineSplitter splitter(32);
  std::size_t total_bytes = 0;
  for (int round = 0; round < 2000; ++round) {
    std::string chunk(std::uniform_int_distribution<std::size_t>(0, 50)(random), '\0');
    for (char& c : chunk) {
      const int value = byte(random);
      c = value < 40 ? '\r' : value < 80 ? '\n' : static_cast<char>(value);
    }
    total_bytes += chunk.size();
    ASSERT_NO_THROW(splitter.append(chunk));
    while (auto line = splitter.next()) {
      EXPECT_LE(line->size(), 32U);
      EXPECT_FALSE(line->empty());
      ASSERT_NO_THROW(decode_everything(*line));
    }
  }
  EXPECT_GT(total_bytes, 0U);
}

}  // namespace
}  // namespace robotd::realman
