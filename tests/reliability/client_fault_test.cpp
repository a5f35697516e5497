// Client faults against a real robotd: a client frozen mid-stream (SIGSTOP) and woken again, a
// command flood from eight intruders at 10 kHz each beside the session's owner, a client that
// takes motors and never commands nor releases them, and malformed service requests. Each prints
// what it measured ("[ measured ]", docs/reliability.md).
#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "log_times.hpp"
#include "robotd_fixture.hpp"

namespace robotd::testing {
namespace {

using namespace std::chrono_literals;

// robotd's uuids are random version-4 uuids: this one is never given out.
constexpr const char* kNeverGivenOut = "00000000-0000-4000-8000-000000000000";

/// A request for the test arm, changed by `change`.
template <class Change>
SessionRequest arm_request(Change change) {
  SessionRequest request;
  request.device = "arm";
  change(request);
  return request;
}
SessionRequest arm_request() {
  return arm_request([](SessionRequest&) {});
}

class ClientFaultTest : public RobotdTest {
 protected:
  void SetUp() override { start_robotd(); }

  /// robotd_command_streamer on this test's domain with `args`.
  std::unique_ptr<ChildProcess> streamer(std::vector<std::string> args) {
    args.insert(args.begin(), {"--domain", std::to_string(domain_.id())});
    return std::make_unique<ChildProcess>(COMMAND_STREAMER, args);
  }
  /// The count a streamer printed ("sent <n>") when its --seconds ran out.
  static std::uint64_t sent_by(ChildProcess& child) {
    for (int line = 0; line < 4; ++line) {
      const auto text = child.read_line(15s);
      if (!text) break;
      if (text->rfind("sent ", 0) == 0) return std::stoull(text->substr(5));
    }
    ADD_FAILURE() << "the streamer never said how many it sent";
    return 0;
  }
  bool sessions_empty() {
    const auto status = client().session_status(1s);
    return status && status.value().sessions.empty();
  }
};

// SIGSTOP freezes a client without closing anything: robotd sees only silence, ends the session
// at its timeout, and once the client wakes, its commands under the dead uuid are rejected.
TEST_F(ClientFaultTest, AFrozenClientsSessionFallsBackAndItsCommandsAreRejectedWhenItWakes) {
  constexpr int kTimeoutMs = 200;
  auto owner = streamer({"--timeout-ms", std::to_string(kTimeoutMs), "--on-timeout", "DAMPING"});
  const auto uuid_line = owner->read_line(10s);
  ASSERT_TRUE(uuid_line && uuid_line->rfind("uuid ", 0) == 0) << uuid_line.value_or("(nothing)");
  std::this_thread::sleep_for(300ms);  // streaming at 1 kHz

  const WallTime stopped = std::chrono::system_clock::now();
  ASSERT_EQ(::kill(owner->pid(), SIGSTOP), 0);
  std::optional<WallTime> timed_out;
  for (int i = 0; i < 300 && !timed_out; ++i) {
    timed_out = logged_at(robotd_->log(), "timed out after", stopped);
    if (!timed_out) std::this_thread::sleep_for(10ms);
  }
  ASSERT_TRUE(timed_out) << robotd_->log();
  const double fallback_ms = milliseconds_between(stopped, *timed_out);
  EXPECT_GE(fallback_ms, kTimeoutMs - 5);
  EXPECT_LT(fallback_ms, kTimeoutMs + 150);
  EXPECT_TRUE(sessions_empty());
  for (const auto& joint : sim_joints()) {
    EXPECT_EQ(joint["command"], "impedance") << joint.dump();
    EXPECT_EQ(joint["kp"], 0.0) << "DAMPING leaves no stiffness: " << joint.dump();
  }

  const CommandCounters before = device_status().commands;
  ASSERT_EQ(::kill(owner->pid(), SIGCONT), 0);
  std::this_thread::sleep_for(500ms);
  const CommandCounters after = device_status().commands;
  const auto rejected = after.rejected_unknown_session - before.rejected_unknown_session;
  EXPECT_GT(rejected, 200U) << "the woken client's commands should be rejected and counted";
  EXPECT_EQ(after.accepted, before.accepted);
  for (const auto& joint : sim_joints()) EXPECT_EQ(joint["kp"], 0.0) << "woke and moved: " << joint.dump();
  std::cout << "[ measured ] SIGSTOP: session ended " << std::lround(fallback_ms)
            << " ms after the client froze (timeout_ms " << kTimeoutMs << "); after SIGCONT " << rejected
            << " commands in 500 ms rejected as unknown session\n";
}

// Eight intruders each try 10 kHz of commands under a uuid robotd never gave out, all to 1.0 rad,
// while the owner streams at 1 kHz a target 0.3 rad below where the arm was: the owner keeps its
// session and the arm goes to the owner's target and nowhere else; every command that reached
// robotd is counted, each intruder's as an unknown session; the device stays RUNNING. A
// functional check: the share of the owner's commands that get through a flood, and its cost,
// are bench/flood.py's figures (docs/performance.md).
TEST_F(ClientFaultTest, AFloodOfForeignCommandsLeavesTheLoopAndTheOwnerAlone) {
  constexpr int kFloodSeconds = 3;
  constexpr double kOwnerOffsetRad = -0.3;
  constexpr double kToleranceRad = 0.02;
  const std::vector<double> start = joint_state().position;
  const DeviceStatus before = device_status();
  ASSERT_TRUE(client().device_call("arm", "loop_timing", R"({"reset": true})"));
  auto owner = streamer({"--timeout-ms", "1000", "--seconds", std::to_string(kFloodSeconds + 2), "--offset",
                         std::to_string(kOwnerOffsetRad)});
  const auto uuid_line = owner->read_line(10s);
  ASSERT_TRUE(uuid_line && uuid_line->rfind("uuid ", 0) == 0) << uuid_line.value_or("(nothing)");
  const std::string owner_session = uuid_line->substr(uuid_line->find(" session ") + 9);
  constexpr int kIntruders = 8;
  std::vector<std::unique_ptr<ChildProcess>> intruders;
  intruders.reserve(kIntruders);
  for (int i = 0; i < kIntruders; ++i) {
    intruders.push_back(streamer({"--uuid", kNeverGivenOut, "--rate", "10000", "--seconds",
                                  std::to_string(kFloodSeconds), "--position", "1.0"}));
  }

  // Through the flood, no joint passes the owner's target towards the intruders' 1.0 rad.
  double beyond_owner_rad = 0;
  for (const auto flood_end = std::chrono::steady_clock::now() + std::chrono::seconds(kFloodSeconds);
       std::chrono::steady_clock::now() < flood_end;) {
    const JointState state = joint_state();
    for (std::size_t j = 0; j < start.size(); ++j) {
      beyond_owner_rad = std::max(beyond_owner_rad, state.position[j] - std::max(start[j], start[j] + kOwnerOffsetRad));
    }
  }
  const auto sessions = client().session_status(1s);
  ASSERT_TRUE(sessions) << sessions.error().message;
  EXPECT_EQ(sessions.value().active_uuids, std::vector<std::string>{owner_session}) << "the owner lost its session";
  const JointState during = joint_state();
  for (std::size_t j = 0; j < start.size(); ++j) {
    EXPECT_NEAR(during.position[j], start[j] + kOwnerOffsetRad, kToleranceRad) << "joint " << j << " (owner's target)";
  }
  EXPECT_LT(beyond_owner_rad, kToleranceRad) << "a forged command moved the arm";

  std::uint64_t forged = 0;
  for (auto& intruder : intruders) forged += sent_by(*intruder);
  const std::uint64_t owned = sent_by(*owner);  // the owner has stopped: the counters stand still
  const DeviceStatus after = device_status();
  const auto received = after.commands.received - before.commands.received;
  const auto accepted = after.commands.accepted - before.commands.accepted;
  const auto rejected = after.commands.rejected_unknown_session - before.commands.rejected_unknown_session;
  std::cout << "[ measured ] flood: 8 intruders sent " << forged << " commands in " << kFloodSeconds << " s ("
            << forged / kFloodSeconds << "/s), " << rejected << " reached robotd and were rejected as unknown session; "
            << "owner sent " << owned << ", " << accepted << " accepted; arm loop period p99 "
            << after.loop.period_p99_us << " µs, max " << after.loop.period_max_us << " µs, overruns "
            << after.loop.overruns - before.loop.overruns << "\n";
  EXPECT_GT(rejected, 0U) << "no forged command reached robotd: the flood was not a flood";
  EXPECT_LE(rejected, forged);
  EXPECT_GT(accepted, 0U);
  EXPECT_LE(accepted, owned);
  EXPECT_EQ(received, accepted + rejected) << "a command was received but neither accepted nor counted as rejected";
  EXPECT_EQ(after.state, DeviceState::kRunning);
}

// A client that takes motors and then neither commands nor releases them: the session ends at
// its timeout like any silent one, and the motors are free for the next client.
TEST_F(ClientFaultTest, MotorsTakenAndNeverUsedAreFreedAtTheTimeout) {
  Client hoarder = make_client("hoarder");
  SessionRequest request;
  request.device = "arm";
  request.timeout = 300ms;
  const WallTime taken = std::chrono::system_clock::now();
  auto held = hoarder.request_control(request);
  ASSERT_TRUE(held) << held.error().message;
  const auto refused = client().request_control(arm_request());
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("hoarder"), std::string::npos) << refused.error().message;

  std::optional<WallTime> freed;
  for (int i = 0; i < 300 && !freed; ++i) {
    freed = logged_at(robotd_->log(), "timed out after", taken);
    if (!freed) std::this_thread::sleep_for(10ms);
  }
  ASSERT_TRUE(freed) << robotd_->log();
  const double held_ms = milliseconds_between(taken, *freed);
  EXPECT_LT(held_ms, 300 + 200);
  auto next = client().request_control(arm_request());
  ASSERT_TRUE(next) << next.error().message;
  std::cout << "[ measured ] an unused session (timeout_ms 300) freed its motors " << std::lround(held_ms)
            << " ms after it was granted\n";
}

// Requests that make no sense get an answer saying what is wrong; robotd keeps serving.
TEST_F(ClientFaultTest, MalformedServiceRequestsAreAnsweredWithTheirMistake) {
  struct Bad {
    SessionRequest request;
    const char* expected;
  };
  const std::vector<Bad> requests{
      {arm_request([](SessionRequest& r) { r.device = "no_such_device"; }), "no_such_device"},
      {arm_request([](SessionRequest& r) {
         r.motor_ids = {0, 99};
       }),
       "99"},
      {arm_request([](SessionRequest& r) {
         r.motor_ids = {1, 1};
       }),
       "1"},
      {arm_request([](SessionRequest& r) { r.motor_ids = {-3}; }), "-3"},
      {arm_request([](SessionRequest& r) { r.mode = static_cast<ControlMode>(42); }), "42"},
      {arm_request([](SessionRequest& r) { r.on_timeout = static_cast<Behavior>(17); }), "17"},
      {arm_request([](SessionRequest& r) { r.timeout = -5ms; }), "timeout"},
      {arm_request([](SessionRequest& r) {
         r.motor_ids = {0, 1};
         r.default_kp = {1.0F};
       }),
       "default_kp"},
  };
  for (const Bad& bad : requests) {
    const auto answer = client().request_control(bad.request);
    ASSERT_FALSE(answer) << "accepted: " << bad.expected;
    EXPECT_NE(answer.error().message.find(bad.expected), std::string::npos)
        << "the answer should name \"" << bad.expected << "\": " << answer.error().message;
  }
  const auto release = client().release_control("not-a-uuid", Behavior::kKeep);
  EXPECT_TRUE(!release || !release.value().success) << "released a session that does not exist";
  const auto call = client().device_call("arm", "loop_timing", "{not json");
  ASSERT_FALSE(call);
  EXPECT_NE(call.error().message.find("JSON"), std::string::npos) << call.error().message;
  const auto unknown_op = client().device_call("arm", "format_disk");
  ASSERT_FALSE(unknown_op);
  EXPECT_NE(unknown_op.error().message.find("format_disk"), std::string::npos) << unknown_op.error().message;

  auto good = client().request_control(arm_request());
  ASSERT_TRUE(good) << "robotd stopped serving: " << good.error().message;
  EXPECT_EQ(device_status().state, DeviceState::kRunning);
}

}  // namespace
}  // namespace robotd::testing
