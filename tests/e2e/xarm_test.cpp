// The xArm driver end to end: robotd loads the xarm plugin, which talks to robotd-xarm-sim's
// command and report ports on loopback; a client drives it through DDS.
#include <chrono>
#include <cmath>
#include <thread>

#include <gtest/gtest.h>

#include "allocation_counter.hpp"
#include "robotd_fixture.hpp"
#include "xarm_sim_process.hpp"

namespace robotd::testing {
namespace {

using namespace std::chrono_literals;

class XarmTest : public RobotdTest {
 protected:
  void start(bool with_sim_arm, std::vector<std::string> environment = {}) {
    const nlohmann::json params{{"model", "xarm6"},
                                {"host", "127.0.0.1"},
                                {"port", sim_.port()},
                                {"report", {{"kind", "real"}, {"port", sim_.report_port()}}}};
    start_with_device(vendor_device("xarm", params), with_sim_arm, std::move(environment));
  }
  Session acquire(std::vector<std::int32_t> motors = {}) { return acquire_device("xarm", std::move(motors)); }
  nlohmann::json call(const std::string& op, const nlohmann::json& args = nlohmann::json::object()) {
    return call_device("xarm", op, args);
  }
  std::vector<float> measured() {
    const std::vector<double> position = joint_state("xarm").position;
    return {position.begin(), position.end()};
  }
  nlohmann::json sim_state() const { return sim_.control({{"op", "state"}}); }

  XarmSimProcess sim_{{"--quiet"}};
};

TEST_F(XarmTest, SessionMovesTheArmInServoModeAndVendorOpsAnswer) {
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
      10s, "xarm"));
  nlohmann::json state = sim_state();
  EXPECT_EQ(state["mode"].get<int>(), 1) << state.dump();
  EXPECT_GT(state["servo"]["frames"].get<int>(), 300) << state.dump();
  EXPECT_EQ(state["servo"]["ignored"].get<int>(), 0) << state.dump();
  EXPECT_EQ(state["error"].get<int>(), 0) << state.dump();

  const nlohmann::json tcp = call("get_tcp_pose");
  EXPECT_GT(tcp["z_m"].get<double>(), 0.05) << tcp.dump();
  const auto refused = client().device_call("xarm", "move_gohome", "{}");
  ASSERT_FALSE(refused) << "a planned move while a session streams";
  EXPECT_NE(refused.error().message.find("move_gohome is refused while a session is active on 'xarm'"),
            std::string::npos)
      << refused.error().message;
  EXPECT_NE(refused.error().message.find("(session " + session.session_id() + ","), std::string::npos)
      << refused.error().message;
  ASSERT_TRUE(session.release(Behavior::kKeep));
  ASSERT_TRUE(wait_for_joints([&](const JointState& /*s*/) { return sim_state()["mode"].get<int>() == 0; }, 5s, "xarm"))
      << "servo mode was not left: " << sim_state().dump();
  const nlohmann::json moved =
      call("move_joint", {{"joints_rad", {0.1, 0.1, -0.1, 0.1, 0.1, 0.1}}, {"speed_rad_s", 1.0}, {"wait", true}});
  EXPECT_TRUE(moved["completed"].get<bool>()) << moved.dump();
  EXPECT_NEAR(measured()[2], -0.1, 0.01);
  const DeviceStatus status = device_status("xarm");
  EXPECT_EQ(status.state, DeviceState::kRunning) << status.fault_text;
  if (kCountsAllocations) {
    EXPECT_EQ(status.loop.rt_heap_allocations, 0) << "the driver allocated on the RT thread";
  }
}

TEST_F(XarmTest, ControllerErrorIsAFaultWithItsTextAndRecoverClearsIt) {
  start(/*with_sim_arm=*/false);
  ASSERT_TRUE(sim_.control({{"op", "error"}, {"code", 22}})["ok"].get<bool>());
  const DeviceStatus fault = wait_for_state("xarm", DeviceState::kFault);
  ASSERT_EQ(fault.state, DeviceState::kFault);
  EXPECT_EQ(fault.fault_code, 22);
  EXPECT_NE(fault.fault_text.find("C22 self-collision"), std::string::npos) << fault.fault_text;
  const auto recovered = client().device_call("xarm", "recover");
  ASSERT_TRUE(recovered) << recovered.error().message;
  EXPECT_EQ(wait_for_state("xarm", DeviceState::kRunning).state, DeviceState::kRunning) << robotd_->log();
}

TEST_F(XarmTest, RobotdsEstopStopsTheArm) {
  start(/*with_sim_arm=*/false);
  Session session = acquire({0});
  const float j1 = measured()[0];
  ASSERT_TRUE(session.send_positions({j1 + 0.8F}));
  ASSERT_TRUE(wait_for_joints([&](const JointState& s) { return s.position[0] > j1 + 0.05; }, 5s, "xarm"));
  ASSERT_TRUE(client().estop("xarm"));
  EXPECT_EQ(wait_for_state("xarm", DeviceState::kEstop).state, DeviceState::kEstop);
  const auto deadline = std::chrono::steady_clock::now() + 2s;
  while (sim_state()["state"].get<int>() != 4 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(20ms);
  }
  EXPECT_EQ(sim_state()["state"].get<int>(), 4) << "set_state(4) did not reach the control box";
  const int frames = sim_state()["servo"]["frames"].get<int>();
  std::this_thread::sleep_for(100ms);
  EXPECT_EQ(sim_state()["servo"]["frames"].get<int>(), frames) << "servo_j during the e-stop";
}

// The control box's e-stop button (error C1) engages robotd's e-stop; once released, robotd's
// reset brings the arm back without a separate recover.
TEST_F(XarmTest, TheEstopButtonEngagesRobotdsEstopUntilReleasedAndReset) {
  start(/*with_sim_arm=*/false);
  ASSERT_TRUE(sim_.control({{"op", "estop"}, {"pressed", true}})["ok"].get<bool>());
  const DeviceStatus pressed = wait_for_state("xarm", DeviceState::kEstop);
  ASSERT_EQ(pressed.state, DeviceState::kEstop) << pressed.fault_text;
  const auto refused = client().reset_estop("xarm");
  ASSERT_FALSE(refused) << "reset while the button is pressed";
  EXPECT_NE(refused.error().message.find("still pressed"), std::string::npos) << refused.error().message;

  ASSERT_TRUE(sim_.control({{"op", "estop"}, {"pressed", false}})["ok"].get<bool>());
  bool reset = false;
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  while (!reset && std::chrono::steady_clock::now() < deadline) {
    const auto attempt = client().reset_estop("xarm");
    reset = attempt && attempt.value().success;
    if (!reset) std::this_thread::sleep_for(100ms);
  }
  ASSERT_TRUE(reset) << "the released button still blocks the reset: " << sim_state().dump();
  EXPECT_EQ(wait_for_state("xarm", DeviceState::kRunning).state, DeviceState::kRunning) << robotd_->log();
  EXPECT_EQ(sim_state()["error"].get<int>(), 0);
}

TEST_F(XarmTest, AClosedConnectionMidMotionIsReportedReconnectedAndTheArmDoesNotJump) {
  start(/*with_sim_arm=*/true);
  Session session = acquire({0});
  const float j1 = measured()[0];
  ASSERT_TRUE(session.send_positions({j1 + 0.55F}));  // far: robotd ramps towards it
  ASSERT_TRUE(wait_for_joints([&](const JointState& s) { return s.position[0] > j1 + 0.1; }, 5s, "xarm"));
  ASSERT_TRUE(sim_.control({{"op", "disconnect"}})["ok"].get<bool>());
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  while (robotd_->log().find("the control box closed the") == std::string::npos &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(20ms);
  }
  EXPECT_NE(robotd_->log().find("FAULT -2 (the control box closed the"), std::string::npos) << robotd_->log();
  EXPECT_EQ(device_status("arm").state, DeviceState::kRunning);
  ASSERT_EQ(wait_for_state("xarm", DeviceState::kRunning, 10s).state, DeviceState::kRunning) << robotd_->log();
  const double at_reconnect = measured()[0];
  std::this_thread::sleep_for(500ms);
  EXPECT_NEAR(measured()[0], at_reconnect, 0.005) << "the arm moved after the reconnect";
  EXPECT_LT(at_reconnect, j1 + 0.5) << "the old target was resumed";
}

TEST_F(XarmTest, KilledSimulatorIsReportedOthersKeepRunningAndARestartedOneIsReconnected) {
  start(/*with_sim_arm=*/true);
  sim_.kill_hard();
  const DeviceStatus fault = wait_for_state("xarm", DeviceState::kFault);
  ASSERT_EQ(fault.state, DeviceState::kFault);
  EXPECT_NE(fault.fault_text.find("closed the"), std::string::npos) << fault.fault_text;
  const std::uint64_t arm_before = device_status("arm").joint_states_published;
  std::this_thread::sleep_for(300ms);
  EXPECT_EQ(device_status("arm").state, DeviceState::kRunning);
  EXPECT_GT(device_status("arm").joint_states_published, arm_before + 100);
  sim_.restart();
  EXPECT_EQ(wait_for_state("xarm", DeviceState::kRunning, 15s).state, DeviceState::kRunning) << robotd_->log();
}

}  // namespace
}  // namespace robotd::testing
