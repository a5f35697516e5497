// End to end: starting and stopping robotd (issue test 7), and what it says when it cannot start.
#include <chrono>
#include <cmath>
#include <mutex>
#include <thread>

#include <gtest/gtest.h>

#include "robotd_fixture.hpp"

namespace robotd::testing {
namespace {

using namespace std::chrono_literals;

class LifecycleTest : public RobotdTest {};

// Issue test 7: SIGTERM mid-motion: sessions end, the arm is brought to its safe stop (DAMPING),
// the driver disconnects, robotd exits 0.
TEST_F(LifecycleTest, SigtermBringsTheArmToItsSafeStopAndExitsZero) {
  start_robotd(sim_arm_config(domain_.id(), nullptr, {{"shutdown_behavior", "DAMPING"}, {"shutdown_ms", 300}}));
  std::mutex mutex;
  std::vector<DeviceStatus> statuses;
  std::vector<SessionStatus> session_statuses;
  JointState last_joint_state;
  auto status_subscription = client().on_device_status([&](const DeviceStatus& s) {
    const std::lock_guard lock(mutex);
    statuses.push_back(s);
  });
  auto session_subscription = client().on_session_status([&](const SessionStatus& s) {
    const std::lock_guard lock(mutex);
    session_statuses.push_back(s);
  });
  auto joint_subscription = client().on_joint_states([&](const JointState& s) {
    const std::lock_guard lock(mutex);
    last_joint_state = s;
  });

  SessionRequest request;
  request.device = "arm";
  request.timeout = 5s;
  auto session = client().request_control(request);
  ASSERT_TRUE(session) << session.error().message;
  for (int i = 0; i < 30; ++i) {  // start a fast move and stop robotd in the middle of it
    ASSERT_TRUE(session.value().send_positions({2.0F, 2.0F, 2.0F, 2.0F, 2.0F, 2.0F}));
    std::this_thread::sleep_for(10ms);
  }

  const auto exit_status = robotd_->terminate(10s);
  ASSERT_TRUE(exit_status.has_value()) << "robotd did not exit after SIGTERM";
  EXPECT_EQ(*exit_status, 0) << robotd_->log();
  std::this_thread::sleep_for(100ms);

  const std::lock_guard lock(mutex);
  ASSERT_FALSE(statuses.empty());
  const DeviceStatus& final_status = statuses.back();
  EXPECT_EQ(final_status.state, DeviceState::kStopped);
  bool motors_disabled = false;
  for (const auto& value : final_status.driver_values) {
    if (value.key == "motors") motors_disabled = value.value == "disabled";
  }
  EXPECT_TRUE(motors_disabled) << "the driver was not disconnected before exit";
  ASSERT_FALSE(session_statuses.empty());
  EXPECT_TRUE(session_statuses.back().sessions.empty()) << "robotd exited with a session still listed";
  // The safe stop (damping, 300 ms) brought the moving arm to rest before the driver let go.
  for (const double v : last_joint_state.velocity) EXPECT_LT(std::fabs(v), 0.3);
  const std::string log = robotd_->log();
  EXPECT_NE(log.find("ended by shutdown"), std::string::npos) << log;
  EXPECT_NE(log.find("safe stop"), std::string::npos) << log;
}

TEST_F(LifecycleTest, InvalidConfigIsRefusedWithKeyPathsAndExitCode2) {
  nlohmann::json config = sim_arm_config(domain_.id());
  config["devices"][0]["rate_hz"] = 0;
  config["devices"][0]["realtime"] = "sometimes";
  config["daemon"]["colour"] = "blue";
  RobotdProcess robotd(config);
  const std::optional<int> status = robotd.wait_for_exit();
  ASSERT_TRUE(status.has_value());
  EXPECT_EQ(*status, 2);
  const std::string log = robotd.log();
  EXPECT_NE(log.find("devices[0].rate_hz: expected an integer in 1..10000, got 0"), std::string::npos) << log;
  EXPECT_NE(log.find("devices[0].realtime: expected one of"), std::string::npos) << log;
  EXPECT_NE(log.find("daemon.colour: unknown key"), std::string::npos) << log;
}

TEST_F(LifecycleTest, InvalidDriverParamsNameTheDeviceParamsPath) {
  nlohmann::json config = sim_arm_config(domain_.id());
  config["devices"][0]["params"]["joint_defaults"]["inertia_kg_m2"] = -1;
  RobotdProcess robotd(config);
  const std::optional<int> status = robotd.wait_for_exit();
  ASSERT_TRUE(status.has_value());
  EXPECT_EQ(*status, 1);
  EXPECT_NE(robotd.log().find("devices[0].params: joint_defaults.inertia_kg_m2"), std::string::npos) << robotd.log();
}

TEST_F(LifecycleTest, MissingRequiredPluginStopsRobotdSayingWhereItLooked) {
  nlohmann::json config = sim_arm_config(domain_.id());
  config["devices"][0]["driver"] = "nosuchdriver";
  RobotdProcess robotd(config);
  const std::optional<int> status = robotd.wait_for_exit();
  ASSERT_TRUE(status.has_value());
  EXPECT_EQ(*status, 1);
  const std::string log = robotd.log();
  EXPECT_NE(log.find("driver plugin 'nosuchdriver' not found: looked for librobotd_driver_nosuchdriver.so in"),
            std::string::npos)
      << log;
}

TEST_F(LifecycleTest, OptionalDeviceThatFailsLeavesTheOthersRunning) {
  nlohmann::json config = sim_arm_config(domain_.id());
  nlohmann::json broken = config["devices"][0];
  broken["name"] = "gripper";
  broken["driver"] = "nosuchdriver";
  broken["required"] = false;
  config["devices"].push_back(broken);
  start_robotd(config);
  auto devices = client().list_devices();
  ASSERT_TRUE(devices);
  ASSERT_EQ(devices.value().size(), 1U);
  EXPECT_EQ(devices.value()[0].name, "arm");
  EXPECT_NE(robotd_->log().find("continuing without device 'gripper'"), std::string::npos);
}

TEST_F(LifecycleTest, ListDevicesDescribesWhatEachDeviceSupports) {
  nlohmann::json config = sim_arm_config(domain_.id());
  config["devices"][0]["params"]["kinematic_model"] = "parol6";
  start_robotd(config);
  auto devices = client().list_devices();
  ASSERT_TRUE(devices);
  ASSERT_EQ(devices.value().size(), 1U);
  const DeviceInfo& arm = devices.value()[0];
  EXPECT_EQ(arm.driver, "sim");
  EXPECT_EQ(arm.kinematic_model, "parol6");
  EXPECT_EQ(arm.joint_names.size(), 6U);
  EXPECT_EQ(arm.control_modes, (std::vector<std::string>{"POSITION", "TORQUE", "MIXED"}));
  EXPECT_EQ(arm.behavior_map, (std::vector<std::int32_t>{0, 1, 2}));
  EXPECT_EQ(arm.position_max[0], 2.5);
  bool has_recover = false;
  for (const auto& op : arm.ops) has_recover = has_recover || op.rfind("recover:", 0) == 0;
  EXPECT_TRUE(has_recover);
}

TEST_F(LifecycleTest, JointLimitOverridesNarrowTheDriverLimitsButMayNotWidenThem) {
  start_robotd(
      sim_arm_config(domain_.id(), nullptr,
                     {{"joint_limits", {{"joint2", {{"position_max_rad", 1.0}, {"velocity_max_rad_s", 0.5}}}}}}));
  auto devices = client().list_devices();
  ASSERT_TRUE(devices);
  EXPECT_EQ(devices.value()[0].position_max[1], 1.0);
  EXPECT_EQ(devices.value()[0].velocity_max[1], 0.5);
  EXPECT_EQ(devices.value()[0].position_max[0], 2.5);

  nlohmann::json widening = sim_arm_config(domain_.id());
  widening["devices"][0]["joint_limits"] = {{"joint2", {{"effort_max_nm", 1000}}}};
  robotd_->terminate();
  RobotdProcess refused(widening);
  const std::optional<int> status = refused.wait_for_exit();
  ASSERT_TRUE(status.has_value());
  EXPECT_EQ(*status, 1);
  EXPECT_NE(refused.log().find("devices[0].joint_limits.joint2.effort_max_nm: 1000 is beyond the driver's limit 40"),
            std::string::npos)
      << refused.log();
}

TEST_F(LifecycleTest, LoopTimingReportsTheWindowAndItsSamplesAndResets) {
  start_robotd();
  // The window fills at 1 kHz from the loop's start, which a slow (sanitized) start-up delays.
  for (const auto give_up = std::chrono::steady_clock::now() + 10s; std::chrono::steady_clock::now() < give_up;) {
    const auto filling = client().device_call("arm", "loop_timing");
    if (filling && nlohmann::json::parse(filling.value())["window_ticks"].get<int>() > 250) break;
    std::this_thread::sleep_for(50ms);
  }
  auto timing = client().device_call("arm", "loop_timing", R"({"samples": true, "reset": true})");
  ASSERT_TRUE(timing) << timing.error().message;
  const auto first = nlohmann::json::parse(timing.value());
  EXPECT_GT(first["window_ticks"].get<int>(), 200);
  EXPECT_EQ(first["wake_latency_ns"].size(), first["window_ticks"].get<std::size_t>());
  EXPECT_GE(first["wake_latency_us"]["p999"].get<double>(), first["wake_latency_us"]["p99"].get<double>());
  EXPECT_NEAR(first["period_us"]["p50"].get<double>(), 1000.0, 50.0);
  EXPECT_GT(first["joint_states_published"].get<int>(), 100);

  const auto after_reset = nlohmann::json::parse(client().device_call("arm", "loop_timing").value());
  EXPECT_LT(after_reset["window_ticks"].get<int>(), first["window_ticks"].get<int>()) << "reset must empty the window";
  EXPECT_FALSE(after_reset.contains("wake_latency_ns"));
  EXPECT_FALSE(client().device_call("arm", "loop_timing", R"({"samples": "yes"})"));
}

// The example program of clients/cpp/examples runs as documented against the default arm.
TEST_F(LifecycleTest, ExampleProgramMovesTheArmAndReleases) {
  start_robotd();
  ChildProcess example("/usr/bin/env", {"ROBOTD_DOMAIN_ID=" + std::to_string(domain_.id()), EXAMPLE_MOVE_ARM});
  std::vector<std::string> lines;
  while (auto line = example.read_line(15s)) lines.push_back(*line);
  ASSERT_GE(lines.size(), 8U) << "the example printed too little";
  EXPECT_EQ(lines.front().rfind("session ", 0), 0U) << lines.front();
  EXPECT_NE(lines[1].find("+0.000 rad -> +0.500 rad"), std::string::npos) << lines[1];
  EXPECT_NE(lines.back().find("released 6 motor(s) of 'arm'"), std::string::npos) << lines.back();
}

}  // namespace
}  // namespace robotd::testing
