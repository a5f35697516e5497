// The session uuid is a capability known only to its holder (docs/security.md): what anyone
// else on the domain sees of a session, on /session_status and in refusals, never commands or
// releases it.
#include <chrono>
#include <set>
#include <sstream>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "robotd_fixture.hpp"

namespace robotd::testing {
namespace {

using namespace std::chrono_literals;

class SessionCapabilityTest : public RobotdTest {
 protected:
  Session acquire(const std::vector<std::int32_t>& motors) {
    SessionRequest request;
    request.device = "arm";
    request.motor_ids = motors;
    request.on_timeout = Behavior::kKeep;
    request.timeout = 10s;
    auto session = client().request_control(request);
    EXPECT_TRUE(session) << session.error().message;
    return std::move(session.value());
  }
};

// Every text of a SessionStatus, and every word of a text (a refusal names the holder inside
// a sentence).
void collect(const std::string& text, std::set<std::string>& seen) {
  seen.insert(text);
  std::istringstream words(text);
  for (std::string word; words >> word;) {
    seen.insert(word);
    const auto first = word.find_first_not_of("'(\"");
    const auto last = word.find_last_not_of("'),;:.\"");
    if (first != std::string::npos && last != std::string::npos && last >= first) {
      seen.insert(word.substr(first, last - first + 1));
    }
  }
}

void collect(const SessionStatus& status, std::set<std::string>& seen) {
  for (const auto& text : {status.state, status.policy_name, status.policy_file_name}) collect(text, seen);
  for (const auto& text : status.active_uuids) collect(text, seen);
  for (const auto& text : status.node_names) collect(text, seen);
  for (const auto& session : status.sessions) {
    for (const auto& text : {session.uuid, session.node_name, session.device}) collect(text, seen);
  }
}

TEST_F(SessionCapabilityTest, NothingAnotherParticipantSeesCommandsOrReleasesTheSession) {
  start_robotd();
  Session held = acquire({0, 1, 2});
  ASSERT_EQ(held.session_id().size(), 8U);

  // A second participant reads everything robotd shows of the session.
  Client observer = make_client("observer");
  std::set<std::string> seen;
  auto status = observer.session_status(3s);
  ASSERT_TRUE(status) << status.error().message;
  ASSERT_EQ(status.value().sessions.size(), 1U);
  EXPECT_EQ(status.value().active_uuids, std::vector<std::string>{held.session_id()});
  EXPECT_EQ(status.value().sessions[0].uuid, held.session_id());
  collect(status.value(), seen);

  SessionRequest overlapping;
  overlapping.device = "arm";
  overlapping.motor_ids = {1};
  auto refused = observer.request_control(overlapping);
  ASSERT_FALSE(refused);
  const std::string& refusal = refused.error().message;
  EXPECT_NE(refusal.find("node 'test_client'"), std::string::npos) << refusal;
  EXPECT_NE(refusal.find("session " + held.session_id()), std::string::npos) << refusal;
  collect(refusal, seen);

  auto zeroing = observer.reset_zero("arm", {});
  ASSERT_FALSE(zeroing);
  EXPECT_NE(zeroing.error().message.find("session " + held.session_id()), std::string::npos) << zeroing.error().message;
  collect(zeroing.error().message, seen);

  for (const auto& text : seen) {
    EXPECT_EQ(text.find(held.uuid()), std::string::npos) << "the holder's uuid is visible to others: " << text;
  }

  // Commands in the session's name with every string the observer saw: each rejected, as
  // naming no session (or, longer than a uuid can be, as malformed), none accepted, the arm
  // never commanded.
  const CommandCounters before = device_status().commands;
  std::uint64_t uuid_sized = 0;
  for (const auto& text : seen) {
    ControlCommand command;
    command.uuid = text;
    command.device = "arm";
    command.motor_ids = {0};
    command.positions = {0.3F};
    ASSERT_TRUE(observer.publish(command));
    if (text.size() <= 36) ++uuid_sized;
  }
  CommandCounters after = device_status().commands;
  for (int i = 0; i < 100 && after.received < before.received + seen.size(); ++i) after = device_status().commands;
  EXPECT_EQ(after.received, before.received + seen.size());
  EXPECT_EQ(after.rejected_unknown_session, before.rejected_unknown_session + uuid_sized);
  EXPECT_EQ(after.rejected_malformed, before.rejected_malformed + seen.size() - uuid_sized);
  EXPECT_EQ(after.accepted, before.accepted);
  for (const auto& joint : sim_joints()) EXPECT_EQ(joint["command"], "none") << joint.dump();

  // Releases with every string are refused; the session lives on.
  for (const auto& text : seen) {
    auto released = observer.release_control(text, Behavior::kZeroTorque);
    ASSERT_FALSE(released) << "released with '" << text << "'";
    EXPECT_EQ(released.error().code, ErrorCode::kRefused) << released.error().message;
  }
  auto release_by_id = observer.release_control(held.session_id(), Behavior::kKeep);
  ASSERT_FALSE(release_by_id);
  EXPECT_NE(release_by_id.error().message.find("is the public id of a session of node 'test_client'"),
            std::string::npos)
      << release_by_id.error().message;
  auto still = observer.session_status(3s);
  ASSERT_TRUE(still);
  ASSERT_EQ(still.value().sessions.size(), 1U);
  EXPECT_EQ(still.value().sessions[0].uuid, held.session_id());

  // The holder's uuid still commands and releases.
  ASSERT_TRUE(held.send_positions({0.1F, 0.1F, 0.1F}));
  EXPECT_TRUE(wait_for_joints([](const JointState& s) { return std::abs(s.position[0] - 0.1) < 0.01; }, 5s));
  EXPECT_TRUE(held.release(Behavior::kKeep));
  EXPECT_EQ(robotd_->log().find(held.uuid()), std::string::npos) << "robotd logged the uuid";
  EXPECT_NE(robotd_->log().find("session " + held.session_id()), std::string::npos) << robotd_->log();
}

TEST_F(SessionCapabilityTest, PublicIdsAreDistinctAndUnrelatedToTheUuids) {
  start_robotd();
  std::vector<Session> sessions;
  sessions.reserve(6);
  for (std::int32_t motor = 0; motor < 6; ++motor) sessions.push_back(acquire({motor}));
  std::set<std::string> ids;
  for (const auto& session : sessions) {
    EXPECT_EQ(session.session_id().find_first_not_of("0123456789abcdef"), std::string::npos) << session.session_id();
    EXPECT_EQ(session.uuid().find(session.session_id()), std::string::npos);
    ids.insert(session.session_id());
  }
  EXPECT_EQ(ids.size(), sessions.size());
  auto status = client().session_status(3s);
  ASSERT_TRUE(status);
  EXPECT_EQ(std::set<std::string>(status.value().active_uuids.begin(), status.value().active_uuids.end()), ids);
}

}  // namespace
}  // namespace robotd::testing
