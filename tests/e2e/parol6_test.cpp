// The PAROL6 driver end to end: robotd loads the parol6 plugin, which talks to
// robotd-parol6-sim over a pseudo-terminal; a client drives it through DDS.
#include <array>
#include <chrono>
#include <cmath>
#include <thread>

#include <gtest/gtest.h>

#include "allocation_counter.hpp"
#include "parol6_sim_process.hpp"
#include "robotd_fixture.hpp"

namespace robotd::testing {
namespace {

using namespace std::chrono_literals;

// Standby after homing (spec §10.3): 90°, −90°, 180°, 0°, 0°, 180°.
constexpr std::array<float, 6> kStandby{1.5708F, -1.5708F, 3.1416F, 0.0F, 0.0F, 3.1416F};

class Parol6Test : public RobotdTest {
 protected:
  void start(bool with_sim_arm, std::vector<std::string> environment = {}) {
    const nlohmann::json params{{"serial", {{"device", sim_.pty_path()}, {"baud", 3000000}}}};
    start_with_device(vendor_device("parol6", params), with_sim_arm, std::move(environment));
  }
  Session acquire(std::vector<std::int32_t> motors = {}, std::chrono::milliseconds timeout = 10s) {
    return acquire_device("parol6", std::move(motors), ControlMode::kPosition, timeout);
  }
  nlohmann::json call(const std::string& op, const nlohmann::json& args = nlohmann::json::object()) {
    return call_device("parol6", op, args);
  }

  Parol6SimProcess sim_{Parol6SimProcess::unique_path("parol6-e2e"), {"--homed"}};
};

TEST_F(Parol6Test, SessionMovesTheArmAndBoardOpsAnswer) {
  start(/*with_sim_arm=*/false, allocation_counter_environment());
  Session session = acquire();
  // Two seconds of 1 kHz commands: a slow wave on J1 and J4, then a hold.
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<float> target(kStandby.begin(), kStandby.end());
  for (auto next = t0; std::chrono::steady_clock::now() - t0 < 2s; next += 1ms) {
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    target[0] = kStandby[0] + static_cast<float>(0.3 * std::sin(M_PI * t / 2));
    target[3] = kStandby[3] - static_cast<float>(0.2 * std::sin(M_PI * t / 2));
    ASSERT_TRUE(session.send_positions(target));
    std::this_thread::sleep_until(next);
  }
  EXPECT_TRUE(wait_for_joints(
      [&](const JointState& s) {
        (void)session.send_positions(target);
        return std::fabs(s.position[0] - target[0]) < 0.005 && std::fabs(s.position[3] - target[3]) < 0.005;
      },
      10s, "parol6"));
  const nlohmann::json io = call("io");
  EXPECT_FALSE(io["estop_pressed"].get<bool>()) << io.dump();
  const nlohmann::json state = call("state");
  EXPECT_TRUE(state["all_homed"].get<bool>()) << state.dump();
  EXPECT_EQ(state["command_in_force"], "go to position") << state.dump();
  // An op that acts on the joints waits for them to be free; a query does not.
  const auto refused = client().device_call("parol6", "home", "{}");
  ASSERT_FALSE(refused) << "homing while a session streams";
  EXPECT_NE(refused.error().message.find("home is refused while a session is active on 'parol6'"), std::string::npos)
      << refused.error().message;
  EXPECT_NE(refused.error().message.find("(session " + session.session_id() + ","), std::string::npos)
      << refused.error().message;
  ASSERT_TRUE(session.release(Behavior::kKeep));
  EXPECT_EQ(call("enable")["sent"], "enable");
  const DeviceStatus status = device_status("parol6");
  EXPECT_EQ(status.state, DeviceState::kRunning) << status.fault_text;
  if (kCountsAllocations) {
    EXPECT_EQ(status.loop.rt_heap_allocations, 0) << "the serial exchange allocated on the RT thread";
  }
}

TEST_F(Parol6Test, TheBoardsEstopInputEngagesRobotdsEstop) {
  start(/*with_sim_arm=*/false);
  ASSERT_TRUE(sim_.control({{"op", "estop"}, {"pressed", true}})["ok"].get<bool>());
  DeviceStatus status = wait_for_state("parol6", DeviceState::kEstop);
  ASSERT_TRUE(status.estop_engaged);
  EXPECT_NE(robotd_->log().find("engaged by the device's own e-stop input"), std::string::npos) << robotd_->log();
  const auto refused = client().reset_estop("parol6");
  ASSERT_FALSE(refused) << "reset while the button is pressed";
  EXPECT_NE(refused.error().message.find("still pressed"), std::string::npos) << refused.error().message;
  ASSERT_TRUE(sim_.control({{"op", "estop"}, {"pressed", false}})["ok"].get<bool>());
  std::this_thread::sleep_for(100ms);
  const auto reset = client().reset_estop("parol6");
  ASSERT_TRUE(reset);
  EXPECT_TRUE(reset.value().success) << reset.value().message;
  EXPECT_EQ(wait_for_state("parol6", DeviceState::kRunning).state, DeviceState::kRunning);
}

TEST_F(Parol6Test, LostLineIsAFaultOthersKeepRunningAndTheArmDoesNotJumpOnReconnect) {
  start(/*with_sim_arm=*/true);
  Session session = acquire({0});
  ASSERT_TRUE(session.send_positions({kStandby[0] + 0.55F}));  // far: robotd ramps towards it
  ASSERT_TRUE(wait_for_joints([](const JointState& s) { return s.position[0] > kStandby[0] + 0.1; }, 5s, "parol6"));
  ASSERT_TRUE(sim_.control({{"op", "disconnect"}, {"ms", 800}})["ok"].get<bool>());
  const DeviceStatus fault = wait_for_state("parol6", DeviceState::kFault);
  ASSERT_EQ(fault.state, DeviceState::kFault);
  EXPECT_NE(fault.fault_text.find("serial"), std::string::npos) << fault.fault_text;

  const std::uint64_t arm_before = device_status("arm").joint_states_published;
  std::this_thread::sleep_for(300ms);
  EXPECT_EQ(device_status("arm").state, DeviceState::kRunning);
  EXPECT_GT(device_status("arm").joint_states_published, arm_before + 100);

  ASSERT_EQ(wait_for_state("parol6", DeviceState::kRunning, 10s).state, DeviceState::kRunning) << robotd_->log();
  const double at_reconnect = joint_state("parol6").position[0];
  std::this_thread::sleep_for(500ms);
  EXPECT_NEAR(joint_state("parol6").position[0], at_reconnect, 0.002) << "the arm moved after the reconnect";
  EXPECT_LT(at_reconnect, kStandby[0] + 0.5) << "the old target was resumed";
}

TEST_F(Parol6Test, KilledSimulatorIsReportedAndARestartedOneIsReconnected) {
  start(/*with_sim_arm=*/true);
  sim_.kill_hard();
  ASSERT_EQ(wait_for_state("parol6", DeviceState::kFault).state, DeviceState::kFault);
  EXPECT_EQ(device_status("arm").state, DeviceState::kRunning);
  sim_.restart();
  EXPECT_EQ(wait_for_state("parol6", DeviceState::kRunning, 10s).state, DeviceState::kRunning) << robotd_->log();
}

TEST_F(Parol6Test, ATimedOutSessionLeavesTheBoardIdleNeverJogging) {
  start(/*with_sim_arm=*/false);
  {
    Session session = acquire({}, 300ms);
    std::vector<float> target(kStandby.begin(), kStandby.end());
    target[5] -= 0.5F;
    ASSERT_TRUE(session.send_positions(target));
    std::this_thread::sleep_for(100ms);
    // Stop sending: robotd's timeout applies KEEP; the board must not be left moving.
    std::this_thread::sleep_for(800ms);
  }
  const nlohmann::json state = sim_.control({{"op", "state"}});
  EXPECT_EQ(state["command"], 255) << state.dump();
  const double before = joint_state("parol6").position[5];
  std::this_thread::sleep_for(300ms);
  EXPECT_NEAR(joint_state("parol6").position[5], before, 1e-3);
}

}  // namespace
}  // namespace robotd::testing
