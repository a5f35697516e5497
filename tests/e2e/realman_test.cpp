// The RealMan driver end to end: robotd loads the realman plugin, which talks TCP JSON and UDP to
// robotd-realman-sim on loopback; a client drives it through DDS.
#include <array>
#include <chrono>
#include <cmath>
#include <thread>

#include <gtest/gtest.h>

#include "allocation_counter.hpp"
#include "realman_sim_process.hpp"
#include "robotd_fixture.hpp"

namespace robotd::testing {
namespace {

using namespace std::chrono_literals;

class RealmanTest : public RobotdTest {
 protected:
  void start(bool with_sim_arm, std::vector<std::string> environment = {}) {
    const nlohmann::json params{
        {"model", "RM65"}, {"host", "127.0.0.1"}, {"port", sim_.port()}, {"push", {{"ip", "127.0.0.1"}, {"port", 0}}}};
    start_with_device(vendor_device("realman", params), with_sim_arm, std::move(environment));
  }
  Session acquire(std::vector<std::int32_t> motors = {}) { return acquire_device("realman", std::move(motors)); }
  nlohmann::json call(const std::string& op, const nlohmann::json& args = nlohmann::json::object()) {
    return call_device("realman", op, args);
  }
  std::vector<float> measured() {
    const std::vector<double> position = joint_state("realman").position;
    return {position.begin(), position.end()};
  }

  RealmanSimProcess sim_{{"--quiet"}};
};

TEST_F(RealmanTest, SessionMovesTheArmAndVendorOpsAnswer) {
  start(/*with_sim_arm=*/false, allocation_counter_environment());
  Session session = acquire();
  std::vector<float> start_position = measured();
  ASSERT_EQ(start_position.size(), 6U);
  std::vector<float> target = start_position;
  // Two seconds of 1 kHz commands: a slow wave on J1 and J5, then a hold.
  const auto t0 = std::chrono::steady_clock::now();
  for (auto next = t0; std::chrono::steady_clock::now() - t0 < 2s; next += 1ms) {
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    target[0] = start_position[0] + static_cast<float>(0.3 * std::sin(M_PI * t / 2));
    target[4] = start_position[4] - static_cast<float>(0.2 * std::sin(M_PI * t / 2));
    ASSERT_TRUE(session.send_positions(target));
    std::this_thread::sleep_until(next);
  }
  EXPECT_TRUE(wait_for_joints(
      [&](const JointState& s) {
        (void)session.send_positions(target);
        return std::fabs(s.position[0] - target[0]) < 0.005 && std::fabs(s.position[4] - target[4]) < 0.005;
      },
      10s, "realman"));
  const nlohmann::json sim_state = sim_.control({{"op", "state"}});
  EXPECT_GT(sim_state["pass_through"]["frames"].get<int>(), 300) << sim_state.dump();
  EXPECT_EQ(sim_state["pass_through"]["ignored"].get<int>(), 0) << sim_state.dump();

  const nlohmann::json gripper = call("get_gripper_state");
  EXPECT_TRUE(gripper["online"].get<bool>()) << gripper.dump();
  const auto refused = client().device_call("realman", "movej", R"({"joints_rad": [0, 0, 0, 0, 0, 0]})");
  ASSERT_FALSE(refused) << "a planned move while a session streams";
  EXPECT_NE(refused.error().message.find("movej is refused while a session is active on 'realman'"), std::string::npos)
      << refused.error().message;
  EXPECT_NE(refused.error().message.find("(session " + session.session_id() + ","), std::string::npos)
      << refused.error().message;
  ASSERT_TRUE(session.release(Behavior::kKeep));
  std::this_thread::sleep_for(20ms);  // the loop applies the release on its next ticks
  const nlohmann::json moved = call("movej", {{"joints_rad", {0.1, 0.1, 0.1, 0.1, 0.1, 0.1}}, {"v", 80}});
  EXPECT_TRUE(moved["completed"].get<bool>()) << moved.dump();
  EXPECT_NEAR(measured()[2], 0.1, 0.01);
  const DeviceStatus status = device_status("realman");
  EXPECT_EQ(status.state, DeviceState::kRunning) << status.fault_text;
  if (kCountsAllocations) {
    EXPECT_EQ(status.loop.rt_heap_allocations, 0) << "the driver allocated on the RT thread";
  }
}

TEST_F(RealmanTest, ControllerErrorIsAFaultWithItsTextAndRecoverClearsIt) {
  start(/*with_sim_arm=*/false);
  ASSERT_TRUE(sim_.control({{"op", "raise_error"}, {"code", 0x1007}})["ok"].get<bool>());
  const DeviceStatus fault = wait_for_state("realman", DeviceState::kFault);
  ASSERT_EQ(fault.state, DeviceState::kFault);
  EXPECT_NE(fault.fault_text.find("0x1007"), std::string::npos) << fault.fault_text;
  const auto recovered = client().device_call("realman", "recover");
  ASSERT_TRUE(recovered) << recovered.error().message;
  EXPECT_EQ(wait_for_state("realman", DeviceState::kRunning).state, DeviceState::kRunning) << robotd_->log();
}

TEST_F(RealmanTest, RobotdsEstopStopsTheArm) {
  start(/*with_sim_arm=*/false);
  ASSERT_TRUE(client().estop("realman"));
  EXPECT_EQ(wait_for_state("realman", DeviceState::kEstop).state, DeviceState::kEstop);
  const auto deadline = std::chrono::steady_clock::now() + 2s;
  while (sim_.control({{"op", "state"}})["commands"].value("set_arm_stop", 0) == 0 &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(20ms);
  }
  EXPECT_EQ(sim_.control({{"op", "state"}})["commands"].value("set_arm_stop", 0), 1);
}

TEST_F(RealmanTest, LostPushIsAFaultOthersKeepRunningAndTheArmDoesNotJumpOnReconnect) {
  start(/*with_sim_arm=*/true);
  Session session = acquire({0});
  const float j1 = measured()[0];
  ASSERT_TRUE(session.send_positions({j1 + 0.55F}));  // far: robotd ramps towards it
  ASSERT_TRUE(wait_for_joints([&](const JointState& s) { return s.position[0] > j1 + 0.1; }, 5s, "realman"));
  // The controller stops pushing (cable of the UDP path, a firewall): reconnecting fails until
  // the push comes back.
  ASSERT_TRUE(sim_.control({{"op", "silence"}, {"on", true}})["ok"].get<bool>());
  const DeviceStatus fault = wait_for_state("realman", DeviceState::kFault);
  ASSERT_EQ(fault.state, DeviceState::kFault);
  EXPECT_NE(fault.fault_text.find("no real-time push"), std::string::npos) << fault.fault_text;

  const std::uint64_t arm_before = device_status("arm").joint_states_published;
  std::this_thread::sleep_for(300ms);
  EXPECT_EQ(device_status("arm").state, DeviceState::kRunning);
  EXPECT_GT(device_status("arm").joint_states_published, arm_before + 100);
  // FAULT, or MAINTENANCE while a reconnect attempt waits for the push: never RUNNING.
  EXPECT_NE(device_status("realman").state, DeviceState::kRunning) << "reconnected without a push";

  ASSERT_TRUE(sim_.control({{"op", "silence"}, {"on", false}})["ok"].get<bool>());
  ASSERT_EQ(wait_for_state("realman", DeviceState::kRunning, 10s).state, DeviceState::kRunning) << robotd_->log();
  const double at_reconnect = measured()[0];
  std::this_thread::sleep_for(500ms);
  EXPECT_NEAR(measured()[0], at_reconnect, 0.002) << "the arm moved after the reconnect";
  EXPECT_LT(at_reconnect, j1 + 0.5) << "the old target was resumed";
}

TEST_F(RealmanTest, AClosedConnectionMidMotionIsReportedAndReconnected) {
  start(/*with_sim_arm=*/false);
  Session session = acquire({0});
  const float j1 = measured()[0];
  ASSERT_TRUE(session.send_positions({j1 + 0.4F}));
  ASSERT_TRUE(wait_for_joints([&](const JointState& s) { return s.position[0] > j1 + 0.05; }, 5s, "realman"));
  ASSERT_TRUE(sim_.control({{"op", "disconnect"}})["ok"].get<bool>());
  // The controller listens again at once, so the fault may last only until the next attempt.
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  while (robotd_->log().find("the controller closed the TCP connection") == std::string::npos &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(20ms);
  }
  EXPECT_NE(robotd_->log().find("FAULT -2 (the controller closed the TCP connection"), std::string::npos)
      << robotd_->log();
  EXPECT_EQ(wait_for_state("realman", DeviceState::kRunning, 10s).state, DeviceState::kRunning) << robotd_->log();
}

TEST_F(RealmanTest, KilledSimulatorIsReportedAndARestartedOneIsReconnected) {
  start(/*with_sim_arm=*/true);
  sim_.kill_hard();
  const DeviceStatus fault = wait_for_state("realman", DeviceState::kFault);
  ASSERT_EQ(fault.state, DeviceState::kFault);
  EXPECT_EQ(device_status("arm").state, DeviceState::kRunning);
  sim_.restart();
  EXPECT_EQ(wait_for_state("realman", DeviceState::kRunning, 15s).state, DeviceState::kRunning) << robotd_->log();
}

}  // namespace
}  // namespace robotd::testing
