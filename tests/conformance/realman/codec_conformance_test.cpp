// robotd's RealMan codec checked against the vendor SDK's recorded sessions, with no simulator:
//  - requests: for each request the SDK sent of a command robotd also sends, the codec given the
//    same arguments builds the same JSON (compared as JSON values: key order is free);
//  - reply shapes: each recorded reply to such a command is recognised by reply_shape() and, for a
//    setter, judged a success as the SDK judged it (its call returned 0);
//  - parsed: the codec reads the messages the driver reads (software info, arm state, events,
//    the gripper's state, the UDP push) and gets the values they carry.
// Differences robotd makes on purpose are listed in differences.json with the reason and robotd's
// own value, which the test checks.
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "codec/realman_codec.hpp"
#include "conformance_report.hpp"
#include "realman_transcript.hpp"
#include "vector_file.hpp"

namespace robotd::realman::conformance {
namespace {

using nlohmann::json;
using robotd::conformance::Outcome;
using robotd::conformance::record;

std::vector<double> radians(const json& millidegrees) {
  std::vector<double> out;
  for (const json& value : millidegrees) out.push_back(rad_from_millidegrees(value.get<std::int64_t>()));
  return out;
}

EulerPose pose_of(const json& wire) {
  EulerPose pose;
  for (std::size_t i = 0; i < 3; ++i) {
    pose.position_m[i] = m_from_micrometres(wire.at(i).get<std::int64_t>());
    pose.euler_rad[i] = rad_from_milliradians(wire.at(i + 3).get<std::int64_t>());
  }
  return pose;
}

bool block_of(const json& request) { return request.value("block", false); }

/// What the codec builds for the command and arguments of `sent`; nullopt for a command robotd
/// does not send.
std::optional<json> rebuilt(const json& sent) {
  const std::string command = message_key(sent);
  const auto move = [&sent] {
    return PlannedMove{.speed_percent = sent.at("v"),
                       .blend_percent = sent.at("r"),
                       .trajectory_connect = sent.value("trajectory_connect", 0) == 1};
  };
  if (command == "movej") return movej_request(radians(sent.at("joint")), move());
  if (command == "movel") return movel_request(pose_of(sent.at("pose")), move());
  if (command == "movej_p") return movej_p_request(pose_of(sent.at("pose")), move());
  if (command == "movej_canfd") {
    PassThrough pass_through;
    pass_through.follow = sent.at("follow");
    if (sent.contains("trajectory_mode")) pass_through.trajectory_mode = sent.at("trajectory_mode");
    if (sent.contains("radio")) pass_through.radio = sent.at("radio");
    return movej_canfd_request(radians(sent.at("joint")), pass_through);
  }
  if (command == "set_gripper_route") return set_gripper_route_request(sent.at("min"), sent.at("max"));
  if (command == "set_gripper_release") return set_gripper_release_request(sent.at("speed"), block_of(sent));
  if (command == "set_gripper_pick") {
    return set_gripper_pick_request(sent.at("speed"), sent.at("force"), block_of(sent));
  }
  if (command == "set_gripper_pick_on") {
    return set_gripper_pick_on_request(sent.at("speed"), sent.at("force"), block_of(sent));
  }
  if (command == "set_gripper_position") return set_gripper_position_request(sent.at("position"), block_of(sent));
  if (command == "set_hand_posture") return set_hand_posture_request(sent.at("posture_num"), block_of(sent));
  if (command == "set_hand_seq") return set_hand_seq_request(sent.at("seq_num"), block_of(sent));
  if (command == "set_hand_angle") return set_hand_angle_request(sent.at("hand_angle"), block_of(sent));
  if (command == "set_hand_speed") return set_hand_speed_request(sent.at("hand_speed"));
  if (command == "set_hand_force") return set_hand_force_request(sent.at("hand_force"));
  if (command == "set_realtime_push") {
    const json custom = sent.value("custom", json::object());
    return set_realtime_push_request(RealtimePushConfig{.cycle = sent.at("cycle"),
                                                        .enable = sent.at("enable"),
                                                        .port = sent.at("port"),
                                                        .ip = sent.at("ip"),
                                                        .joint_speed = custom.value("joint_speed", false),
                                                        .arm_current_status = custom.value("arm_current_status", false),
                                                        .hand = custom.value("hand", false)});
  }
  // Queries, stops and clears carry only their name.
  if (sent.size() == 1 && reply_shape(command)) return plain_request(command);
  return std::nullopt;
}

/// differences.json: {"requests": {command: {"why", "robotd"}}} — robotd's request on purpose.
const json* difference_for(const json& differences, const std::string& command) {
  const json& requests = differences.at("requests");
  return requests.contains(command) ? &requests.at(command) : nullptr;
}

TEST(RealmanCodecConformance, TheCodecBuildsTheRequestsTheSdkSent) {
  const json differences = robotd::conformance::load_json("differences.json");
  for (const Session& session : load_sessions()) {
    for (const Connection& connection : session.connections) {
      for (const Exchange& exchange : connection.exchanges) {
        const json sent = json::parse(exchange.request);
        const std::optional<json> ours = rebuilt(sent);
        if (!ours) continue;  // robotd never sends this command
        const std::string command = message_key(sent);
        if (*ours == sent) {
          record("requests", Outcome::passed);
          continue;
        }
        const json* difference = difference_for(differences, command);
        // A listed difference pins robotd's own request for these arguments: the SDK's with the
        // fields it names replaced.
        json expected = sent;
        if (difference) {
          for (const auto& [field, value] : difference->at("robotd").items()) {
            if (value.is_null()) {
              expected.erase(field);
            } else {
              expected[field] = value;
            }
          }
        }
        const bool deliberate = difference && *ours == expected;
        record("requests", deliberate ? Outcome::deliberate_difference : Outcome::failed);
        EXPECT_TRUE(deliberate) << session.name << ": the SDK sent " << sent.dump() << "\n  robotd builds "
                                << ours->dump();
      }
    }
  }
}

TEST(RealmanCodecConformance, EveryReplyIsRecognisedAndJudgedAsTheSdkJudgedIt) {
  for (const Session& session : load_sessions()) {
    for (const Connection& connection : session.connections) {
      for (const Exchange& exchange : connection.exchanges) {
        const std::string command = message_key(json::parse(exchange.request));
        const auto shape = reply_shape(command);
        if (!shape || !shape->has_reply) continue;
        // The reply is the first line that is not a trajectory event.
        std::optional<Message> reply;
        for (const std::string& line : exchange.replies) {
          auto message = parse_message(line);
          ASSERT_TRUE(message) << line;
          if (message.value().kind == MessageKind::kReply) {
            reply = message.value();
            break;
          }
        }
        ASSERT_TRUE(reply) << session.name << ": no reply to " << exchange.request;
        bool ok = std::ranges::find(shape->keys, reply->key) != shape->keys.end();
        if (ok && !shape->result_field.empty()) ok = reply_success(*reply, *shape, command).ok();
        record("reply shapes", ok ? Outcome::passed : Outcome::failed);
        EXPECT_TRUE(ok) << session.name << ": " << exchange.request << " -> " << reply->body.dump();
      }
    }
  }
}

void check_parsed(const Session& session, const std::string& line) {
  const auto parsed = parse_message(line);
  ASSERT_TRUE(parsed) << line;
  const Message& message = parsed.value();
  const json& body = message.body;
  bool ok = true;
  if (message.kind == MessageKind::kTrajectoryEvent) {
    const auto event = parse_trajectory_event(message);
    ok = event && event.value().reached == body.at("trajectory_state").get<bool>() &&
         static_cast<int>(event.value().device) == body.at("device").get<int>() &&
         event.value().more_segments == (body.value("trajectory_connect", 0) == 1);
  } else if (message.key == "arm_software_info") {
    const auto info = parse_software_info(message);
    ok = info && info.value().product_version == body.at("Product_version").get<std::string>() &&
         find_model(info.value().product_version).has_value();
  } else if (message.key == "current_arm_state") {
    const auto state = parse_current_arm_state(message);
    const std::vector<double> joints = radians(body.at("arm_state").at("joint"));
    ok = state && state.value().dof == joints.size() &&
         std::equal(joints.begin(), joints.end(), state.value().joints_rad.begin());
  } else if (message.key == "get_gripper_state") {
    const auto gripper = parse_gripper_state(message);
    ok = gripper && gripper.value().opening == body.at("actpos").get<int>() &&
         gripper.value().mode == body.at("mode").get<int>();
  } else {
    return;  // the driver does not read it
  }
  record("parsed", ok ? Outcome::passed : Outcome::failed);
  EXPECT_TRUE(ok) << session.name << ": " << line;
}

TEST(RealmanCodecConformance, TheCodecReadsWhatTheDriverReads) {
  for (const Session& session : load_sessions()) {
    for (const Connection& connection : session.connections) {
      for (const Exchange& exchange : connection.exchanges) {
        for (const std::string& line : exchange.replies) check_parsed(session, line);
      }
    }
    for (const std::string& datagram : session.pushes) {
      const auto push = parse_realtime_push(datagram);
      const json body = json::parse(datagram);
      const std::vector<double> joints = radians(body.at("joint_status").at("joint_position"));
      const bool ok = push && push.value().dof == joints.size() &&
                      std::equal(joints.begin(), joints.end(), push.value().position_rad.begin());
      record("parsed", ok ? Outcome::passed : Outcome::failed);
      EXPECT_TRUE(ok) << session.name << ": " << datagram;
    }
  }
}

}  // namespace
}  // namespace robotd::realman::conformance
