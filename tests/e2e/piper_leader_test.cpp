// A PiPER leader (master) arm as a robotd device: robotd loads the piper plugin with
// "role": "leader" against robotd-piper-sim --role leader; a client sees the leader's joints and
// is refused control.
#include <chrono>
#include <cmath>

#include <gtest/gtest.h>

#include "piper_sim_process.hpp"
#include "robotd_fixture.hpp"

namespace robotd::testing {
namespace {

using namespace std::chrono_literals;

class PiperLeaderTest : public RobotdTest {
 protected:
  void start() {
    nlohmann::json device =
        vendor_device("piper", {{"can", {{"transport", "standin"}, {"path", sim_.bus_path()}}}, {"role", "leader"}});
    device["name"] = "leader";
    start_with_device(device, /*with_sim_arm=*/false);
  }

  PiperSimProcess sim_{PiperSimProcess::unique_path("piper-leader-e2e"), {"--role", "leader"}};
};

TEST_F(PiperLeaderTest, JointStatesShowTheLeaderAndControlIsRefused) {
  start();
  ASSERT_TRUE(sim_.control({{"op", "set_joint"}, {"joint", 1}, {"position_rad", 0.7}})["ok"].get<bool>());
  ASSERT_TRUE(sim_.control({{"op", "set_joint"}, {"joint", 3}, {"position_rad", -0.9}})["ok"].get<bool>());
  EXPECT_TRUE(wait_for_joints(
      [](const JointState& s) {
        return std::fabs(s.position[0] - 0.7) < 0.01 && std::fabs(s.position[2] + 0.9) < 0.01;
      },
      10s, "leader"))
      << "joint states do not show the leader's joints";

  SessionRequest request;
  request.device = "leader";
  request.mode = ControlMode::kPosition;
  request.on_timeout = Behavior::kKeep;
  request.timeout = 1000ms;
  auto session = client().request_control(request);
  ASSERT_FALSE(session) << "control of a leader arm was granted";
  EXPECT_NE(session.error().message.find("device 'leader' (piper) takes no commands: this PiPER is a leader arm"),
            std::string::npos)
      << session.error().message;

  auto devices = client().list_devices();
  ASSERT_TRUE(devices);
  ASSERT_EQ(devices.value().size(), 1U);
  EXPECT_TRUE(devices.value()[0].control_modes.empty());
  EXPECT_EQ(device_status("leader").state, DeviceState::kRunning) << device_status("leader").fault_text;
  EXPECT_TRUE(sim_.control({{"op", "state"}})["frames_received"].empty()) << "robotd sent the leader frames";
}

}  // namespace
}  // namespace robotd::testing
