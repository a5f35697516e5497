// The PiPER driver with a leader (master) arm and with ids moved by MasterSlaveConfig offsets,
// against robotd-piper-sim over the stand-in CAN bus (--role leader, --*-id-offset).
#include <array>
#include <chrono>
#include <cmath>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "driver/piper_driver.hpp"
#include "driver_loop.hpp"
#include "piper_sim_process.hpp"

namespace robotd::piper {
namespace {

using namespace std::chrono_literals;
using driver::IoResult;
using testing::DriverLoop;
using testing::PiperSimProcess;

using testing::kPiperDeviceJoints;

nlohmann::json params(const std::string& bus_path, const nlohmann::json& extra = nlohmann::json::object()) {
  nlohmann::json params{{"can", {{"transport", "standin"}, {"path", bus_path}}}, {"feedback_timeout_ms", 100}};
  params.update(extra);
  return params;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

bool near(double a, double b) { return std::fabs(a - b) < 1e-3; }

class PiperLeaderTest : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_TRUE(driver_.configure(params(sim_.bus_path(), {{"role", "leader"}}))); }

  PiperSimProcess sim_{PiperSimProcess::unique_path("piper-leader"), {"--role", "leader"}};
  PiperDriver driver_;
};

// A person moves the leader (the sim's set_joint / set_gripper): robotd's joint states follow the
// commands it sends, and robotd sends it nothing, whatever the loop asks write() to do.
TEST_F(PiperLeaderTest, JointStatesFollowTheLeaderAndNothingIsSentToIt) {
  ASSERT_TRUE(driver_.connect());
  ASSERT_TRUE(sim_.control({{"op", "reset_counters"}})["ok"].get<bool>());
  DriverLoop loop(driver_, kPiperDeviceJoints);
  const std::array<double, 6> commanded{0.1, 0.2, -0.3, 0.1, 0.1, 0.1};
  loop.set_command(testing::position_frame(commanded, true, kPiperDeviceJoints));
  ASSERT_TRUE(sim_.control({{"op", "set_joint"}, {"joint", 2}, {"position_rad", 0.8}})["ok"].get<bool>());
  ASSERT_TRUE(sim_.control({{"op", "set_joint"}, {"joint", 3}, {"position_rad", -1.1}})["ok"].get<bool>());
  ASSERT_TRUE(sim_.control({{"op", "set_gripper"}, {"stroke_m", 0.03}})["ok"].get<bool>());
  EXPECT_TRUE(loop.wait_for([](DriverLoop& l) {
    const driver::Feedback feedback = l.feedback();
    return near(feedback.joints[1].position_rad, 0.8) && near(feedback.joints[2].position_rad, -1.1) &&
           near(feedback.joints[6].position_rad, 0.03);
  })) << "joint2 "
      << loop.feedback().joints[1].position_rad << ", gripper " << loop.feedback().joints[6].position_rad;
  ASSERT_TRUE(sim_.control({{"op", "set_joint"}, {"joint", 2}, {"position_rad", 0.4}})["ok"].get<bool>());
  EXPECT_TRUE(loop.wait_for([](DriverLoop& l) { return near(l.feedback().joints[1].position_rad, 0.4); }));
  EXPECT_EQ(loop.last_write(), IoResult::kOk);
  const nlohmann::json state = sim_.control({{"op", "state"}});
  EXPECT_TRUE(state["frames_received"].empty()) << state["frames_received"].dump();
  EXPECT_TRUE(contains(testing::diagnostic(driver_, "role"), "leader")) << testing::diagnostic(driver_, "role");
  EXPECT_EQ(testing::diagnostic(driver_, "leader_mode"), "can command, move j, 0xAD");
  EXPECT_NEAR(driver_.call("master_commands", nlohmann::json::object()).value()["joints_rad"][1].get<double>(), 0.4,
              1e-3);
}

TEST_F(PiperLeaderTest, ALeaderThatStopsSendingIsALostLinkAndRecoverWaitsForIt) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kPiperDeviceJoints);
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kOk; }));
  const auto silent_until = std::chrono::steady_clock::now() + 1500ms;
  ASSERT_TRUE(sim_.control({{"op", "silence"}, {"ms", 1500}})["ok"].get<bool>());
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kDisconnected; }));
  EXPECT_TRUE(contains(loop.fault_text(), "no leader joint commands (0x155-0x157)")) << loop.fault_text();
  std::this_thread::sleep_until(silent_until + 100ms);
  const auto recovered = loop.paused([&] { return driver_.recover(); });
  ASSERT_TRUE(recovered) << recovered.error().message;
  EXPECT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kOk; }));
}

// robotd commands nothing on a leader: the daemon grants no control (read_only_reason), the ops
// that move, configure or query the arm refuse, reset_zero refuses; what reads the received
// frames runs, and master_slave (the way back to a follower) goes out.
TEST_F(PiperLeaderTest, ALeaderIsReadOnlyAndRefusesWhatWouldMoveOrConfigureIt) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kPiperDeviceJoints);
  EXPECT_TRUE(contains(driver_.describe().read_only_reason, "leader arm")) << driver_.describe().read_only_reason;
  EXPECT_FALSE(driver_.describe().supports_torque);
  for (const auto& [op, args] :
       {std::pair{"enable", nlohmann::json::object()},
        std::pair{
            "end_pose",
            nlohmann::json{{"x_m", 0.2}, {"y_m", 0}, {"z_m", 0.2}, {"roll_rad", 0}, {"pitch_rad", 0}, {"yaw_rad", 0}}},
        std::pair{"set_crash_protection", nlohmann::json{{"levels", {1, 1, 1, 1, 1, 1}}}},
        std::pair{"limits", nlohmann::json::object()}}) {
    const auto refused = driver_.call(op, args);
    ASSERT_FALSE(refused) << op;
    EXPECT_EQ(refused.error().code, ErrorCode::kRefused) << op;
    EXPECT_TRUE(contains(refused.error().message, std::string(op) + ": this PiPER is a leader arm"))
        << refused.error().message;
    EXPECT_TRUE(contains(refused.error().message, "runs only state, can_fps")) << refused.error().message;
  }
  const std::array<int, 1> joints{0};
  const auto zeroed = driver_.reset_zero(joints);
  ASSERT_FALSE(zeroed);
  EXPECT_TRUE(contains(zeroed.error().message, "leader arm")) << zeroed.error().message;
  EXPECT_TRUE(driver_.call("state", nlohmann::json::object()));
  EXPECT_TRUE(driver_.call("can_fps", nlohmann::json::object()));
  EXPECT_TRUE(driver_.call("master_commands", nlohmann::json::object()).value()["seen"].get<bool>());
  const auto to_follower = driver_.call("master_slave", {{"role", "slave"}});
  ASSERT_TRUE(to_follower) << to_follower.error().message;
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& /*l*/) {
    return sim_.control({{"op", "state"}})["master_slave"].get<int>() == 0xFC;
  }));
  // The arm takes it at its next start: a leader device then sees a follower and loses its link.
  EXPECT_EQ(sim_.control({{"op", "state"}})["role"], "leader");
  EXPECT_EQ(sim_.control({{"op", "restart"}})["role"], "follower");
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kDisconnected; }));
  const auto reconnect = loop.paused([&] { return driver_.recover(); });
  ASSERT_FALSE(reconnect);
  EXPECT_TRUE(contains(reconnect.error().message, "not set as leader")) << reconnect.error().message;
}

TEST(PiperLeaderConnect, ALeaderDeviceOnAFollowerSaysTheArmIsNotSetAsLeader) {
  PiperSimProcess follower{PiperSimProcess::unique_path("piper-follower")};
  PiperDriver driver;
  ASSERT_TRUE(driver.configure(params(follower.bus_path(), {{"role", "leader"}})));
  const auto connected = driver.connect();
  ASSERT_FALSE(connected);
  EXPECT_EQ(connected.error().code, ErrorCode::kNotAvailable);
  EXPECT_TRUE(contains(connected.error().message, "follower's feedback")) << connected.error().message;
  EXPECT_TRUE(contains(connected.error().message, "not set as leader")) << connected.error().message;
}

TEST_F(PiperLeaderTest, AFollowerDeviceOnALeaderSaysTheArmIsSetAsLeader) {
  PiperDriver follower;
  ASSERT_TRUE(follower.configure(params(sim_.bus_path())));
  const auto connected = follower.connect();
  ASSERT_FALSE(connected);
  EXPECT_TRUE(contains(connected.error().message, "it is set as leader")) << connected.error().message;
  EXPECT_TRUE(contains(connected.error().message, "params.role \"leader\"")) << connected.error().message;
}

TEST(PiperLeaderConfig, RoleAndIdOffsetsAreValidated) {
  PiperDriver driver;
  const auto configured = driver.configure(
      params("/tmp/x.sock", {{"role", "master"}, {"feedback_id_offset", 5}, {"control_id_offset", 272}}));
  ASSERT_FALSE(configured);
  const std::string& message = configured.error().message;
  EXPECT_TRUE(contains(message, "role")) << message;
  EXPECT_TRUE(contains(message, "leader")) << message;
  EXPECT_TRUE(contains(message, "feedback_id_offset: expected 0, 16 (0x10) or 32 (0x20)")) << message;
  EXPECT_TRUE(contains(message, "got 5")) << message;
  EXPECT_TRUE(contains(message, "got 272")) << message;
}

// An arm whose MasterSlaveConfig moved its ids by 0x10: with the offsets in its params the driver
// drives it (its 0x15x commands go out at 0x16x) and reads its feedback (0x2Bx).
TEST(PiperIdOffsets, ADriverWithTheArmsOffsetsDrivesIt) {
  PiperSimProcess sim{PiperSimProcess::unique_path("piper-offset"),
                      {"--feedback-id-offset", "16", "--control-id-offset", "16"}};
  PiperDriver driver;
  ASSERT_TRUE(driver.configure(params(sim.bus_path(), {{"feedback_id_offset", 16}, {"control_id_offset", 16}})));
  ASSERT_TRUE(driver.connect());
  DriverLoop loop(driver, kPiperDeviceJoints);
  const std::array<double, 6> target{0.0, 0.5, -0.4, 0.0, 0.0, 0.0};
  loop.set_command(testing::position_frame(target, true, kPiperDeviceJoints));
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& l) { return testing::joints_near(l.feedback(), target, 0.002); }))
      << "joint2 " << loop.feedback().joints[1].position_rad;
  const nlohmann::json state = sim.control({{"op", "state"}});
  EXPECT_NEAR(state["joints"][1]["position_rad"].get<double>(), 0.5, 0.002) << state.dump();
  EXPECT_GT(state["frames_received"].value("0x166", 0), 0) << state["frames_received"].dump();
  EXPECT_EQ(state["frames_received"].value("0x156", 0), 0) << state["frames_received"].dump();
}

TEST(PiperIdOffsets, ADriverWithoutTheOffsetSaysWhichOffsetTheArmUses) {
  PiperSimProcess sim{PiperSimProcess::unique_path("piper-offset"), {"--feedback-id-offset", "16"}};
  PiperDriver driver;
  ASSERT_TRUE(driver.configure(params(sim.bus_path())));
  const auto connected = driver.connect();
  ASSERT_FALSE(connected);
  EXPECT_TRUE(contains(connected.error().message, "0x2B1-0x2B8, moved by a feedback offset 0x10"))
      << connected.error().message;
  EXPECT_TRUE(contains(connected.error().message, "set params.feedback_id_offset to 16 (0x10)"))
      << connected.error().message;
}

TEST(PiperIdOffsets, ALeaderDeviceWithoutTheLinkageOffsetSaysWhichOffsetTheLeaderUses) {
  PiperSimProcess sim{PiperSimProcess::unique_path("piper-offset"), {"--role", "leader", "--control-id-offset", "32"}};
  PiperDriver driver;
  ASSERT_TRUE(driver.configure(params(sim.bus_path(), {{"role", "leader"}})));
  const auto connected = driver.connect();
  ASSERT_FALSE(connected);
  EXPECT_TRUE(contains(connected.error().message, "0x170-0x17F")) << connected.error().message;
  EXPECT_TRUE(contains(connected.error().message, "set params.control_id_offset to 32 (0x20)"))
      << connected.error().message;
  PiperDriver with_offset;
  ASSERT_TRUE(with_offset.configure(params(sim.bus_path(), {{"role", "leader"}, {"control_id_offset", 32}})));
  ASSERT_TRUE(with_offset.connect());
}

}  // namespace
}  // namespace robotd::piper
