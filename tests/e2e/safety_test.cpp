// End to end through a real robotd process: what must never reach a motor (issue tests 4, 5),
// device faults and recovery, the black box, ops that act on the joints.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <limits>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "robotd_fixture.hpp"
#include "session/session_ids.hpp"

namespace robotd::testing {
namespace {

using namespace std::chrono_literals;

class SafetyTest : public RobotdTest {
 protected:
  Session acquire(std::vector<std::int32_t> motors, std::chrono::milliseconds timeout = 10s) {
    SessionRequest request;
    request.device = "arm";
    request.motor_ids = std::move(motors);
    request.on_timeout = Behavior::kKeep;
    request.timeout = timeout;
    auto session = client().request_control(request);
    EXPECT_TRUE(session) << session.error().message;
    return std::move(session.value());
  }

  ControlCommand command_for(const Session& session) {
    ControlCommand command;
    command.uuid = session.uuid();
    command.device = "arm";
    command.motor_ids = {0, 1};
    command.positions = {0.4F, 0.4F};
    return command;
  }

  /// Publishes `command` and waits until DeviceStatus has counted it.
  CommandCounters send_and_count(const ControlCommand& command) {
    const std::uint64_t before = device_status().commands.received;
    EXPECT_TRUE(client().publish(command));
    for (int i = 0; i < 100; ++i) {
      const DeviceStatus status = device_status();
      if (status.commands.received > before) return status.commands;
    }
    ADD_FAILURE() << "the command was never counted";
    return {};
  }
};

// Issue test 4: each bad command is rejected, counted by reason, and the arm does not move.
TEST_F(SafetyTest, BadCommandsAreRejectedCountedAndNeverMoveTheArm) {
  start_robotd();
  Session session = acquire({0, 1, 2});
  const JointState before = joint_state();
  const float nan = std::numeric_limits<float>::quiet_NaN();

  ControlCommand wrong_uuid = command_for(session);
  wrong_uuid.uuid = session::random_session_uuid();
  EXPECT_EQ(send_and_count(wrong_uuid).rejected_unknown_session, 1U);

  ControlCommand unowned = command_for(session);
  unowned.motor_ids = {0, 4};
  EXPECT_EQ(send_and_count(unowned).rejected_not_owner, 1U);

  ControlCommand unknown_motor = command_for(session);
  unknown_motor.motor_ids = {0, 17};
  EXPECT_EQ(send_and_count(unknown_motor).rejected_unknown_motor, 1U);

  ControlCommand not_a_number = command_for(session);
  not_a_number.positions = {0.4F, nan};
  EXPECT_EQ(send_and_count(not_a_number).rejected_non_finite, 1U);

  ControlCommand mismatched = command_for(session);
  mismatched.positions = {0.4F};
  EXPECT_EQ(send_and_count(mismatched).rejected_malformed, 1U);

  ControlCommand out_of_range = command_for(session);
  out_of_range.positions = {0.4F, 10.0F};
  EXPECT_EQ(send_and_count(out_of_range).rejected_out_of_range, 1U);

  ControlCommand wrong_device = command_for(session);
  wrong_device.device = "humanoid";
  const CommandCounters counters = send_and_count(wrong_device);
  EXPECT_EQ(counters.rejected_wrong_device, 1U);
  EXPECT_EQ(counters.accepted, 0U);
  EXPECT_EQ(counters.rejected_total(), 7U);

  // Nothing reached the driver: it was never commanded, and nothing moved.
  for (const auto& joint : sim_joints()) EXPECT_EQ(joint["command"], "none") << joint.dump();
  const JointState after = joint_state();
  for (std::size_t j = 0; j < after.position.size(); ++j) EXPECT_NEAR(after.position[j], before.position[j], 1e-6);

  // The same session's good command still works.
  EXPECT_EQ(send_and_count(command_for(session)).accepted, 1U);
  EXPECT_TRUE(wait_for_joints([](const JointState& s) { return std::fabs(s.position[0] - 0.4) < 0.01; }, 5s));
}

// Issue test 5: e-stop from a client with no session latches and blocks commands until reset.
TEST_F(SafetyTest, EstopFromAnyClientLatchesAndBlocksCommandsUntilReset) {
  start_robotd();
  Session session = acquire({0, 1});
  Client bystander = make_client("safety_officer");
  ASSERT_TRUE(bystander.estop("", "test: hand in the workspace"));

  const DeviceStatus engaged = device_status();
  EXPECT_EQ(engaged.state, DeviceState::kEstop);
  EXPECT_TRUE(engaged.estop_engaged);
  EXPECT_NE(engaged.state_text.find("safety_officer"), std::string::npos) << engaged.state_text;

  const JointState before = joint_state();
  EXPECT_EQ(send_and_count(command_for(session)).rejected_estop, 1U);
  std::this_thread::sleep_for(300ms);
  EXPECT_NEAR(joint_state().position[0], before.position[0], 1e-6) << "a command moved an e-stopped arm";
  EXPECT_TRUE(sim_state()["estop"].get<bool>()) << "the vendor e-stop was not triggered";

  // Still latched later, and new sessions are refused while it is.
  std::this_thread::sleep_for(200ms);
  EXPECT_EQ(device_status().state, DeviceState::kEstop);
  SessionRequest other;
  other.device = "arm";
  other.motor_ids = {5};
  auto refused = client().request_control(other);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("e-stopped"), std::string::npos) << refused.error().message;

  ASSERT_TRUE(bystander.reset_estop());
  for (int i = 0; i < 20 && device_status().state != DeviceState::kRunning; ++i) std::this_thread::sleep_for(20ms);
  EXPECT_EQ(device_status().state, DeviceState::kRunning);
  EXPECT_EQ(send_and_count(command_for(session)).accepted, 1U);
  EXPECT_TRUE(wait_for_joints([](const JointState& s) { return std::fabs(s.position[0] - 0.4) < 0.01; }, 5s));
}

TEST_F(SafetyTest, InjectedFaultLatchesUntilRecoverAndTheArmDoesNotJump) {
  start_robotd();
  Session session = acquire({0, 1});
  ASSERT_TRUE(wait_for_joints(
      [&](const JointState& s) {
        (void)session.send_positions({0.4F, 0.4F});
        return std::fabs(s.position[0] - 0.4) < 0.01;
      },
      5s));

  ASSERT_TRUE(client().device_call("arm", "raise_fault", R"({"code": 42, "text": "overcurrent on joint1"})"));
  DeviceStatus faulted = device_status();
  for (int i = 0; i < 20 && faulted.state != DeviceState::kFault; ++i) faulted = device_status();
  EXPECT_EQ(faulted.state, DeviceState::kFault);
  EXPECT_EQ(faulted.fault_code, 42);
  EXPECT_NE(faulted.fault_text.find("overcurrent"), std::string::npos);
  EXPECT_EQ(send_and_count(command_for(session)).rejected_fault, 1U);

  // The black box kept the ticks before the fault.
  auto box = client().device_call("arm", "blackbox");
  ASSERT_TRUE(box) << box.error().message;
  const auto black_box = nlohmann::json::parse(box.value());
  EXPECT_NE(black_box["reason"].get<std::string>().find("overcurrent"), std::string::npos);
  EXPECT_GT(black_box["ticks"].size(), 100U);

  const JointState before = joint_state();
  auto recovered = client().device_call("arm", "recover");
  ASSERT_TRUE(recovered) << recovered.error().message;
  EXPECT_EQ(device_status().state, DeviceState::kRunning);
  // Recovery holds where the arm is: no jump back to a stale target.
  std::this_thread::sleep_for(300ms);
  const JointState after = joint_state();
  EXPECT_NEAR(after.position[0], before.position[0], 0.05);
  EXPECT_EQ(sim_state()["joints"][0]["command"], "position");
}

TEST_F(SafetyTest, StoppedFeedbackBecomesAFaultNamingTheSilence) {
  start_robotd(sim_arm_config(domain_.id(), nullptr, {{"feedback_timeout_ms", 50}}));
  ASSERT_TRUE(client().device_call("arm", "stop_feedback", R"({"enabled": true})"));
  DeviceStatus status = device_status();
  for (int i = 0; i < 20 && status.state != DeviceState::kFault; ++i) status = device_status();
  EXPECT_EQ(status.state, DeviceState::kFault);
  EXPECT_NE(status.fault_text.find("no feedback"), std::string::npos) << status.fault_text;

  ASSERT_TRUE(client().device_call("arm", "recover"));
  EXPECT_EQ(device_status().state, DeviceState::kRunning);
}

TEST_F(SafetyTest, LostLinkIsAFaultAndRecoverReconnects) {
  start_robotd(sim_arm_config(domain_.id(), nullptr, {{"reconnect_interval_ms", 0}}));  // by hand only
  ASSERT_TRUE(client().device_call("arm", "disconnect"));
  DeviceStatus status = device_status();
  for (int i = 0; i < 20 && status.state != DeviceState::kFault; ++i) status = device_status();
  EXPECT_EQ(status.state, DeviceState::kFault);
  EXPECT_NE(status.fault_text.find("link lost"), std::string::npos) << status.fault_text;
  SessionRequest request;
  request.device = "arm";
  auto refused = client().request_control(request);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("FAULT"), std::string::npos) << refused.error().message;

  ASSERT_TRUE(client().device_call("arm", "recover"));
  EXPECT_EQ(device_status().state, DeviceState::kRunning);
  EXPECT_EQ(sim_state()["link"], "connected");
}

TEST_F(SafetyTest, ReconnectAttemptsBackOffWhileTheLinkStaysDown) {
  start_robotd(
      sim_arm_config(domain_.id(), nullptr, {{"reconnect_interval_ms", 100}, {"reconnect_max_interval_ms", 800}}));
  ASSERT_TRUE(client().device_call("arm", "disconnect", R"({"for_ms": 2500})"));
  const auto lost_at = std::chrono::steady_clock::now();
  bool lost = false;  // first the loop must see the link go (a slow build may answer before it has)
  while (!lost && std::chrono::steady_clock::now() - lost_at < 2s)
    lost = device_status().state != DeviceState::kRunning;
  ASSERT_TRUE(lost) << "robotd never saw the link go";
  bool back = false;
  while (!back && std::chrono::steady_clock::now() - lost_at < 6s)
    back = device_status().state == DeviceState::kRunning;
  ASSERT_TRUE(back) << "robotd did not reconnect after the outage";
  // Attempts 100, 200, 400, 800, 800 … ms apart: about 6 in 2.5 s, where a fixed 100 ms would make 25.
  const auto calls = sim_state()["recover_calls"].get<int>();
  EXPECT_GE(calls, 4);
  EXPECT_LE(calls, 8);
  EXPECT_LT(std::chrono::steady_clock::now() - lost_at, 2500ms + 800ms + 1s) << "waited beyond the ceiling";
}

TEST_F(SafetyTest, LostLinkReconnectsByItselfWhenTheLinkReturnsAndTheArmDoesNotJump) {
  start_robotd(sim_arm_config(domain_.id(), nullptr, {{"reconnect_interval_ms", 200}}));
  Session session = acquire({0, 1});
  ASSERT_TRUE(wait_for_joints(
      [&](const JointState& s) {
        (void)session.send_positions({0.6F, -0.4F});
        return std::fabs(s.position[0] - 0.6) < 0.01 && std::fabs(s.position[1] + 0.4) < 0.01;
      },
      5s));

  ASSERT_TRUE(client().device_call("arm", "disconnect", R"({"for_ms": 1500})"));
  const auto lost_at = std::chrono::steady_clock::now();
  DeviceStatus status = device_status();
  for (int i = 0; i < 20 && status.state != DeviceState::kFault; ++i) status = device_status();
  EXPECT_EQ(status.state, DeviceState::kFault);
  EXPECT_NE(status.fault_text.find("link lost"), std::string::npos) << status.fault_text;

  bool back = false;
  while (!back && std::chrono::steady_clock::now() - lost_at < 5s)
    back = device_status().state == DeviceState::kRunning;
  ASSERT_TRUE(back) << "robotd did not reconnect after the outage";
  EXPECT_GE(std::chrono::steady_clock::now() - lost_at, 1400ms) << "reconnected while the link was still down";
  std::this_thread::sleep_for(300ms);
  const JointState after = joint_state();
  EXPECT_NEAR(after.position[0], 0.6, 0.05) << "the arm moved on reconnect";
  EXPECT_NEAR(after.position[1], -0.4, 0.05) << "the arm moved on reconnect";
  EXPECT_NE(robotd_->log().find("device 'arm': reconnected after"), std::string::npos) << robotd_->log();
}

// A device's own e-stop input (PAROL6's E-stop connector, say) engages robotd's e-stop; it
// latches past the release, and cannot be reset while the button is still pressed.
TEST_F(SafetyTest, DeviceEstopInputEngagesTheEstopAndBlocksItsResetWhilePressed) {
  start_robotd();
  Session session = acquire({0, 1});
  ASSERT_TRUE(client().device_call("arm", "estop_input", R"({"pressed": true})"));
  DeviceStatus status = device_status();
  for (int i = 0; i < 20 && !status.estop_engaged; ++i) status = device_status();
  ASSERT_TRUE(status.estop_engaged);
  EXPECT_EQ(status.state, DeviceState::kEstop);
  EXPECT_NE(robotd_->log().find("e-stop applied (engaged by the device's own e-stop input)"), std::string::npos)
      << robotd_->log();

  const auto refused = client().reset_estop("arm");
  ASSERT_FALSE(refused) << "reset while the button is pressed";
  EXPECT_NE(refused.error().message.find("still pressed"), std::string::npos) << refused.error().message;

  ASSERT_TRUE(client().device_call("arm", "estop_input", R"({"pressed": false})"));
  std::this_thread::sleep_for(50ms);
  EXPECT_TRUE(device_status().estop_engaged) << "released, but latched until someone resets";
  const auto reset = client().reset_estop("arm");
  ASSERT_TRUE(reset);
  EXPECT_TRUE(reset.value().success) << reset.value().message;
  status = device_status();
  for (int i = 0; i < 20 && status.estop_engaged; ++i) status = device_status();
  EXPECT_FALSE(status.estop_engaged);
}

TEST_F(SafetyTest, ClampPolicyClampsInsteadOfRejecting) {
  start_robotd(sim_arm_config(domain_.id(), nullptr, {{"limit_policy", "clamp"}}));
  Session session = acquire({0, 1});
  ControlCommand far = command_for(session);
  far.positions = {10.0F, 0.0F};
  const CommandCounters counters = send_and_count(far);
  EXPECT_EQ(counters.accepted, 1U);
  EXPECT_EQ(counters.clamped, 1U);
  EXPECT_TRUE(wait_for_joints([](const JointState& s) { return std::fabs(s.position[0] - 2.5) < 0.02; }, 5s));
}

// Defect 8: an op that acts on the joints (the sim's motors op, as a vendor's disable) is refused
// while a session holds a motor of the device, naming the holder by its public id; the driver then
// refuses to let go of a joint robotd still holds in the session's fallback; and no session is
// granted while such an op runs.
TEST_F(SafetyTest, AnOpThatActsOnTheJointsWaitsForFreeMotorsAndNoSessionStartsWhileItRuns) {
  start_robotd();
  const auto devices = client().list_devices();
  ASSERT_TRUE(devices) << devices.error().message;
  ASSERT_EQ(devices.value().size(), 1U);
  const auto line_of = [&](const std::string& op) {
    const auto& ops = devices.value()[0].ops;
    const auto line =
        std::find_if(ops.begin(), ops.end(), [&](const std::string& l) { return l.starts_with(op + ":"); });
    return line == ops.end() ? std::string("(no " + op + ")") : *line;
  };
  EXPECT_TRUE(line_of("motors").ends_with(" [needs free motors]")) << line_of("motors");
  EXPECT_EQ(line_of("state").find("[needs free motors]"), std::string::npos) << line_of("state");
  const std::string off = R"({"enabled": false})";

  Session session = acquire({2});
  const auto refused = client().device_call("arm", "motors", off);
  ASSERT_FALSE(refused) << "the motors were disabled under a session";
  EXPECT_NE(refused.error().message.find("motors is refused while a session is active on 'arm'"), std::string::npos)
      << refused.error().message;
  EXPECT_NE(refused.error().message.find("(session " + session.session_id() + ","), std::string::npos)
      << refused.error().message;
  EXPECT_EQ(refused.error().message.find(session.uuid()), std::string::npos) << "the refusal gave the uuid away";
  EXPECT_EQ(sim_state()["motors"], "enabled");

  // Released with KEEP, the joint is still robotd's to hold: the driver will not let it go.
  ASSERT_TRUE(session.release(Behavior::kKeep));
  const auto held = client().device_call("arm", "motors", off);
  ASSERT_FALSE(held) << "the motors were disabled under robotd's KEEP";
  EXPECT_NE(held.error().message.find("robotd still holds joint 'joint3'"), std::string::npos) << held.error().message;
  // Let go by its owner (ZERO_TORQUE), the device is free and the op runs.
  Session owner = acquire({2});
  ASSERT_TRUE(owner.release(Behavior::kZeroTorque));
  const auto disabled = client().device_call("arm", "motors", off);
  ASSERT_TRUE(disabled) << disabled.error().message;
  EXPECT_EQ(sim_state()["motors"], "disabled");

  // A slow op (the controller answers in 1.5 s) holds the device: no session meanwhile.
  call_device("arm", "slow_maintenance", {{"ms", 1500}});
  Client maintainer = make_client("maintainer");
  auto enabling =
      std::async(std::launch::async, [&] { return maintainer.device_call("arm", "motors", R"({"enabled": true})"); });
  bool switching = false;
  for (int i = 0; i < 40 && !switching; ++i) {
    for (const KeyValue& value : device_status().driver_values) {
      switching = switching || (value.key == "motors" && value.value.find("switching") != std::string::npos);
    }
  }
  SessionRequest request;
  request.device = "arm";
  request.motor_ids = {0};
  const auto during = client().request_control(request);
  const auto enabled = enabling.get();
  ASSERT_TRUE(switching) << "the motors op never showed as running";
  ASSERT_FALSE(during) << "a session was granted while the motors op ran";
  EXPECT_NE(during.error().message.find("device 'arm' is in maintenance (motors)"), std::string::npos)
      << during.error().message;
  ASSERT_TRUE(enabled) << enabled.error().message;
  EXPECT_EQ(sim_state()["motors"], "enabled");
  const auto after = client().request_control(request);
  EXPECT_TRUE(after) << "no session once the op was done: " << after.error().message;
}

}  // namespace
}  // namespace robotd::testing
