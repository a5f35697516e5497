// Every request the xArm SDK sent in the recorded session, decoded with robotd's codec and
// encoded again with the driver's request builders: the bytes must be the SDK's, or the
// deliberate difference differences.json lists (checked to be exactly robotd's value), or one of
// its registers robotd never sends (checked to have no request). Every reply the SDK accepted,
// parsed with the driver's reply parsers and encoded again byte for byte.
#include <map>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "conformance_report.hpp"
#include "transcript.hpp"
#include "vector_file.hpp"

namespace robotd::conformance::xarm {
namespace {

using namespace robotd::xarm;

struct Difference {
  std::size_t keep = 0;
  std::size_t zeros = 0;
};

const std::map<std::uint8_t, Difference>& differences() {
  static const std::map<std::uint8_t, Difference> loaded = [] {
    std::map<std::uint8_t, Difference> table;
    const nlohmann::json listed = load_json("differences.json");  // outlives the loop
    for (const auto& entry : listed.at("requests")) {
      table[entry.at("register").get<std::uint8_t>()] =
          Difference{.keep = entry.at("keep").get<std::size_t>(), .zeros = entry.at("zeros").get<std::size_t>()};
    }
    return table;
  }();
  return loaded;
}

/// differences.json's not_sent: register → the execution state the SDK returned for its reply.
const std::map<std::uint8_t, int>& not_sent() {
  static const std::map<std::uint8_t, int> loaded = [] {
    std::map<std::uint8_t, int> table;
    const nlohmann::json listed = load_json("differences.json");  // outlives the loop
    for (const auto& entry : listed.at("not_sent")) {
      table[entry.at("register").get<std::uint8_t>()] = entry.at("sdk_code").get<int>();
    }
    return table;
  }();
  return loaded;
}

/// The request robotd's driver codec builds for what the SDK's request asks; nullopt when robotd
/// has no builder for the register (not implemented).
std::optional<Result<Request>> robotd_request(const Frame& sdk) {
  const ByteView body = sdk.body;
  const auto wrap = [](auto parsed, auto build) -> Result<Request> {
    if (!parsed) return parsed.error();
    return build(parsed.value());
  };
  switch (static_cast<Register>(sdk.reg)) {
    case Register::kGetVersion:
    case Register::kGetRobotSn:
    case Register::kGetState:
    case Register::kGetCmdnum:
    case Register::kGetErrCode:
    case Register::kCleanErr:
    case Register::kCleanWar:
    case Register::kGetTcpPose:
    case Register::kGetJointPos:
    case Register::kGetReducedMode:
    case Register::kServoGetDbmsg:
      return Result<Request>(plain_request(static_cast<Register>(sdk.reg)));
    case Register::kSetReducedMode:
      return wrap(parse_u8_param(sdk.reg, body), [](int on) { return set_reduced_mode_request(on == 1); });
    case Register::kSetFeedbackType:
      return wrap(parse_u8_param(sdk.reg, body),
                  [](int types) { return set_feedback_type_request(static_cast<std::uint8_t>(types)); });
    case Register::kMotionEnable:
      return wrap(parse_motion_enable(body), [](const JointSwitch& s) { return motion_enable_request(s.joint, s.on); });
    case Register::kSetState:
      return wrap(parse_u8_param(sdk.reg, body), [](int state) { return set_state_request(state); });
    case Register::kSetMode:
      return wrap(parse_u8_param(sdk.reg, body), [](int mode) { return set_mode_request(mode); });
    case Register::kMoveLine:
      return wrap(parse_line_move(sdk.reg, body), [](const LineMove& move) { return move_line_request(move); });
    case Register::kMoveJoint:
      return wrap(parse_joint_move(body), [](const JointMove& move) { return move_joint_request(move); });
    case Register::kMoveGohome:
      return wrap(parse_gohome(body), [](const JointMove& move) { return move_gohome_request(move); });
    case Register::kServoJ:
      return wrap(parse_joint_params(sdk.reg, body), [](const JointValues& joints) { return servo_j_request(joints); });
    case Register::kGetFk:
      return wrap(parse_joint_params(sdk.reg, body), [](const JointValues& joints) { return get_fk_request(joints); });
    case Register::kIsJointLimit:
      return wrap(parse_joint_params(sdk.reg, body),
                  [](const JointValues& joints) { return is_joint_limit_request(joints); });
    case Register::kToolRead16:
      return wrap(parse_tool_register_access(sdk.reg, body), [](const ToolRegisterAccess& access) {
        return tool_register_read_request(access.id, access.address);
      });
    case Register::kToolModbus:
      return wrap(parse_tool_modbus_request(body), [](const ToolModbusRequest& modbus) {
        return modbus.function == kModbusReadHolding
                   ? tool_modbus_read_request(modbus.slave, modbus.address, modbus.count)
                   : tool_modbus_write_request(modbus.slave, modbus.address, modbus.values);
      });
    default:
      return std::nullopt;
  }
}

TEST(XarmCodec, TheDriverBuildsTheSdksRequests) {
  for (const Exchange& exchange : transcript().exchanges) {
    const Frame& sdk = exchange.request_frame;
    const auto built = robotd_request(sdk);
    const bool listed_not_sent = not_sent().contains(sdk.reg);
    if (!built) {
      record("requests", listed_not_sent ? Outcome::deliberate_difference : Outcome::not_implemented);
      continue;
    }
    if (listed_not_sent) {
      record("requests", Outcome::failed);
      ADD_FAILURE() << register_name(sdk.reg) << " is listed as never sent, but robotd builds it";
      continue;
    }
    ASSERT_TRUE(built->ok()) << register_name(sdk.reg) << ": " << built->error().message;
    const Request& robotd = built->value();
    const auto difference = differences().find(sdk.reg);
    Bytes expected = sdk.body;
    if (difference != differences().end()) {
      expected.resize(std::min(expected.size(), difference->second.keep));
      expected.insert(expected.end(), difference->second.zeros, 0);
    }
    const bool same = robotd.reg == sdk.reg && robotd.params == expected;
    const bool deliberate = difference != differences().end() && expected != sdk.body;
    record("requests", !same ? Outcome::failed : deliberate ? Outcome::deliberate_difference : Outcome::passed);
    EXPECT_TRUE(same) << register_name(sdk.reg) << " (step " << exchange.step << ")\n  SDK    " << hex_text(sdk.body)
                      << "\n  robotd " << hex_text(robotd.params) << "\n  expected " << hex_text(expected);
  }
}

/// The reply's data parsed with the driver's parser and encoded again; nullopt when robotd does
/// not read this register's reply.
std::optional<Result<Bytes>> reencoded_reply(const Frame& request, const Reply& reply) {
  const ByteView data = reply.data;
  const auto wrap = [](auto parsed, auto encode) -> Result<Bytes> {
    if (!parsed) return parsed.error();
    return encode(parsed.value());
  };
  switch (static_cast<Register>(request.reg)) {
    case Register::kGetVersion:
      return wrap(parse_version(data), [](const Version& version) { return encode_version(version); });
    case Register::kGetRobotSn:
      return wrap(parse_robot_sn(data), [](const SerialNumbers& serials) { return encode_robot_sn(serials); });
    case Register::kGetState:
      return wrap(parse_state(data), [](int state) { return encode_state(state); });
    case Register::kGetCmdnum:
    case Register::kMoveLine:
    case Register::kMoveJoint:
    case Register::kMoveGohome:
      return wrap(parse_cmdnum(data), [](std::uint16_t count) { return encode_cmdnum(count); });
    case Register::kGetErrCode:
      return wrap(parse_err_code(data), [](const ErrorWarning& codes) { return encode_err_code(codes); });
    case Register::kGetTcpPose:
    case Register::kGetFk:
      return wrap(parse_pose(data), [](const Pose& pose) { return encode_pose(pose); });
    case Register::kGetJointPos:
      return wrap(parse_joints(data), [](const JointValues& joints) { return encode_joints(joints); });
    case Register::kIsJointLimit:
      return wrap(parse_limit_flag(data), [](bool outside) { return encode_limit_flag(outside); });
    case Register::kGetReducedMode:
      return wrap(parse_reduced_mode(data), [](bool on) { return encode_reduced_mode(on); });
    case Register::kServoGetDbmsg:
      return wrap(parse_servo_dbmsg(data),
                  [](const std::array<ServoStatus, 8>& servos) { return encode_servo_dbmsg(servos); });
    case Register::kMotionEnable:
    case Register::kSetState:
    case Register::kSetMode:
    case Register::kCleanWar:
    case Register::kServoJ:
    case Register::kSetReducedMode:
    case Register::kSetFeedbackType:
      return Result<Bytes>(Bytes{});  // state only
    case Register::kToolRead16:
      return wrap(parse_tool_register_value(data),
                  [](std::int32_t value) { return encode_tool_register_value(value); });
    case Register::kToolModbus: {
      const auto modbus = parse_tool_modbus_request(request.body);
      if (!modbus) return modbus.error();
      const ToolModbusRequest& asked = modbus.value();
      if (asked.function == kModbusReadHolding) {
        return wrap(parse_tool_modbus_read_reply(data, asked.slave, asked.count),
                    [&](const std::vector<std::uint16_t>& values) {
                      return encode_tool_modbus_read_reply(asked.slave, values);
                    });
      }
      if (auto echoed = parse_tool_modbus_write_reply(data, asked.slave, asked.address, asked.count); !echoed) {
        return echoed.error();
      }
      return Result<Bytes>(encode_tool_modbus_write_reply(asked.slave, asked.address, asked.count));
    }
    default:
      return std::nullopt;
  }
}

TEST(XarmCodec, TheDriverReadsTheRepliesTheSdkRead) {
  for (const Exchange& exchange : transcript().exchanges) {
    const auto reply = parse_reply(exchange.reply_frame);
    ASSERT_TRUE(reply) << reply.error().message;
    if (const auto listed = not_sent().find(exchange.request_frame.reg); listed != not_sent().end()) {
      // robotd never sends it, but reads such a reply as the SDK did.
      const int code = execution_state(reply.value());
      record("replies", code == listed->second ? Outcome::passed : Outcome::failed);
      EXPECT_EQ(code, listed->second) << register_name(exchange.request_frame.reg) << " reply "
                                      << hex_text(exchange.reply);
      continue;
    }
    const auto reencoded = reencoded_reply(exchange.request_frame, reply.value());
    if (!reencoded) {
      record("replies", Outcome::not_implemented);
      continue;
    }
    const bool same = reencoded->ok() && reencoded->value() == reply.value().data;
    record("replies", same ? Outcome::passed : Outcome::failed);
    EXPECT_TRUE(same) << register_name(exchange.request_frame.reg) << " (step " << exchange.step << ") reply "
                      << hex_text(exchange.reply) << ": "
                      << (reencoded->ok() ? "encodes back as " + hex_text(reencoded->value())
                                          : reencoded->error().message);
  }
}

TEST(XarmCodec, TheDriverReadsTheMotionFeedbackTheSdkGot) {
  for (const Bytes& recorded : transcript().feedback) {
    FrameSplitter splitter;
    splitter.append(recorded);
    const auto frame = splitter.next();
    ASSERT_TRUE(frame && frame.value()) << hex_text(recorded);
    const auto feedback = parse_motion_feedback(*frame.value());
    const bool same =
        feedback && encode_frame(motion_feedback_frame(feedback.value(), frame.value()->protocol)) == recorded;
    record("feedback", same ? Outcome::passed : Outcome::failed);
    EXPECT_TRUE(same) << "motion feedback " << hex_text(recorded) << ": "
                      << (feedback ? "does not encode back the same" : feedback.error().message);
  }
}

TEST(XarmCodec, TheDriverParsesTheRichReport) {
  for (const ReportConnection& connection : transcript().reports) {
    for (const Bytes& packet : connection.packets) {
      const auto report = parse_report(packet, connection.kind);
      const bool parsed = report && report.value().has_rich && report.value().rich.axes == 6 &&
                          report.value().rich.firmware == transcript().firmware;
      const bool same = parsed && encode_report(report.value(), connection.kind) == packet;
      record("reports", same ? Outcome::passed : Outcome::failed);
      EXPECT_TRUE(same) << "rich packet " << hex_text(packet) << ": "
                        << (report ? "does not encode back the same" : report.error().message);
    }
  }
}

}  // namespace
}  // namespace robotd::conformance::xarm
