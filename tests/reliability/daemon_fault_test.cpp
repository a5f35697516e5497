// robotd itself killed mid-motion (SIGKILL, as a crash or the OOM killer would) and started
// again as systemd would: the xArm simulator outlives it, so the test sees what the arm does
// while robotd is gone, that the new robotd reconnects, that the old session is gone for its
// client, and that nothing moves until a new session commands it.
#include <chrono>
#include <cmath>
#include <csignal>
#include <iostream>
#include <memory>
#include <thread>

#include <gtest/gtest.h>

#include "robotd_fixture.hpp"
#include "xarm_sim_process.hpp"

namespace robotd::testing {
namespace {

using namespace std::chrono_literals;

class DaemonFaultTest : public RobotdTest {
 protected:
  void SetUp() override {
    const nlohmann::json params{{"model", "xarm6"},
                                {"host", "127.0.0.1"},
                                {"port", sim_.port()},
                                {"report", {{"kind", "real"}, {"port", sim_.report_port()}}}};
    config_ = sim_arm_config(domain_.id());
    config_["devices"] = nlohmann::json::array({vendor_device("xarm", params)});
    start_robotd(config_);
  }
  /// The simulated arm's joint 1 as the simulator has it (robotd may not be there to say).
  double sim_joint1() const { return sim_.control({{"op", "state"}})["joints_rad"][0].get<double>(); }

  XarmSimProcess sim_{{"--quiet"}};
  nlohmann::json config_;
};

TEST_F(DaemonFaultTest, KilledMidMotionItComesBackForgetsSessionsAndMovesNothingUntilANewOne) {
  Session session = acquire_device("xarm", {0});
  const double start = joint_state("xarm").position[0];
  ASSERT_TRUE(session.send_positions({static_cast<float>(start + 0.55)}));  // far: robotd ramps towards it
  ASSERT_TRUE(wait_for_joints([&](const JointState& s) { return s.position[0] > start + 0.1; }, 5s, "xarm"));

  ASSERT_EQ(::kill(robotd_->pid(), SIGKILL), 0);
  ASSERT_TRUE(robotd_->wait_for_exit(2s));
  // robotd gone: the controller holds the last servo target it got (docs/reliability.md).
  const double at_kill = sim_joint1();
  std::this_thread::sleep_for(500ms);
  const double while_gone = sim_joint1();
  EXPECT_NEAR(while_gone, at_kill, 0.01) << "the arm kept moving without robotd";
  EXPECT_LT(while_gone, start + 0.5) << "the arm went on to the far target without robotd";

  const auto restarted = std::chrono::steady_clock::now();
  robotd_ = std::make_unique<RobotdProcess>(config_);
  ASSERT_TRUE(robotd_->wait_ready(client())) << robotd_->log();
  ASSERT_EQ(wait_for_state("xarm", DeviceState::kRunning, 10s).state, DeviceState::kRunning) << robotd_->log();
  const double restart_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - restarted).count();

  // The old session is gone, and its client is told so by what it can see.
  const auto status = client().session_status(2s);
  ASSERT_TRUE(status);
  EXPECT_TRUE(status.value().sessions.empty());
  const CommandCounters before = device_status("xarm").commands;
  for (int i = 0; i < 20; ++i) {
    (void)session.send_positions({static_cast<float>(start + 0.55)});
    std::this_thread::sleep_for(5ms);
  }
  std::this_thread::sleep_for(200ms);
  const CommandCounters after = device_status("xarm").commands;
  EXPECT_GE(after.rejected_unknown_session - before.rejected_unknown_session, 15U)
      << "the dead session's commands should be rejected and counted";
  EXPECT_EQ(after.accepted, before.accepted);
  EXPECT_NEAR(sim_joint1(), while_gone, 0.01) << "something moved before a new session";

  Session fresh = acquire_device("xarm", {0});
  ASSERT_TRUE(fresh.send_positions({static_cast<float>(while_gone + 0.1)}));
  EXPECT_TRUE(wait_for_joints([&](const JointState& s) { return std::fabs(s.position[0] - (while_gone + 0.1)) < 0.01; },
                              5s, "xarm"));
  std::cout << "[ measured ] robotd SIGKILL mid-motion: the xArm held (moved " << std::fabs(while_gone - at_kill)
            << " rad in 500 ms); restarted robotd ready with the arm RUNNING in " << std::lround(restart_ms)
            << " ms; the old session's commands rejected; a new session moves the arm\n";
}

}  // namespace
}  // namespace robotd::testing
