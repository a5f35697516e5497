// The RealMan driver against robotd-realman-sim over real TCP and UDP sockets on loopback, and a
// 1 kHz thread that calls read()/write() the way robotd's loop does.
#include "driver/realman_driver.hpp"

#include <chrono>
#include <cmath>
#include <fstream>
#include <future>
#include <iostream>
#include <iterator>
#include <thread>

#include <gtest/gtest.h>

#include "driver/realman_params.hpp"
#include "driver_loop.hpp"
#include "maintenance_abort.hpp"
#include "realman_sim_process.hpp"
#include "robotd/driver/json_reader.hpp"
#include "unanswered_port.hpp"

namespace robotd::realman {
namespace {

using namespace std::chrono_literals;
using driver::IoResult;
using testing::diagnostic;
using testing::DriverLoop;
using testing::joints_near;
using testing::position_frame;
using testing::RealmanSimProcess;

constexpr std::size_t kDof = 6;

nlohmann::json driver_params(std::uint16_t port, const nlohmann::json& extra = nlohmann::json::object()) {
  nlohmann::json params{{"model", "RM65"},
                        {"host", "127.0.0.1"},
                        {"port", port},
                        {"connect_timeout_ms", 1000},
                        {"request_timeout_ms", 500},
                        {"push", {{"ip", "127.0.0.1"}, {"port", 0}}}};
  params.update(extra);
  return params;
}

class RealmanDriverTest : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_TRUE(driver_.configure(driver_params(sim_.port()))); }

  nlohmann::json sim_state() const { return sim_.control({{"op", "state"}}); }

  RealmanSimProcess sim_{{"--quiet"}};
  RealmanDriver driver_;
};

TEST(RealmanConfigs, ShippedExamplesParse) {
  for (const char* file : {"config/examples/realman.json", "config/examples/realman-sim.json", "config/robotd.json"}) {
    std::ifstream in(std::string(ROBOTD_SOURCE_DIR) + "/" + file);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::vector<std::string> errors;
    const auto config = parse_json_with_comments(text, file, errors);
    ASSERT_TRUE(config) << join_errors(errors);
    int realman_devices = 0;
    for (const auto& device : config->at("devices")) {
      if (device.at("driver") != "realman") continue;
      ++realman_devices;
      const auto params = parse_realman_params(device.at("params"));
      EXPECT_TRUE(params) << file << ": " << params.error().message;
    }
    EXPECT_EQ(realman_devices, 1) << file;
  }
}

TEST(RealmanParams, BadParamsAreNamedWithWhatIsExpected) {
  RealmanDriver driver;
  const auto configured = driver.configure({{"model", "RM99"},
                                            {"port", 0},
                                            {"command_rate_hz", 50},
                                            {"push", {{"cycle", 0}, {"speed_unit", "rpm"}}},
                                            {"radio", 10},
                                            {"colour", "red"}});
  ASSERT_FALSE(configured);
  const std::string& message = configured.error().message;
  for (const char* key : {"model", "RM65", "port", "command_rate_hz", "at least 100 Hz", "push.cycle",
                          "push.speed_unit", "radio", "colour"}) {
    EXPECT_NE(message.find(key), std::string::npos) << key << " in: " << message;
  }
  const auto seventh = driver.configure({{"model", "RM65"}, {"joints", {{"joint7", {{"velocity_max_rad_s", 1}}}}}});
  ASSERT_FALSE(seventh);
  EXPECT_NE(seventh.error().message.find("expected joint1 … joint6"), std::string::npos) << seventh.error().message;
}

TEST(RealmanParams, DescribeTellsTheModelsJointsAndLimits) {
  RealmanDriver driver;
  ASSERT_TRUE(driver.configure({{"model", "GEN72"}, {"command_rate_hz", 250}}));
  driver::DeviceDescription description = driver.describe();
  EXPECT_EQ(description.model, "RealMan GEN72");
  EXPECT_EQ(description.kinematic_model, "gen72");
  EXPECT_DOUBLE_EQ(description.native_rate_hz, 250);
  ASSERT_EQ(description.joints.size(), 7U);
  EXPECT_NEAR(description.joints[3].limits.position_max_rad, 55.0 * M_PI / 180, 1e-6);  // J4 −170…+55°
  EXPECT_FALSE(description.supports_torque);
  EXPECT_FALSE(description.supports_damping);
  EXPECT_TRUE(description.has_end_pose);

  ASSERT_TRUE(driver.configure({{"model", "ECO65"}}));
  description = driver.describe();
  EXPECT_EQ(description.kinematic_model, "") << "ECO65's published DH table is inconsistent";
}

// The ops that act on the arm robotd drives need free motors: power and enable, planned motion,
// the trajectory's state and error clearing. The gripper, the hand and the queries do not.
TEST(RealmanParams, TheOpsThatActOnTheArmNeedFreeMotors) {
  RealmanDriver driver;
  ASSERT_TRUE(driver.configure({{"model", "RM65"}}));
  EXPECT_EQ(
      testing::ops_needing_free_motors(driver.describe()),
      (std::vector<std::string>{"movej", "movel", "movej_p", "set_arm_stop", "set_arm_slow_stop", "set_arm_pause",
                                "set_arm_continue", "set_delete_current_trajectory", "set_arm_delete_trajectory",
                                "set_joint_en_state", "set_joint_clear_err", "clear_system_err", "set_arm_power"}));
}

TEST(RealmanConnect, NothingListeningIsNotAvailableAndNamesTheAddress) {
  const std::uint16_t port = RealmanSimProcess::free_port();
  RealmanDriver driver;
  ASSERT_TRUE(driver.configure(driver_params(port)));
  const auto connected = driver.connect();
  ASSERT_FALSE(connected);
  EXPECT_EQ(connected.error().code, ErrorCode::kNotAvailable);
  EXPECT_NE(connected.error().message.find("127.0.0.1:" + std::to_string(port)), std::string::npos)
      << connected.error().message;
  driver::Feedback feedback;
  driver::FaultInfo fault;
  EXPECT_EQ(driver.read(feedback, fault), IoResult::kDisconnected);
  EXPECT_NE(std::string(fault.text.data()).find("not connected"), std::string::npos) << fault.text.data();

  // Ops check their arguments with or without the controller, then need it.
  const auto bad = driver.call("movej", {{"joints_rad", {0, 0, 0}}});
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(bad.error().message.find("joints_rad"), std::string::npos) << bad.error().message;
  const auto good = driver.call("movej", {{"joints_rad", {0, 0, 0, 0, 0, 0}}, {"block", false}});
  ASSERT_FALSE(good);
  EXPECT_EQ(good.error().code, ErrorCode::kRefused);
  EXPECT_NE(good.error().message.find("movej: not connected to the RealMan controller at 127.0.0.1:"),
            std::string::npos)
      << good.error().message;
}

TEST(RealmanConnect, AControllerOfAnotherModelIsRefusedWithTheFix) {
  RealmanSimProcess rm75({"--quiet", "--model", "RM75-B"});
  RealmanDriver driver;
  ASSERT_TRUE(driver.configure(driver_params(rm75.port())));
  const auto connected = driver.connect();
  ASSERT_FALSE(connected);
  EXPECT_NE(connected.error().message.find("RM75-B"), std::string::npos) << connected.error().message;
  EXPECT_NE(connected.error().message.find(R"(set "model": "RM75")"), std::string::npos) << connected.error().message;
}

TEST_F(RealmanDriverTest, ConnectReadsTheModelSetsUpThePushAndFeedbackFlows) {
  ASSERT_TRUE(driver_.connect()) << "connect";
  EXPECT_EQ(diagnostic(driver_, "product"), "RM65-B");
  const nlohmann::json state = sim_state();
  ASSERT_TRUE(state["ok"].get<bool>()) << state.dump();
  EXPECT_EQ(state["push"]["ip"], "127.0.0.1") << state.dump();
  EXPECT_NE(state["push"]["port"].get<int>(), 8089) << "the driver's own port, told to the controller";

  DriverLoop loop(driver_, kDof);
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.feedback().joint_count == kDof; }));
  const driver::Feedback feedback = loop.feedback();
  EXPECT_TRUE(feedback.has_end_pose);
  EXPECT_GT(feedback.end_pose.position_m[2], 0.1) << "the RM65's flange is above its base";
  // Nothing owned: nothing streamed.
  std::this_thread::sleep_for(200ms);
  EXPECT_EQ(sim_state()["pass_through"]["frames"].get<int>(), 0) << sim_state().dump();
}

// The rate is checked as a ceiling: a loaded host may send fewer frames, never more (a late
// period is skipped, not caught up). How closely J1 follows is printed, not asserted.
TEST_F(RealmanDriverTest, StreamedPositionsMoveTheArmThroughMovejCanfdNoFasterThanTheConfiguredRate) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kDof);
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.feedback().joint_count == kDof; }));
  const driver::Feedback start = loop.feedback();
  const auto stream_start = std::chrono::steady_clock::now();
  std::array<double, kDof> target{};
  for (std::size_t j = 0; j < kDof; ++j) target[j] = start.joints[j].position_rad;
  // A 1 kHz ramp like robotd's limiter makes: 0.3 rad on J1 over 1 s.
  double worst_lag = 0;
  const auto t0 = std::chrono::steady_clock::now();
  const double j1_start = target[0];
  for (auto next = t0; std::chrono::steady_clock::now() - t0 < 1s; next += 1ms) {
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    target[0] = j1_start + 0.3 * std::min(t, 1.0);
    loop.set_command(position_frame(target));
    if (t > 0.1) worst_lag = std::max(worst_lag, target[0] - loop.feedback().joints[0].position_rad);
    std::this_thread::sleep_until(next);
  }
  target[0] = j1_start + 0.3;
  loop.set_command(position_frame(target));
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& l) { return joints_near(l.feedback(), target, 1e-3); }))
      << loop.feedback().joints[0].position_rad;
  const nlohmann::json state = sim_state();
  const double streamed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - stream_start).count();
  const nlohmann::json& pass = state["pass_through"];
  std::cout << "[ measured ] J1 lag behind a 0.3 rad/s ramp: worst " << worst_lag * 1000 << " mrad (one 5 ms period "
            << "plus one push cycle is about 3 mrad); movej_canfd over " << streamed_s << " s: " << pass.dump() << "\n";
  EXPECT_EQ(pass["ignored"].get<int>(), 0) << pass.dump();
  EXPECT_TRUE(pass["follow"].get<bool>()) << pass.dump();
  EXPECT_GT(pass["frames"].get<int>(), 0) << pass.dump();
  EXPECT_LE(pass["frames"].get<int>(), static_cast<int>(200 * streamed_s) + 2) << "200 Hz configured; " << pass.dump();
  EXPECT_EQ(loop.last_write(), IoResult::kOk);
}

TEST_F(RealmanDriverTest, AFarTargetIsApproachedWithinThePassThroughStepLimit) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kDof);
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.feedback().joint_count == kDof; }));
  std::array<double, kDof> target{};
  for (std::size_t j = 0; j < kDof; ++j) target[j] = loop.feedback().joints[j].position_rad;
  target[1] += 1.0;  // a 1 rad step at once: the controller would ignore it as one frame
  loop.set_command(position_frame(target));
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& l) { return joints_near(l.feedback(), target, 1e-3); }, 5s));
  EXPECT_EQ(sim_state()["pass_through"]["ignored"].get<int>(), 0) << sim_state().dump();
  const std::string frames = diagnostic(driver_, "stream_frames");
  EXPECT_EQ(frames.find("(0 limited"), std::string::npos) << frames;
}

TEST_F(RealmanDriverTest, EstopSendsTheQuickStopAndAReleaseMidMotionTheSlowStop) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kDof);
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.feedback().joint_count == kDof; }));
  std::array<double, kDof> target{};
  for (std::size_t j = 0; j < kDof; ++j) target[j] = loop.feedback().joints[j].position_rad;
  target[0] += 0.5;
  loop.set_command(position_frame(target));
  ASSERT_TRUE(loop.wait_for([&](DriverLoop& l) { return l.feedback().joints[0].position_rad > target[0] - 0.45; }));
  driver::CommandFrame stop = position_frame(target);
  stop.estop = true;
  loop.set_command(stop);
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& /*l*/) { return sim_state()["commands"].value("set_arm_stop", 0) == 1; }))
      << sim_state().dump();
  const int frames_at_stop = sim_state()["pass_through"]["frames"].get<int>();
  std::this_thread::sleep_for(100ms);
  EXPECT_EQ(sim_state()["pass_through"]["frames"].get<int>(), frames_at_stop) << "streamed during the e-stop";

  loop.set_command(position_frame(target));  // reset: streaming resumes from where the arm is
  ASSERT_TRUE(loop.wait_for([&](DriverLoop& l) { return joints_near(l.feedback(), target, 1e-3); }));
  ASSERT_TRUE(loop.wait_for([&](DriverLoop& l) { return joints_near(l.feedback(), target, 1e-3); }));
  std::this_thread::sleep_for(100ms);
  loop.set_command(position_frame(target, /*owned=*/false));  // released at rest: nothing to stop
  std::this_thread::sleep_for(100ms);
  EXPECT_EQ(sim_state()["commands"].value("set_arm_slow_stop", 0), 0) << sim_state().dump();

  target[0] -= 0.8;  // a new session, released on the way
  loop.set_command(position_frame(target));
  ASSERT_TRUE(loop.wait_for([&](DriverLoop& l) { return l.feedback().joints[0].position_rad < target[0] + 0.6; }));
  loop.set_command(position_frame(target, /*owned=*/false));
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& /*l*/) {
    return sim_state()["commands"].value("set_arm_slow_stop", 0) == 1;
  })) << sim_state().dump();
  const int frames_at_release = sim_state()["pass_through"]["frames"].get<int>();
  const double at_release = loop.feedback().joints[0].position_rad;
  // A planned move right away waits for the slow stop to end instead of being cut short by it.
  const auto moved = driver_.call("movej", {{"joints_rad", {0.2, 0, 0, 0, 0, 0}}, {"v", 80}});
  ASSERT_TRUE(moved) << moved.error().message;
  EXPECT_TRUE(moved.value()["completed"].get<bool>()) << moved.value().dump();
  EXPECT_EQ(sim_state()["pass_through"]["frames"].get<int>(), frames_at_release) << "streamed after the release";
  EXPECT_GT(std::fabs(at_release - 0.2), 0.05) << "the planned move had nothing to do";
}

TEST_F(RealmanDriverTest, ControllerErrorsAreFaultsInTheControllersWordsAndRecoverClearsThem) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kDof);
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.feedback().joint_count == kDof; }));
  ASSERT_TRUE(sim_.control({{"op", "raise_error"}, {"code", 0x100D}})["ok"].get<bool>());
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_write() == IoResult::kFault; }));
  EXPECT_NE(loop.fault_text().find("0x100D collision detected"), std::string::npos) << loop.fault_text();

  ASSERT_TRUE(sim_.control({{"op", "joint_error"}, {"joint", 3}, {"bits", 0x0008}})["ok"].get<bool>());
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.fault_text().find("joint 3") != std::string::npos; }))
      << loop.fault_text();
  EXPECT_NE(loop.fault_text().find("over-temperature"), std::string::npos) << loop.fault_text();

  const auto recovered = loop.paused([&] { return driver_.recover(); });
  EXPECT_TRUE(recovered) << recovered.error().message;
  EXPECT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_write() == IoResult::kOk; }));
  const nlohmann::json commands = sim_state()["commands"];
  EXPECT_EQ(commands.value("clear_system_err", 0), 1) << commands.dump();
  EXPECT_EQ(commands.value("set_joint_clear_err", 0), 1) << commands.dump();
}

TEST_F(RealmanDriverTest, PlannedMovesBlockUntilTheArmArrivesWithoutHoldingUpTheLoop) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kDof);
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.feedback().joint_count == kDof; }));
  const std::array<double, kDof> goal{0.3, -0.2, 0.4, 0.1, 0.5, -0.3};
  const auto t0 = std::chrono::steady_clock::now();
  auto moved = std::async(std::launch::async, [&] {
    return driver_.call("movej", {{"joints_rad", goal}, {"v", 50}, {"block", true}, {"timeout_s", 10}});
  });
  // While the call waits, the loop keeps reading fresh feedback.
  const double first = loop.feedback().joints[4].position_rad;
  EXPECT_TRUE(
      loop.wait_for([&](DriverLoop& l) { return std::fabs(l.feedback().joints[4].position_rad - first) > 0.05; }, 3s));
  const auto result = moved.get();
  ASSERT_TRUE(result) << result.error().message;
  EXPECT_TRUE(result.value()["completed"].get<bool>()) << result.value().dump();
  const double took_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_GT(took_s, 0.05);
  EXPECT_TRUE(joints_near(loop.feedback(), goal, 2e-3)) << loop.feedback().joints[4].position_rad;
}

TEST_F(RealmanDriverTest, OpsCheckTheirArgumentsBeforeSendingAnything) {
  ASSERT_TRUE(driver_.connect());
  const int requests_before = sim_state()["requests"].get<int>();
  const auto out_of_range = driver_.call("movej", {{"joints_rad", {0, 0, 3.0, 0, 0, 0}}});
  ASSERT_FALSE(out_of_range);
  EXPECT_NE(out_of_range.error().message.find("joint3 = 3 rad is outside its range"), std::string::npos)
      << out_of_range.error().message;
  const auto short_list = driver_.call("movej", {{"joints_rad", {0, 0}}});
  ASSERT_FALSE(short_list);
  EXPECT_NE(short_list.error().message.find("expected 6 angles, got 2"), std::string::npos)
      << short_list.error().message;
  const auto slow_gripper = driver_.call("set_gripper_pick", {{"speed", 0}, {"force", 200}});
  ASSERT_FALSE(slow_gripper);
  EXPECT_NE(slow_gripper.error().message.find("1..1000"), std::string::npos) << slow_gripper.error().message;
  const auto bad_hand = driver_.call("set_hand_angle", {{"angles", {-2, 0, 0, 0, 0, 0}}});
  ASSERT_FALSE(bad_hand);
  EXPECT_NE(bad_hand.error().message.find("-1"), std::string::npos) << bad_hand.error().message;
  const auto huge_angle = driver_.call("set_hand_angle", {{"angles", {0, 0, 3e28, 0, 0, 0}}});  // beyond an int
  ASSERT_FALSE(huge_angle);
  EXPECT_NE(huge_angle.error().message.find("angles"), std::string::npos) << huge_angle.error().message;
  const auto connected_block =
      driver_.call("movej", {{"joints_rad", {0, 0, 0, 0, 0, 0}}, {"trajectory_connect", true}});
  ASSERT_FALSE(connected_block);
  EXPECT_NE(connected_block.error().message.find("block needs trajectory_connect false"), std::string::npos);
  const auto unknown = driver_.call("fly", nlohmann::json::object());
  ASSERT_FALSE(unknown);
  EXPECT_NE(unknown.error().message.find("set_gripper_pick"), std::string::npos) << unknown.error().message;
  EXPECT_EQ(sim_state()["requests"].get<int>(), requests_before) << "a refused op reached the controller";
}

TEST_F(RealmanDriverTest, GripperAndHandOpsReachTheirDevices) {
  ASSERT_TRUE(driver_.connect());
  ASSERT_TRUE(sim_.control({{"op", "place_object"}, {"opening", 400}})["ok"].get<bool>());
  const auto picked = driver_.call("set_gripper_pick", {{"speed", 1000}, {"force", 300}, {"block", true}});
  ASSERT_TRUE(picked) << picked.error().message;
  EXPECT_TRUE(picked.value()["completed"].get<bool>());
  const auto gripper = driver_.call("get_gripper_state", nlohmann::json::object());
  ASSERT_TRUE(gripper) << gripper.error().message;
  EXPECT_EQ(gripper.value()["mode"].get<int>(), 6) << gripper.value().dump();
  EXPECT_NEAR(gripper.value()["opening"].get<int>(), 400, 20) << gripper.value().dump();

  const auto posed = driver_.call("set_hand_angle", {{"angles", {100, 200, 300, 400, 500, 600}}, {"block", true}});
  ASSERT_TRUE(posed) << posed.error().message;
  const auto kept = driver_.call("set_hand_angle", {{"angles", {-1, -1, 0, -1, -1, -1}}, {"block", true}});
  ASSERT_TRUE(kept) << kept.error().message;
  const nlohmann::json hand = sim_state()["hand"];
  EXPECT_EQ(hand["angles"], nlohmann::json({100, 200, 0, 400, 500, 600})) << hand.dump();
  const auto speed = driver_.call("set_hand_speed", {{"speed", 500}});
  EXPECT_TRUE(speed) << speed.error().message;
}

TEST_F(RealmanDriverTest, QueriesAnswerInRobotdsUnits) {
  ASSERT_TRUE(sim_.control({{"op", "set_joints"}, {"joints_rad", {0.5, 0, 0, 0, 0, 0}}})["ok"].get<bool>());
  ASSERT_TRUE(driver_.connect());
  const auto arm = driver_.call("get_current_arm_state", nlohmann::json::object());
  ASSERT_TRUE(arm) << arm.error().message;
  EXPECT_NEAR(arm.value()["joints_rad"][0].get<double>(), 0.5, 1e-4) << arm.value().dump();
  const auto all = driver_.call("get_arm_all_state", nlohmann::json::object());
  ASSERT_TRUE(all) << all.error().message;
  EXPECT_EQ(all.value()["temperature_c"].size(), kDof) << all.value().dump();
  EXPECT_LT(all.value()["temperature_c"][0].get<double>(), 100) << "°C, not 0.001 °C";
  const auto enabled = driver_.call("get_joint_en_state", nlohmann::json::object());
  ASSERT_TRUE(enabled) << enabled.error().message;
  EXPECT_TRUE(enabled.value()["enabled"][0].get<bool>()) << enabled.value().dump();
  const auto disabled = driver_.call("set_joint_en_state", {{"joint", 2}, {"enable", false}});
  ASSERT_TRUE(disabled) << disabled.error().message;
  EXPECT_FALSE(driver_.call("get_joint_en_state", nlohmann::json::object()).value()["enabled"][1].get<bool>());
}

TEST_F(RealmanDriverTest, AClosedConnectionIsALostLinkAndRecoverReconnectsWithoutAJump) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kDof);
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.feedback().joint_count == kDof; }));
  std::array<double, kDof> held{};
  for (std::size_t j = 0; j < kDof; ++j) held[j] = loop.feedback().joints[j].position_rad;
  ASSERT_TRUE(sim_.control({{"op", "disconnect"}})["ok"].get<bool>());
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kDisconnected; }));
  EXPECT_NE(loop.fault_text().find("closed the TCP connection"), std::string::npos) << loop.fault_text();
  const auto recovered = loop.paused([&] { return driver_.recover(); });
  ASSERT_TRUE(recovered) << recovered.error().message;
  EXPECT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kOk; }));
  std::this_thread::sleep_for(200ms);
  EXPECT_TRUE(joints_near(loop.feedback(), held, 1e-3)) << "the arm moved across the reconnect";
}

TEST_F(RealmanDriverTest, ASilentPushIsALostLinkThatSaysWhereItWasExpected) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kDof);
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.feedback().joint_count == kDof; }));
  ASSERT_TRUE(sim_.control({{"op", "silence"}, {"on", true}})["ok"].get<bool>());
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kDisconnected; }));
  EXPECT_NE(loop.fault_text().find("no real-time push from the controller"), std::string::npos) << loop.fault_text();
  EXPECT_NE(loop.fault_text().find("127.0.0.1:"), std::string::npos) << loop.fault_text();
  ASSERT_TRUE(sim_.control({{"op", "silence"}, {"on", false}})["ok"].get<bool>());
  const auto recovered = loop.paused([&] { return driver_.recover(); });
  EXPECT_TRUE(recovered) << recovered.error().message;
}

TEST_F(RealmanDriverTest, GarbageIsCountedAndDroppedRepliesTimeOutWithoutLosingTheLink) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kDof);
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.feedback().joint_count == kDof; }));
  ASSERT_TRUE(sim_.control({{"op", "garbage"}})["ok"].get<bool>());
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& /*l*/) { return diagnostic(driver_, "unreadable_lines") != "0"; }));
  ASSERT_TRUE(sim_.control({{"op", "drop_replies"}, {"count", 1}})["ok"].get<bool>());
  const auto dropped = driver_.call("get_joint_en_state", nlohmann::json::object());
  ASSERT_FALSE(dropped);
  EXPECT_EQ(dropped.error().code, ErrorCode::kTimeout);
  EXPECT_NE(dropped.error().message.find("no reply to get_joint_en_state"), std::string::npos)
      << dropped.error().message;
  const auto answered = driver_.call("get_joint_en_state", nlohmann::json::object());
  EXPECT_TRUE(answered) << answered.error().message;
  EXPECT_EQ(loop.last_read() == IoResult::kDisconnected, false);
}

TEST(RealmanAbort, AnAbortEndsARecoverThatWaitsForAControllerThatDoesNotAnswer) {
  const testing::UnansweredPort unanswered;
  constexpr auto kConnectTimeout = 5000ms;
  RealmanDriver driver;
  ASSERT_TRUE(driver.configure(driver_params(unanswered.port(), {{"connect_timeout_ms", kConnectTimeout.count()}})));
  const auto aborted = testing::abort_during(
      driver, [&] { return driver.recover(); }, 200ms);
  ASSERT_FALSE(aborted.returned_before_abort);
  ASSERT_FALSE(aborted.result);
  EXPECT_EQ(aborted.result.error().code, ErrorCode::kRefused);
  EXPECT_EQ(aborted.result.error().message,
            "aborted: an e-stop or shutdown pre-empted recover (connecting to 127.0.0.1:" +
                std::to_string(unanswered.port()) + ")");
  EXPECT_LT(aborted.abort_to_return, kConnectTimeout / 5);
  testing::print_abort_figure("realman recover, connecting to a controller that does not answer", aborted,
                              kConnectTimeout);
}

TEST_F(RealmanDriverTest, AnAbortEndsARecoverWaitingForTheControllerAndTheNextRecoverWorks) {
  constexpr auto kConnectTimeout = 5000ms;
  constexpr auto kRequestTimeout = 3000ms;
  RealmanDriver driver;
  ASSERT_TRUE(driver.configure(driver_params(sim_.port(), {{"connect_timeout_ms", kConnectTimeout.count()},
                                                           {"request_timeout_ms", kRequestTimeout.count()}})));
  ASSERT_TRUE(driver.connect());
  DriverLoop loop(driver, kDof);
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.feedback().joint_count == kDof; }));

  // Every reply dropped: recover waits for its clear_system_err (request_timeout_ms + 1 s).
  ASSERT_TRUE(sim_.control({{"op", "drop_replies"}, {"count", 100000}})["ok"].get<bool>());
  const auto unanswered = loop.paused([&] {
    return testing::abort_during(
        driver, [&] { return driver.recover(); }, 200ms);
  });
  ASSERT_FALSE(unanswered.returned_before_abort);
  ASSERT_FALSE(unanswered.result);
  EXPECT_EQ(unanswered.result.error().message,
            "aborted: an e-stop or shutdown pre-empted recover (waiting for the reply to clear_system_err)");
  EXPECT_LT(unanswered.abort_to_return, kRequestTimeout / 5);
  testing::print_abort_figure("realman recover, waiting for a reply", unanswered, kRequestTimeout + 1000ms);
  ASSERT_TRUE(sim_.control({{"op", "drop_replies"}, {"count", 0}})["ok"].get<bool>());

  // No push: the link is lost, and recover reconnects and waits for the first push.
  ASSERT_TRUE(sim_.control({{"op", "silence"}, {"on", true}})["ok"].get<bool>());
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kDisconnected; }));
  const auto silent = loop.paused([&] {
    return testing::abort_during(
        driver, [&] { return driver.recover(); }, 200ms);
  });
  ASSERT_FALSE(silent.returned_before_abort);
  ASSERT_FALSE(silent.result);
  EXPECT_EQ(silent.result.error().message,
            "aborted: an e-stop or shutdown pre-empted recover (waiting for the first feedback)");
  EXPECT_LT(silent.abort_to_return, kConnectTimeout / 5);
  testing::print_abort_figure("realman recover, waiting for the first push", silent, kConnectTimeout);

  // A request that came before a recover started is not that recover's.
  ASSERT_TRUE(sim_.control({{"op", "silence"}, {"on", false}})["ok"].get<bool>());
  driver.abort_maintenance();
  const auto recovered = loop.paused([&] { return driver.recover(); });
  ASSERT_TRUE(recovered) << recovered.error().message;
  EXPECT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kOk; }));
}

TEST_F(RealmanDriverTest, WithoutThePushTheDriverPollsTheArmState) {
  RealmanDriver polling;
  ASSERT_TRUE(polling.configure(driver_params(
      sim_.port(), {{"push", {{"enabled", false}}}, {"poll_period_ms", 10}, {"feedback_timeout_ms", 200}})));
  ASSERT_TRUE(sim_.control({{"op", "set_joints"}, {"joints_rad", {0, 0.25, 0, 0, 0, 0}}})["ok"].get<bool>());
  ASSERT_TRUE(polling.connect());
  DriverLoop loop(polling, kDof);
  ASSERT_TRUE(
      loop.wait_for([](DriverLoop& l) { return std::fabs(l.feedback().joints[1].position_rad - 0.25) < 1e-4; }));
  EXPECT_NE(diagnostic(polling, "feedback").find("polling"), std::string::npos);
  EXPECT_NE(diagnostic(polling, "polls"), "0");
}

TEST(RealmanErrorShapes, LegacyArmErrAndSysErrAreReadToo) {
  RealmanSimProcess legacy({"--quiet", "--error-shape", "legacy"});
  RealmanDriver driver;
  ASSERT_TRUE(driver.configure(driver_params(legacy.port())));
  ASSERT_TRUE(driver.connect());
  DriverLoop loop(driver, kDof);
  ASSERT_TRUE(legacy.control({{"op", "raise_error"}, {"code", 0x1002}})["ok"].get<bool>());
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_write() == IoResult::kFault; }));
  EXPECT_NE(loop.fault_text().find("0x1002 target angle beyond joint limit"), std::string::npos) << loop.fault_text();
}

}  // namespace
}  // namespace robotd::realman
