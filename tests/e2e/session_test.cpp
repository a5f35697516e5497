// End to end through a real robotd process: sessions (issue tests 1, 2, 3, 6).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include <gtest/gtest.h>

#include "robotd_fixture.hpp"

namespace robotd::testing {
namespace {

using namespace std::chrono_literals;

SessionRequest arm_request(std::vector<std::int32_t> motors = {}, Behavior on_timeout = Behavior::kDamping,
                           std::chrono::milliseconds timeout = 1000ms) {
  SessionRequest request;
  request.device = "arm";
  request.motor_ids = std::move(motors);
  request.on_timeout = on_timeout;
  request.timeout = timeout;
  return request;
}

class SessionTest : public RobotdTest {
 protected:
  void expect_fallback_after_kill(Behavior behavior, const std::string& behavior_name);
};

// Issue test 1. Also reports the loop timing DeviceStatus shows while the arm moves.
TEST_F(SessionTest, AcquireMoveReadTargetBackRelease) {
  start_robotd();
  auto session = client().request_control(arm_request());
  ASSERT_TRUE(session) << session.error().message;
  EXPECT_EQ(session.value().motor_ids().size(), 6U);

  const std::vector<float> target{0.5F, -0.3F, 0.8F, 0.2F, -0.6F, 1.0F};
  const auto t0 = std::chrono::steady_clock::now();
  bool arrived = false;
  while (!arrived && std::chrono::steady_clock::now() - t0 < 5s) {
    ASSERT_TRUE(session.value().send_positions(target));
    auto state = client().next_joint_state("arm", 1s);
    arrived = state && max_error(state.value(), target) < 0.01;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_TRUE(arrived) << "arm did not reach the target within 5 s";
  // The farthest joint moves 1.0 rad at <= 2 rad/s with 10 rad/s² ramps: at least ~0.7 s.
  EXPECT_GT(seconds, 0.6) << "the move was faster than the velocity limit allows";

  const DeviceStatus status = device_status();
  EXPECT_EQ(status.state, DeviceState::kRunning);
  EXPECT_GT(status.commands.accepted, 0U);
  EXPECT_EQ(status.commands.rejected_total(), 0U);
  EXPECT_GT(status.loop.window_ticks, 500U);
  std::printf(
      "[ measured ] arrived in %.2f s; loop wake latency p50 %.1f µs, p99 %.1f µs, max %.1f µs; "
      "execution p50 %.1f µs, p99 %.1f µs; overruns %llu over %llu ticks; realtime %s\n",
      seconds, status.loop.wake_latency_p50_us, status.loop.wake_latency_p99_us, status.loop.wake_latency_max_us,
      status.loop.execution_p50_us, status.loop.execution_p99_us, static_cast<unsigned long long>(status.loop.overruns),
      static_cast<unsigned long long>(status.loop.ticks), status.loop.realtime ? "yes" : "no");

  auto released = session.value().release(Behavior::kKeep);
  ASSERT_TRUE(released) << released.error().message;
  EXPECT_FALSE(session.value().active());
  auto sessions = client().session_status(2s);
  ASSERT_TRUE(sessions);
  // The release is applied by the loop within a tick; status follows at once.
  for (int i = 0; i < 50 && !sessions.value().sessions.empty(); ++i) {
    std::this_thread::sleep_for(20ms);
    sessions = client().session_status(2s);
  }
  EXPECT_TRUE(sessions.value().sessions.empty());
  // KEEP: the arm stays at the target after release.
  EXPECT_LT(max_error(joint_state(), target), 0.01);
}

// Issue test 2.
TEST_F(SessionTest, OverlapRefusedNamingHolderDisjointGranted) {
  start_robotd();
  Client first = make_client("teleop");
  Client second = make_client("planner");
  auto held = first.request_control(arm_request({0, 1, 2}, Behavior::kDamping, 5000ms));
  ASSERT_TRUE(held) << held.error().message;

  auto overlap = second.request_control(arm_request({2, 3}));
  ASSERT_FALSE(overlap);
  EXPECT_EQ(overlap.error().code, ErrorCode::kRefused);
  EXPECT_NE(overlap.error().message.find("held by node 'teleop'"), std::string::npos) << overlap.error().message;
  EXPECT_NE(overlap.error().message.find("session " + held.value().session_id()), std::string::npos)
      << overlap.error().message;
  EXPECT_EQ(overlap.error().message.find(held.value().uuid()), std::string::npos) << overlap.error().message;
  EXPECT_NE(overlap.error().message.find("motor(s) 2"), std::string::npos) << overlap.error().message;

  auto disjoint = second.request_control(arm_request({3, 4, 5}));
  ASSERT_TRUE(disjoint) << disjoint.error().message;
  auto status = client().session_status(2s);
  ASSERT_TRUE(status);
  EXPECT_EQ(status.value().sessions.size(), 2U);
  EXPECT_EQ(status.value().state, "active");

  auto available = client().available_motors("arm");
  ASSERT_TRUE(available);
  EXPECT_TRUE(available.value().motor_ids.empty());
}

// Issue test 3: a client killed mid-stream while holding the arm against a 2 N·m load on joint2;
// its session ends after timeout_ms and the motors are in the requested fallback. Prints how long
// it took.
void SessionTest::expect_fallback_after_kill(Behavior behavior, const std::string& behavior_name) {
  constexpr int kTimeoutMs = 300;
  ChildProcess streamer(COMMAND_STREAMER, {"--domain", std::to_string(domain_.id()), "--timeout-ms",
                                           std::to_string(kTimeoutMs), "--on-timeout", behavior_name});
  const auto uuid_line = streamer.read_line(10s);
  ASSERT_TRUE(uuid_line.has_value());
  ASSERT_EQ(uuid_line->rfind("uuid ", 0), 0U) << *uuid_line;
  const std::string session = uuid_line->substr(uuid_line->find(" session ") + 9);
  std::this_thread::sleep_for(300ms);  // streaming at 1 kHz
  auto streaming = client().session_status(1s);
  ASSERT_TRUE(streaming);
  ASSERT_EQ(streaming.value().sessions.size(), 1U)
      << "the streamer's commands did not keep session " << session << " alive for its " << kTimeoutMs << " ms timeout";
  // The load comes once the streamer holds the arm: loaded from the start, an unowned joint2 would
  // fall to its hard stop before a slow (sanitized) streamer took it, and a joint resting on its
  // stop shows no fallback at all.
  call_device("arm", "set_external_torque", {{"joint", 1}, {"torque_nm", -2.0}});
  std::this_thread::sleep_for(100ms);

  const auto killed_at = std::chrono::steady_clock::now();
  streamer.kill_hard();
  bool ended = false;
  std::chrono::steady_clock::time_point ended_at;
  while (!ended && std::chrono::steady_clock::now() - killed_at < 3s) {
    auto status = client().session_status(1s);
    ended = status && status.value().sessions.empty();
    ended_at = std::chrono::steady_clock::now();
    if (!ended) std::this_thread::sleep_for(1ms);
  }
  ASSERT_TRUE(ended) << "session " << session << " did not end after its client died";
  const double elapsed_ms = std::chrono::duration<double, std::milli>(ended_at - killed_at).count();
  std::printf("[ measured ] %s fallback: session ended %.1f ms after SIGKILL (timeout_ms %d)\n", behavior_name.c_str(),
              elapsed_ms, kTimeoutMs);
  EXPECT_GE(elapsed_ms, kTimeoutMs - 5);
  EXPECT_LT(elapsed_ms, kTimeoutMs + 250);

  // The loop applies the fallback on the tick after the session ends.
  const auto fallback_applied = [](const nlohmann::json& state) {
    return std::all_of(state["joints"].begin(), state["joints"].end(),
                       [](const nlohmann::json& joint) { return joint["command"] == "impedance"; });
  };
  nlohmann::json sim = sim_state();
  for (const auto deadline = std::chrono::steady_clock::now() + 2s;
       !fallback_applied(sim) && std::chrono::steady_clock::now() < deadline; sim = sim_state()) {
    std::this_thread::sleep_for(1ms);
  }
  for (const auto& joint : sim["joints"]) {
    EXPECT_EQ(joint["command"], "impedance") << joint.dump();
    EXPECT_EQ(joint["kp"], 0.0) << joint.dump();
    if (behavior == Behavior::kDamping) {
      EXPECT_GT(joint["kd"].get<double>(), 0.0) << joint.dump();
    } else {
      EXPECT_EQ(joint["kd"], 0.0) << joint.dump();
    }
  }
}

TEST_F(SessionTest, KilledClientDampingFallbackDampsTheLoadedJoint) {
  start_robotd();
  expect_fallback_after_kill(Behavior::kDamping, "DAMPING");
  // Damped, joint2 sinks under its 2 N·m load at about 2 / (kd 10 + friction 0.3) ≈ 0.19 rad/s.
  std::this_thread::sleep_for(200ms);
  const JointState state = joint_state();
  EXPECT_LT(state.velocity[1], -0.1) << "joint2 at " << state.position[1] << " rad";
  EXPECT_GT(state.velocity[1], -0.35) << "joint2 at " << state.position[1] << " rad";
}

TEST_F(SessionTest, KilledClientZeroTorqueFallbackLetsTheLoadedJointFall) {
  start_robotd();
  expect_fallback_after_kill(Behavior::kZeroTorque, "ZERO_TORQUE");
  // Let go, joint2 falls freely (only friction 0.3 resists) until its hard stop at -2.5 rad.
  EXPECT_TRUE(wait_for_joints([](const JointState& s) { return s.position[1] < -2.4; }, 5s));
}

TEST_F(SessionTest, KeepFallbackHoldsPosition) {
  start_robotd(sim_arm_config(domain_.id(), sim_arm_params(-2.0)));
  // The timeout leaves a sanitized build time to send the first command.
  auto session = client().request_control(arm_request({}, Behavior::kKeep, 500ms));
  ASSERT_TRUE(session) << session.error().message;
  const std::vector<float> target{0.2F, 0.4F, 0, 0, 0, 0};
  ASSERT_TRUE(session.value().send_positions(target));
  ASSERT_TRUE(wait_for_joints(
      [&](const JointState& s) {
        (void)session.value().send_positions(target);
        return max_error(s, target) < 0.02;
      },
      5s));
  // The commands stop: the session times out 500 ms after the last one.
  bool ended = false;
  const auto deadline = std::chrono::steady_clock::now() + 3s;
  while (!ended && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(50ms);
    auto status = client().session_status(1s);
    ended = status && status.value().sessions.empty();
  }
  ASSERT_TRUE(ended) << "the session did not time out";
  std::this_thread::sleep_for(200ms);
  EXPECT_LT(max_error(joint_state(), target), 0.02) << "KEEP must hold the last target";
}

// The PI Plus shows the policy in command in /session_status; a robotd session names its own.
TEST_F(SessionTest, SessionsNameTheirPolicyInSessionStatus) {
  start_robotd();
  SessionRequest legs = arm_request({0, 1, 2}, Behavior::kKeep, 10'000ms);
  legs.policy_name = "walk";
  legs.policy_file_name = "/opt/policies/walk_v3.onnx";
  auto walking = client().request_control(legs);
  ASSERT_TRUE(walking) << walking.error().message;
  auto unnamed = client().request_control(arm_request({3}, Behavior::kKeep, 10'000ms));
  ASSERT_TRUE(unnamed) << unnamed.error().message;

  auto status = client().session_status(2s);
  ASSERT_TRUE(status);
  EXPECT_EQ(status.value().policy_name, "walk");
  EXPECT_EQ(status.value().policy_file_name, "/opt/policies/walk_v3.onnx");
  ASSERT_EQ(status.value().sessions.size(), 2U);
  for (const auto& session : status.value().sessions) {
    const bool is_walking = session.uuid == walking.value().session_id();
    EXPECT_EQ(session.policy_name, is_walking ? "walk" : "") << session.uuid;
    EXPECT_EQ(session.policy_file_name, is_walking ? "/opt/policies/walk_v3.onnx" : "") << session.uuid;
  }

  // The newest session that names a policy is the one /session_status names; when it ends,
  // the one before it is named again.
  SessionRequest arms = arm_request({4, 5}, Behavior::kKeep, 10'000ms);
  arms.policy_name = "wave";
  auto waving = client().request_control(arms);
  ASSERT_TRUE(waving) << waving.error().message;
  status = client().session_status(2s);
  ASSERT_TRUE(status);
  EXPECT_EQ(status.value().policy_name, "wave");
  EXPECT_EQ(status.value().policy_file_name, "");
  ASSERT_TRUE(waving.value().release(Behavior::kKeep));
  status = client().session_status(2s);
  ASSERT_TRUE(status);
  EXPECT_EQ(status.value().policy_name, "walk");

  // A name beyond its limit is refused like every other over-long field, and nothing is granted.
  SessionRequest oversized = arm_request({4}, Behavior::kKeep, 10'000ms);
  oversized.policy_file_name = std::string(1024, 'f');
  auto refused = client().request_control(oversized);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("policy_file_name is 1024 bytes long; the limit is 1023 bytes"),
            std::string::npos)
      << refused.error().message.substr(0, 300);
  status = client().session_status(2s);
  ASSERT_TRUE(status);
  EXPECT_EQ(status.value().sessions.size(), 2U);
  EXPECT_NE(robotd_->log().find("policy 'walk' from '/opt/policies/walk_v3.onnx'"), std::string::npos);
}

// Issue test 6.
TEST_F(SessionTest, ResetZeroRefusedWhileSessionActiveAndWorksWithout) {
  start_robotd();
  auto session = client().request_control(arm_request({0, 1}, Behavior::kKeep, 5000ms));
  ASSERT_TRUE(session) << session.error().message;
  ASSERT_TRUE(wait_for_joints(
      [&](const JointState& s) {
        (void)session.value().send_positions({0.3F, -0.2F});
        return std::fabs(s.position[0] - 0.3) < 0.01 && std::fabs(s.position[1] + 0.2) < 0.01;
      },
      5s));

  auto refused = client().reset_zero("arm", {});
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().code, ErrorCode::kRefused);
  EXPECT_NE(refused.error().message.find("session is active"), std::string::npos) << refused.error().message;
  EXPECT_NE(refused.error().message.find("session " + session.value().session_id()), std::string::npos)
      << refused.error().message;
  EXPECT_EQ(refused.error().message.find(session.value().uuid()), std::string::npos) << refused.error().message;

  ASSERT_TRUE(session.value().release(Behavior::kKeep));
  std::this_thread::sleep_for(50ms);
  auto zeroed = client().reset_zero("arm", {0, 1});
  ASSERT_TRUE(zeroed) << zeroed.error().message;
  const JointState after = joint_state();
  EXPECT_NEAR(after.position[0], 0.0, 0.1);
  EXPECT_NEAR(after.position[1], 0.0, 0.1);
}

TEST_F(SessionTest, CommandsFromAReleasedSessionAreRejected) {
  start_robotd();
  auto session = client().request_control(arm_request());
  ASSERT_TRUE(session) << session.error().message;
  const std::string uuid = session.value().uuid();
  ASSERT_TRUE(session.value().release(Behavior::kKeep));
  ControlCommand stale;
  stale.uuid = uuid;
  stale.motor_ids = {0};
  stale.positions = {0.5F};
  ASSERT_TRUE(client().publish(stale));
  DeviceStatus status = device_status();
  for (int i = 0; i < 40 && status.commands.rejected_unknown_session == 0; ++i) status = device_status();
  EXPECT_EQ(status.commands.rejected_unknown_session, 1U);
  EXPECT_EQ(status.commands.accepted, 0U);
  // Released with KEEP the joint holds where it was; it never heads for the stale 0.5 rad.
  std::this_thread::sleep_for(300ms);
  EXPECT_NEAR(joint_state().position[0], 0.0, 1e-3);
}

}  // namespace
}  // namespace robotd::testing
