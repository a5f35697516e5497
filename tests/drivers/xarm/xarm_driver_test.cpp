// The xArm driver against robotd-xarm-sim over real TCP sockets on loopback (command port and
// report port), and a 1 kHz thread that calls read()/write() the way robotd's loop does.
#include "driver/xarm_driver.hpp"

#include <chrono>
#include <cmath>
#include <fstream>
#include <future>
#include <iostream>
#include <iterator>
#include <thread>

#include <gtest/gtest.h>

#include "driver/xarm_params.hpp"
#include "driver_loop.hpp"
#include "maintenance_abort.hpp"
#include "robotd/driver/json_reader.hpp"
#include "unanswered_port.hpp"
#include "xarm_sim_process.hpp"

namespace robotd::xarm {
namespace {

using namespace std::chrono_literals;
using driver::IoResult;
using testing::diagnostic;
using testing::DriverLoop;
using testing::joints_near;
using testing::position_frame;
using testing::XarmSimProcess;

constexpr std::size_t kDof = 6;
using Joints = std::array<double, kDof>;

nlohmann::json driver_params(const XarmSimProcess& sim, const nlohmann::json& extra = nlohmann::json::object()) {
  nlohmann::json params{{"model", "xarm6"},
                        {"host", "127.0.0.1"},
                        {"port", sim.port()},
                        {"report", {{"kind", "real"}, {"port", sim.report_port()}}},
                        {"request_timeout_ms", 500}};
  params.update(extra);
  return params;
}

Joints measured(DriverLoop& loop) {
  const driver::Feedback feedback = loop.feedback();
  Joints q{};
  for (std::size_t j = 0; j < kDof; ++j) q[j] = feedback.joints[j].position_rad;
  return q;
}

bool has_feedback(DriverLoop& loop) { return loop.feedback().joint_count == kDof; }

/// Requests the simulator answered, but for the driver's own error polls.
int requests_but_polls(const nlohmann::json& sim_state) {
  int total = 0;
  for (const auto& [reg, count] : sim_state["commands"].items()) {
    if (reg != "get_err_code") total += count.get<int>();
  }
  return total;
}

class XarmDriverTest : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_TRUE(driver_.configure(driver_params(sim_))); }

  nlohmann::json sim_state() const { return sim_.control({{"op", "state"}}); }
  int sim_count(const char* reg) const { return sim_state()["commands"].value(reg, 0); }
  nlohmann::json call(const std::string& op, const nlohmann::json& args = nlohmann::json::object()) {
    auto result = driver_.call(op, args);
    EXPECT_TRUE(result) << op << ": " << result.error().message;
    return result ? result.value() : nlohmann::json();
  }
  /// The standard bring-up through the ops: motors on, position mode, ready.
  void enable_through_ops() {
    call("motion_en", {{"joint", "all"}, {"enable", true}});
    call("set_state", {{"state", 0}});
  }

  XarmSimProcess sim_{{"--quiet"}};
  XarmDriver driver_;
};

TEST(XarmConfigs, ShippedExamplesParse) {
  for (const char* file : {"config/examples/xarm.json", "config/examples/xarm-sim.json", "config/robotd.json"}) {
    std::ifstream in(std::string(ROBOTD_SOURCE_DIR) + "/" + file);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::vector<std::string> errors;
    const auto config = parse_json_with_comments(text, file, errors);
    ASSERT_TRUE(config) << join_errors(errors);
    int xarm_devices = 0;
    for (const auto& device : config->at("devices")) {
      if (device.at("driver") != "xarm") continue;
      ++xarm_devices;
      const auto params = parse_xarm_params(device.at("params"));
      EXPECT_TRUE(params) << file << ": " << params.error().message;
    }
    EXPECT_EQ(xarm_devices, 1) << file;
  }
}

TEST(XarmParams, BadParamsAreNamedWithWhatIsExpected) {
  XarmDriver driver;
  const auto configured = driver.configure({{"model", "xarm9"},
                                            {"port", 0},
                                            {"servo_rate_hz", 500},
                                            {"enable", "always"},
                                            {"report", {{"kind", "rich"}, {"timeout_ms", 5}}},
                                            {"colour", "red"}});
  ASSERT_FALSE(configured);
  const std::string& message = configured.error().message;
  for (const char* key : {"model", "xarm6", "lite6", "port", "servo_rate_hz", "enable", "report.kind", "real",
                          "report.timeout_ms", "colour"}) {
    EXPECT_NE(message.find(key), std::string::npos) << key << " in: " << message;
  }
  const auto missing = driver.configure({{"host", "127.0.0.1"}});
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("model"), std::string::npos) << missing.error().message;
  const auto seventh = driver.configure({{"model", "xarm6"}, {"joints", {{"joint7", {{"velocity_max_rad_s", 1}}}}}});
  ASSERT_FALSE(seventh);
  EXPECT_NE(seventh.error().message.find("expected joint1 … joint6"), std::string::npos) << seventh.error().message;
  const auto slow_report =
      driver.configure({{"model", "xarm6"}, {"report", {{"kind", "normal"}, {"timeout_ms", 300}}}});
  ASSERT_FALSE(slow_report);
  EXPECT_NE(slow_report.error().message.find("two report periods"), std::string::npos) << slow_report.error().message;
}

TEST(XarmParams, DescribeTellsTheModelsJointsAndLimits) {
  XarmDriver driver;
  ASSERT_TRUE(driver.configure({{"model", "xarm7"}, {"servo_rate_hz", 200}}));
  driver::DeviceDescription description = driver.describe();
  EXPECT_EQ(description.model, "UFACTORY xArm 7");
  EXPECT_EQ(description.kinematic_model, "xarm7");
  EXPECT_DOUBLE_EQ(description.native_rate_hz, 200);
  ASSERT_EQ(description.joints.size(), 7U);
  EXPECT_NEAR(description.joints[1].limits.position_min_rad, -118.0 * M_PI / 180, 1e-6);  // J2 −118…120°
  EXPECT_NEAR(description.joints[3].limits.position_max_rad, 225.0 * M_PI / 180, 1e-6);   // J4 −11…225°
  EXPECT_NEAR(description.joints[0].limits.velocity_max_rad_s, M_PI, 1e-9);
  EXPECT_FALSE(description.supports_torque);
  EXPECT_TRUE(description.has_end_pose);

  ASSERT_TRUE(driver.configure({{"model", "lite6"}}));
  description = driver.describe();
  EXPECT_EQ(description.model, "UFACTORY Lite 6");
  EXPECT_EQ(description.kinematic_model, "lite6");
  ASSERT_EQ(description.joints.size(), 6U);
  EXPECT_NEAR(description.joints[2].limits.position_max_rad, 300.0 * M_PI / 180, 1e-6);  // J3 −3.5…300°
  EXPECT_DOUBLE_EQ(description.native_rate_hz, 250);
}

// The ops that act on the arm robotd drives need free motors: power, brakes, state and mode,
// planned motion, motion limits and reduced mode. The queries, clean_war and save_conf do not.
TEST(XarmParams, TheOpsThatActOnTheArmNeedFreeMotors) {
  XarmDriver driver;
  ASSERT_TRUE(driver.configure({{"model", "xarm6"}}));
  EXPECT_EQ(testing::ops_needing_free_motors(driver.describe()),
            (std::vector<std::string>{"motion_en", "set_state", "set_mode", "clean_err", "set_brake", "move_line",
                                      "move_lineb", "move_joint", "move_gohome", "sleep_instruction", "set_tcp_jerk",
                                      "set_tcp_maxacc", "set_joint_jerk", "set_joint_maxacc", "set_tcp_offset",
                                      "clean_conf", "set_reduced_mode"}));
}

TEST(XarmConnect, NothingListeningIsNotAvailableAndNamesTheAddress) {
  const std::uint16_t port = XarmSimProcess::free_port();
  XarmDriver driver;
  ASSERT_TRUE(driver.configure({{"model", "xarm6"}, {"host", "127.0.0.1"}, {"port", port}}));
  const auto connected = driver.connect();
  ASSERT_FALSE(connected);
  EXPECT_EQ(connected.error().code, ErrorCode::kNotAvailable);
  EXPECT_NE(connected.error().message.find("127.0.0.1:" + std::to_string(port)), std::string::npos)
      << connected.error().message;
  driver::Feedback feedback;
  driver::FaultInfo fault;
  EXPECT_EQ(driver.read(feedback, fault), IoResult::kDisconnected);
  EXPECT_NE(std::string(fault.text.data()).find("not connected"), std::string::npos) << fault.text.data();

  // Ops check their arguments with or without the control box, then need it.
  const auto bad = driver.call("move_joint", {{"joints_rad", {0, 0, 0}}});
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(bad.error().message.find("joints_rad"), std::string::npos) << bad.error().message;
  const auto good = driver.call("move_joint", {{"joints_rad", {0, 0, 0, 0, 0, 0}}});
  ASSERT_FALSE(good);
  EXPECT_EQ(good.error().code, ErrorCode::kRefused);
  EXPECT_NE(good.error().message.find("move_joint: not connected to the xArm control box at 127.0.0.1:"),
            std::string::npos)
      << good.error().message;
}

TEST(XarmConnect, AnArmOfAnotherModelIsRefusedWithTheFix) {
  XarmSimProcess xarm7({"--quiet", "--model", "xarm7"});
  XarmDriver driver;
  ASSERT_TRUE(driver.configure(driver_params(xarm7)));
  const auto connected = driver.connect();
  ASSERT_FALSE(connected);
  EXPECT_NE(connected.error().message.find("7 axes"), std::string::npos) << connected.error().message;
  EXPECT_NE(connected.error().message.find(R"(set "model": "xarm7")"), std::string::npos) << connected.error().message;
}

TEST_F(XarmDriverTest, ConnectReadsTheVersionAndReportsFlowWithoutMovingAnything) {
  ASSERT_TRUE(driver_.connect()) << "connect";
  EXPECT_NE(diagnostic(driver_, "arm").find("xArm 6, 6 axes, type 6"), std::string::npos) << diagnostic(driver_, "arm");
  DriverLoop loop(driver_, kDof);
  ASSERT_TRUE(loop.wait_for(has_feedback));
  const driver::Feedback feedback = loop.feedback();
  EXPECT_TRUE(feedback.has_end_pose);
  EXPECT_GT(feedback.end_pose.position_m[2], 0.1) << "the xArm 6's TCP is above its base";
  EXPECT_FALSE(feedback.estop_input);
  std::this_thread::sleep_for(200ms);
  const nlohmann::json state = sim_state();
  EXPECT_EQ(state["servo"]["frames"].get<int>(), 0) << state.dump();
  EXPECT_EQ(state["commands"].value("motion_en", 0), 0) << "on_session: the motors stay as they are";
  EXPECT_EQ(state["mode"].get<int>(), 0) << state.dump();
  EXPECT_EQ(loop.last_write(), IoResult::kOk);
}

// The servo rate is checked as a ceiling: a loaded host may send fewer frames, never more (a late
// period is skipped, not caught up). How closely J1 follows is printed, not asserted.
TEST_F(XarmDriverTest, ASessionEntersServoModeStreamsServoJAndLeavesCleanly) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kDof);
  ASSERT_TRUE(loop.wait_for(has_feedback));
  Joints target = measured(loop);
  const auto stream_start = std::chrono::steady_clock::now();
  const double j1_start = target[0];
  // A 1 kHz ramp like robotd's limiter makes: 0.3 rad on J1 over 1 s.
  double worst_lag = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (auto next = t0; std::chrono::steady_clock::now() - t0 < 1200ms; next += 1ms) {
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    target[0] = j1_start + 0.3 * std::clamp(t - 0.2, 0.0, 1.0);  // 0.2 s to enter servo mode first
    loop.set_command(position_frame(target));
    if (t > 0.4) worst_lag = std::max(worst_lag, target[0] - loop.feedback().joints[0].position_rad);
    std::this_thread::sleep_until(next);
  }
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& l) { return joints_near(l.feedback(), target, 2e-3); }))
      << loop.feedback().joints[0].position_rad;
  nlohmann::json state = sim_state();
  const double streamed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - stream_start).count();
  std::cout << "[ measured ] J1 lag behind a 0.3 rad/s ramp: worst " << worst_lag * 1000 << " mrad (one servo "
            << "period plus one report period is about 4 mrad); servo over " << streamed_s
            << " s: " << state["servo"].dump() << "\n";
  EXPECT_EQ(state["mode"].get<int>(), 1) << state.dump();
  EXPECT_EQ(state["commands"].value("motion_en", 0), 1) << state.dump();
  EXPECT_EQ(state["servo"]["ignored"].get<int>(), 0) << state.dump();
  EXPECT_EQ(state["error"].get<int>(), 0) << state.dump();
  EXPECT_GT(state["servo"]["frames"].get<int>(), 0) << state.dump();
  EXPECT_LE(state["servo"]["frames"].get<int>(), static_cast<int>(250 * streamed_s) + 2)
      << "250 Hz configured; " << state.dump();

  loop.set_command(position_frame(target, /*owned=*/false));  // the session ends: back to position mode
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& /*l*/) {
    const nlohmann::json s = sim_state();
    return s["mode"].get<int>() == 0 && s["state"].get<int>() == 2;
  })) << sim_state().dump();
  const int frames = sim_state()["servo"]["frames"].get<int>();
  std::this_thread::sleep_for(100ms);
  EXPECT_EQ(sim_state()["servo"]["frames"].get<int>(), frames) << "streamed after the session ended";
  EXPECT_TRUE(joints_near(loop.feedback(), target, 2e-3)) << "the arm moved when servo mode was left";
  EXPECT_EQ(loop.last_write(), IoResult::kOk) << loop.fault_text();
}

TEST_F(XarmDriverTest, AFarTargetIsApproachedWithinTheJointSpeedLimit) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kDof);
  ASSERT_TRUE(loop.wait_for(has_feedback));
  Joints target = measured(loop);
  target[1] += 1.0;  // a 1 rad step at once: as one servo_j the arm would stop with C24
  loop.set_command(position_frame(target));
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& l) { return joints_near(l.feedback(), target, 2e-3); }, 5s))
      << loop.feedback().joints[1].position_rad << " " << sim_state().dump();
  EXPECT_EQ(sim_state()["error"].get<int>(), 0) << sim_state().dump();
  const std::string frames = diagnostic(driver_, "servo_frames");
  EXPECT_EQ(frames.find("(0 limited"), std::string::npos) << frames;
}

TEST_F(XarmDriverTest, EstopStopsTheArmAndAResetResumesFromWhereItIs) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kDof);
  ASSERT_TRUE(loop.wait_for(has_feedback));
  Joints target = measured(loop);
  target[0] += 0.8;
  loop.set_command(position_frame(target));
  ASSERT_TRUE(loop.wait_for([&](DriverLoop& l) { return l.feedback().joints[0].position_rad > target[0] - 0.7; }));
  driver::CommandFrame stop = position_frame(target);
  stop.estop = true;
  loop.set_command(stop);
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& /*l*/) { return sim_state()["state"].get<int>() == 4; }))
      << sim_state().dump();
  const int frames_at_stop = sim_state()["servo"]["frames"].get<int>();
  const double stopped_at = loop.feedback().joints[0].position_rad;
  std::this_thread::sleep_for(100ms);
  EXPECT_EQ(sim_state()["servo"]["frames"].get<int>(), frames_at_stop) << "streamed during the e-stop";
  EXPECT_NEAR(loop.feedback().joints[0].position_rad, stopped_at, 0.03) << "the arm kept moving";
  EXPECT_LT(stopped_at, target[0] - 0.05) << "the e-stop came after the arm had arrived";

  loop.set_command(position_frame(target));  // reset: servo mode again, streaming from where the arm is
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& l) { return joints_near(l.feedback(), target, 2e-3); }))
      << sim_state().dump();
  EXPECT_EQ(sim_state()["error"].get<int>(), 0) << sim_state().dump();
}

TEST_F(XarmDriverTest, AStopFromElsewhereUnderASessionIsAFaultAndRecoverResumesTheStream) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kDof);
  ASSERT_TRUE(loop.wait_for(has_feedback));
  Joints target = measured(loop);
  loop.set_command(position_frame(target));
  ASSERT_TRUE(loop.wait_for([&](DriverLoop& /*l*/) { return sim_state()["servo"]["frames"].get<int>() > 10; }));
  call("set_state", {{"state", 4}});  // as UFACTORY Studio or another program could
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_write() == IoResult::kFault; }));
  EXPECT_NE(loop.fault_text().find("the control box left servo mode: stopped"), std::string::npos) << loop.fault_text();

  const auto recovered = loop.paused([&] { return driver_.recover(); });
  ASSERT_TRUE(recovered) << recovered.error().message;
  target[0] += 0.2;
  loop.set_command(position_frame(target));
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& l) { return joints_near(l.feedback(), target, 2e-3); }))
      << loop.fault_text() << " " << sim_state().dump();
  EXPECT_EQ(loop.last_write(), IoResult::kOk) << loop.fault_text();
}

TEST_F(XarmDriverTest, ControllerErrorsAreFaultsInTheControllersWordsAndRecoverClearsThem) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kDof);
  ASSERT_TRUE(loop.wait_for(has_feedback));
  ASSERT_TRUE(sim_.control({{"op", "error"}, {"code", 31}})["ok"].get<bool>());
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_write() == IoResult::kFault; }));
  EXPECT_NE(loop.fault_text().find("C31 collision caused abnormal current"), std::string::npos) << loop.fault_text();
  EXPECT_NE(diagnostic(driver_, "controller_error").find("C31"), std::string::npos);

  const auto recovered = loop.paused([&] { return driver_.recover(); });
  EXPECT_TRUE(recovered) << recovered.error().message;
  EXPECT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_write() == IoResult::kOk; }));
  EXPECT_EQ(sim_count("clean_err"), 1);
  EXPECT_EQ(sim_count("clean_war"), 1);
  EXPECT_EQ(sim_state()["error"].get<int>(), 0);

  // A warning is no fault; it shows in the diagnostics.
  ASSERT_TRUE(sim_.control({{"op", "warning"}, {"code", 11}})["ok"].get<bool>());
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& /*l*/) {
    return diagnostic(driver_, "controller_warning").find("W11 command cache full") != std::string::npos;
  })) << diagnostic(driver_, "controller_warning");
  EXPECT_EQ(loop.last_write(), IoResult::kOk);
}

TEST_F(XarmDriverTest, TheControlBoxEstopButtonIsTheDevicesEstopInput) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kDof);
  ASSERT_TRUE(loop.wait_for(has_feedback));
  ASSERT_TRUE(sim_.control({{"op", "estop"}, {"pressed", true}})["ok"].get<bool>());
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.feedback().estop_input; }));
  EXPECT_NE(diagnostic(driver_, "controller_error").find("C1 "), std::string::npos)
      << diagnostic(driver_, "controller_error");
  EXPECT_EQ(loop.last_write(), IoResult::kOk) << "an input, not a fault: robotd engages its e-stop";
  const auto held = loop.paused([&] { return driver_.recover(); });
  ASSERT_FALSE(held);
  EXPECT_NE(held.error().message.find("release the e-stop"), std::string::npos) << held.error().message;
  ASSERT_TRUE(sim_.control({{"op", "estop"}, {"pressed", false}})["ok"].get<bool>());
  const auto recovered = loop.paused([&] { return driver_.recover(); });
  EXPECT_TRUE(recovered) << recovered.error().message;
  EXPECT_TRUE(
      loop.wait_for([](DriverLoop& l) { return !l.feedback().estop_input && l.last_write() == IoResult::kOk; }));
}

TEST_F(XarmDriverTest, PlannedMovesQueueInPositionModeAndCanWaitForTheArm) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kDof);
  ASSERT_TRUE(loop.wait_for(has_feedback));
  // Motors off after power-on: the box says so in its own words.
  const auto not_ready = driver_.call("move_joint", {{"joints_rad", {0.1, 0, 0, 0, 0, 0}}});
  ASSERT_FALSE(not_ready);
  EXPECT_NE(not_ready.error().message.find("not ready to move"), std::string::npos) << not_ready.error().message;

  enable_through_ops();
  const Joints goal{0.3, -0.2, -0.4, 0.1, 0.5, -0.3};
  // Read before the move starts: a test thread starved for the whole move must still see it.
  const double first = loop.feedback().joints[4].position_rad;
  const auto t0 = std::chrono::steady_clock::now();
  auto moved = std::async(std::launch::async, [&] {
    return driver_.call("move_joint", {{"joints_rad", goal}, {"speed_rad_s", 1.0}, {"wait", true}, {"timeout_s", 10}});
  });
  // While the call waits, the loop keeps reading fresh feedback.
  EXPECT_TRUE(
      loop.wait_for([&](DriverLoop& l) { return std::fabs(l.feedback().joints[4].position_rad - first) > 0.05; }, 3s));
  const auto result = moved.get();
  ASSERT_TRUE(result) << result.error().message;
  EXPECT_TRUE(result.value()["completed"].get<bool>()) << result.value().dump();
  EXPECT_EQ(result.value()["execution_state"].get<int>(), 0) << result.value().dump();
  const double took_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_GT(took_s, 0.4) << "0.5 rad at 1 rad/s with its ramps";
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& l) { return joints_near(l.feedback(), goal, 2e-3); }));

  // A straight line to a pose: where get_tcp_pose then says the TCP is.
  nlohmann::json pose = call("get_tcp_pose");
  pose.erase("execution_state");
  pose.erase("execution_text");
  pose["z_m"] = pose["z_m"].get<double>() - 0.05;
  pose["wait"] = true;
  pose["speed_m_s"] = 0.2;
  const nlohmann::json line = call("move_line", pose);
  EXPECT_TRUE(line.value("completed", false)) << line.dump();
  EXPECT_NEAR(call("get_tcp_pose")["z_m"].get<double>(), pose["z_m"].get<double>(), 1e-3);

  // Without wait: queued behind each other in the command cache (the pause long enough that the
  // two calls after it find the move still queued however slowly this test runs).
  call("sleep_instruction", {{"seconds", 1.0}});
  const nlohmann::json queued = call("move_gohome", {{"speed_rad_s", 1.5}});
  EXPECT_GE(queued["cmdnum"].get<int>(), 1) << queued.dump();
  EXPECT_GE(call("get_cmdnum")["cmdnum"].get<int>(), 1);
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& l) { return joints_near(l.feedback(), Joints{}, 2e-3); }, 10s));
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& /*l*/) { return call("get_state")["state"] == kStateSleeping; }));

  // A session owns the arm: planned moves are refused until it ends.
  Joints here = measured(loop);
  loop.set_command(position_frame(here));
  ASSERT_TRUE(loop.wait_for([&](DriverLoop& /*l*/) { return sim_state()["mode"].get<int>() == 1; }));
  const auto refused = driver_.call("move_gohome", nlohmann::json::object());
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("release the session first"), std::string::npos) << refused.error().message;
}

TEST_F(XarmDriverTest, OpsCheckTheirArgumentsBeforeSendingAnything) {
  ASSERT_TRUE(driver_.connect());
  const int requests_before = requests_but_polls(sim_state());
  const auto wrong_count = driver_.call("move_joint", {{"joints_rad", {0, 0, 0}}});
  ASSERT_FALSE(wrong_count);
  EXPECT_NE(wrong_count.error().message.find("expected 6 angles, got 3"), std::string::npos)
      << wrong_count.error().message;
  const auto beyond = driver_.call("move_joint", {{"joints_rad", {0, 2.5, 0, 0, 0, 0}}, {"speed_rad_s", 9}});
  ASSERT_FALSE(beyond);
  for (const char* part : {"joint 2", "speed_rad_s", "expects"}) {
    EXPECT_NE(beyond.error().message.find(part), std::string::npos) << part << " in " << beyond.error().message;
  }
  const auto reported_state = driver_.call("set_state", {{"state", 2}});
  ASSERT_FALSE(reported_state);
  EXPECT_NE(reported_state.error().message.find("a state the controller reports"), std::string::npos);
  const auto bad_joint = driver_.call("motion_en", {{"joint", 7}, {"enable", true}});
  ASSERT_FALSE(bad_joint);
  EXPECT_NE(bad_joint.error().message.find("1..6"), std::string::npos) << bad_joint.error().message;
  const auto servo = driver_.call("set_mode", {{"mode", 1}});
  ASSERT_FALSE(servo);
  EXPECT_NE(servo.error().message.find("entered by robotd"), std::string::npos) << servo.error().message;
  const auto typo = driver_.call("set_tcp_jerk", {{"jerk", 10}});
  ASSERT_FALSE(typo);
  EXPECT_NE(typo.error().message.find("jerk_m_s3"), std::string::npos) << typo.error().message;
  const auto unknown = driver_.call("move_circle", nlohmann::json::object());
  ASSERT_FALSE(unknown);
  EXPECT_NE(unknown.error().message.find("the xarm driver has: motion_en"), std::string::npos);
  EXPECT_EQ(requests_but_polls(sim_state()), requests_before) << sim_state()["commands"].dump();
}

TEST_F(XarmDriverTest, QueriesAndSettingsAnswerInRobotdsUnits) {
  ASSERT_TRUE(sim_.control({{"op", "set_joints"}, {"joints_rad", {0.2, -0.3, -0.5, 0.1, 0.6, 0.2}}})["ok"].get<bool>());
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kDof);
  ASSERT_TRUE(loop.wait_for(has_feedback));
  const nlohmann::json joints = call("get_joint_pose");
  ASSERT_EQ(joints["joints_rad"].size(), kDof) << joints.dump();
  EXPECT_NEAR(joints["joints_rad"][2].get<double>(), -0.5, 1e-5);
  const nlohmann::json tcp = call("get_tcp_pose");
  const nlohmann::json fk = call("get_fk", {{"joints_rad", joints["joints_rad"]}});
  for (const char* key : {"x_m", "y_m", "z_m", "roll_rad", "pitch_rad", "yaw_rad"}) {
    EXPECT_NEAR(fk[key].get<double>(), tcp[key].get<double>(), 1e-4) << key;
  }
  const driver::Feedback feedback = loop.feedback();
  EXPECT_NEAR(feedback.end_pose.position_m[0], tcp["x_m"].get<double>(), 1e-3) << "the report's pose, in metres";
  EXPECT_GT(std::fabs(tcp["x_m"].get<double>()), 0.05);
  EXPECT_FALSE(call("is_joint_limit", {{"joints_rad", joints["joints_rad"]}})["outside_limits"].get<bool>());
  EXPECT_TRUE(call("is_joint_limit", {{"joints_rad", {0, 0, 0.5, 0, 0, 0}}})["outside_limits"].get<bool>())
      << "J3 of an xArm 6 ends at 11°";

  ASSERT_TRUE(sim_.control({{"op", "warning"}, {"code", 12}})["ok"].get<bool>());
  const nlohmann::json codes = call("get_err_code");
  EXPECT_EQ(codes["warning"], 12);
  EXPECT_EQ(codes["warning_text"], "W12 command parameter error") << codes.dump();
  EXPECT_EQ(codes["execution_state"], 2) << codes.dump();
  call("clean_war");

  ASSERT_TRUE(sim_.control({{"op", "servo_error"}, {"joint", 3}, {"code", 15}})["ok"].get<bool>());
  const nlohmann::json servos = call("servo_get_dbmsg");
  ASSERT_EQ(servos["servos"].size(), kDof + 1) << servos.dump();
  EXPECT_EQ(servos["servos"][2]["error_text"], "joint over-temperature") << servos.dump();
  EXPECT_EQ(servos["servos"][6]["servo"], "gripper");
  EXPECT_EQ(call("get_err_code")["error_text"], controller_error_text(13));
  ASSERT_TRUE(sim_.control({{"op", "servo_error"}, {"joint", 3}, {"code", 0}})["ok"].get<bool>());
  call("clean_err");

  const nlohmann::json version = call("get_version");
  EXPECT_EQ(version["model"], "xarm6") << version.dump();
  EXPECT_EQ(version["axes"], 6);

  // Settings: the TCP offset moves the reported TCP along the flange's z.
  enable_through_ops();
  const double z_before = call("get_fk", {{"joints_rad", {0, 0, 0, 0, 0, 0}}})["z_m"].get<double>();
  call("set_tcp_offset", {{"x_m", 0}, {"y_m", 0}, {"z_m", 0.1}, {"roll_rad", 0}, {"pitch_rad", 0}, {"yaw_rad", 0}});
  const double z_after = call("get_fk", {{"joints_rad", {0, 0, 0, 0, 0, 0}}})["z_m"].get<double>();
  EXPECT_NEAR(std::fabs(z_after - z_before), 0.1, 1e-3) << "the flange points down or up at zero";
  EXPECT_EQ(sim_state()["state"].get<int>(), 5) << "set_tcp_offset resets the system";
  call("set_state", {{"state", 0}});
  call("save_conf");
  EXPECT_TRUE(sim_state()["saved_conf"].get<bool>());
  call("clean_conf");
  EXPECT_NEAR(sim_state()["tcp_offset"][2].get<double>(), 0, 1e-9);
  for (const auto& [op, key, value] :
       std::vector<std::tuple<std::string, std::string, double>>{{"set_tcp_jerk", "jerk_m_s3", 10},
                                                                 {"set_tcp_maxacc", "acc_m_s2", 5},
                                                                 {"set_joint_jerk", "jerk_rad_s3", 100},
                                                                 {"set_joint_maxacc", "acc_rad_s2", 10}}) {
    EXPECT_EQ(call(op, {{key, value}})["execution_state"], 0) << op;
  }
  call("set_brake", {{"joint", 2}, {"release", true}});
  EXPECT_TRUE(sim_state()["brakes_released"][1].get<bool>());
  call("set_brake", {{"joint", "all"}, {"release", false}});
  EXPECT_FALSE(sim_state()["brakes_released"][1].get<bool>());
  EXPECT_EQ(call("feedback_check")["execution_state"], 0);
}

TEST_F(XarmDriverTest, TheGripperOpensClosesAndReportsItsErrorsOverTheToolBus) {
  ASSERT_TRUE(driver_.connect());
  const auto moving_disabled =
      driver_.call("gripper_set_position", {{"position", 400}, {"wait", true}, {"timeout_s", 1}});
  ASSERT_FALSE(moving_disabled) << "a disabled gripper does not move";
  EXPECT_NE(moving_disabled.error().message.find("disabled (gripper_enable first)"), std::string::npos)
      << moving_disabled.error().message;

  call("gripper_enable", {{"enable", true}});
  EXPECT_TRUE(sim_state()["gripper"]["enabled"].get<bool>());
  call("gripper_set_speed", {{"speed_rpm", 3000}});
  EXPECT_EQ(sim_state()["gripper"]["speed_rpm"], 3000);
  const nlohmann::json opened = call("gripper_open", {{"wait", true}});
  EXPECT_EQ(opened["position"], 850) << opened.dump();
  EXPECT_EQ(call("gripper_get_position")["position"], 850);
  const nlohmann::json placed = call("gripper_set_position", {{"position", 300}, {"speed_rpm", 5000}, {"wait", true}});
  EXPECT_EQ(placed["position"], 300) << placed.dump();
  EXPECT_EQ(sim_state()["gripper"]["speed_rpm"], 5000);
  call("gripper_close");
  EXPECT_EQ(sim_state()["gripper"]["target_pulses"], 0) << "without wait: the target is set, the op returns";

  const auto beyond = driver_.call("gripper_set_position", {{"position", 900}});
  ASSERT_FALSE(beyond);
  EXPECT_NE(beyond.error().message.find("position"), std::string::npos) << beyond.error().message;

  ASSERT_TRUE(sim_.control({{"op", "gripper_error"}, {"code", 14}})["ok"].get<bool>());
  EXPECT_EQ(call("gripper_get_error")["error"], 14);
  const auto faulted = driver_.call("gripper_open", nlohmann::json::object());
  ASSERT_FALSE(faulted);
  EXPECT_NE(faulted.error().message.find("gripper error 14"), std::string::npos) << faulted.error().message;
  call("gripper_clean_error");
  EXPECT_EQ(call("gripper_get_error")["error"], 0);
  call("gripper_enable", {{"enable", true}});
  EXPECT_EQ(call("gripper_open", {{"wait", true}})["position"], 850);
}

TEST_F(XarmDriverTest, TheGripperSaysWhenItHoldsAnObject) {
  ASSERT_TRUE(driver_.connect());
  call("gripper_enable", {{"enable", true}});
  const nlohmann::json opened = call("gripper_open", {{"speed_rpm", 5000}, {"wait", true}});
  EXPECT_FALSE(opened["object_gripped"].get<bool>()) << opened.dump();
  EXPECT_EQ(call("gripper_get_status")["status"], 0);

  ASSERT_TRUE(sim_.control({{"op", "gripper_object"}, {"width_pulses", 300}})["ok"].get<bool>());
  const nlohmann::json closed = call("gripper_close", {{"wait", true}});
  EXPECT_EQ(closed["position"], 300) << closed.dump();
  EXPECT_TRUE(closed["object_gripped"].get<bool>()) << closed.dump();
  const nlohmann::json status = call("gripper_get_status");
  EXPECT_EQ(status["status"], 2) << status.dump();
  EXPECT_EQ(status["status_text"], "gripping an object");
  EXPECT_TRUE(status["object_gripped"].get<bool>());

  EXPECT_FALSE(call("gripper_open", {{"wait", true}})["object_gripped"].get<bool>()) << "opened, it lets go";
}

TEST_F(XarmDriverTest, ReducedModeIsSwitchedAndReadAsTheSdkDoes) {
  ASSERT_TRUE(driver_.connect());
  EXPECT_FALSE(call("get_reduced_mode")["reduced_mode"].get<bool>());
  call("set_reduced_mode", {{"on", true}});
  EXPECT_TRUE(sim_state()["reduced_mode"].get<bool>());
  EXPECT_TRUE(call("get_reduced_mode")["reduced_mode"].get<bool>());
  const auto missing = driver_.call("set_reduced_mode", nlohmann::json::object());
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("on"), std::string::npos) << missing.error().message;
  call("set_reduced_mode", {{"on", false}});
  EXPECT_FALSE(call("get_reduced_mode")["reduced_mode"].get<bool>());
}

TEST_F(XarmDriverTest, ManualEnableRefusesServoModeUntilTheMotorsAreOn) {
  XarmDriver manual;
  ASSERT_TRUE(manual.configure(driver_params(sim_, {{"enable", "manual"}})));
  ASSERT_TRUE(manual.connect());
  DriverLoop loop(manual, kDof);
  ASSERT_TRUE(loop.wait_for(has_feedback));
  loop.set_command(position_frame(measured(loop)));
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_write() == IoResult::kFault; }));
  EXPECT_NE(loop.fault_text().find("servo mode refused"), std::string::npos) << loop.fault_text();
  EXPECT_NE(loop.fault_text().find("call motion_en"), std::string::npos) << loop.fault_text();
  EXPECT_EQ(sim_count("motion_en"), 0);

  ASSERT_TRUE(manual.call("motion_en", {{"joint", "all"}, {"enable", true}}));
  const auto recovered = loop.paused([&] { return manual.recover(); });
  ASSERT_TRUE(recovered) << recovered.error().message;
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& /*l*/) { return sim_state()["servo"]["frames"].get<int>() > 10; }))
      << loop.fault_text();
}

TEST_F(XarmDriverTest, AClosedConnectionIsALostLinkAndRecoverReconnectsWithoutAJump) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kDof);
  ASSERT_TRUE(loop.wait_for(has_feedback));
  Joints target = measured(loop);
  target[0] += 0.6;
  loop.set_command(position_frame(target));
  ASSERT_TRUE(loop.wait_for([&](DriverLoop& l) { return l.feedback().joints[0].position_rad > target[0] - 0.5; }));
  ASSERT_TRUE(sim_.control({{"op", "disconnect"}})["ok"].get<bool>());
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kDisconnected; }));
  EXPECT_NE(loop.fault_text().find("the control box closed the"), std::string::npos) << loop.fault_text();
  // robotd holds the measured joints across a reconnect (the session's old target is gone).
  loop.set_command(position_frame(target, /*owned=*/false));
  const auto recovered = loop.paused([&] { return driver_.recover(); });
  ASSERT_TRUE(recovered) << recovered.error().message;
  EXPECT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kOk; }));
  const Joints at_reconnect = measured(loop);
  std::this_thread::sleep_for(300ms);
  EXPECT_TRUE(joints_near(loop.feedback(), at_reconnect, 1e-3)) << "the arm moved after the reconnect";
  EXPECT_LT(at_reconnect[0], target[0] - 0.05) << "the old target was resumed";
}

TEST_F(XarmDriverTest, ASilentReportIsALostLinkThatSaysWhereItWasExpected) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kDof);
  ASSERT_TRUE(loop.wait_for(has_feedback));
  ASSERT_TRUE(sim_.control({{"op", "silence"}, {"on", true}})["ok"].get<bool>());
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kDisconnected; }));
  EXPECT_NE(loop.fault_text().find("no report from the control box"), std::string::npos) << loop.fault_text();
  EXPECT_NE(loop.fault_text().find("127.0.0.1:" + std::to_string(sim_.report_port())), std::string::npos)
      << loop.fault_text();
  const auto silent = loop.paused([&] { return driver_.recover(); });
  EXPECT_FALSE(silent) << "reconnected without a report";
  ASSERT_TRUE(sim_.control({{"op", "silence"}, {"on", false}})["ok"].get<bool>());
  const auto recovered = loop.paused([&] { return driver_.recover(); });
  EXPECT_TRUE(recovered) << recovered.error().message;
}

TEST(XarmAbort, AnAbortEndsARecoverThatWaitsForAControlBoxThatDoesNotAnswer) {
  const testing::UnansweredPort unanswered;
  constexpr auto kConnectTimeout = 5000ms;
  XarmDriver driver;
  ASSERT_TRUE(driver.configure({{"model", "xarm6"},
                                {"host", "127.0.0.1"},
                                {"port", unanswered.port()},
                                {"connect_timeout_ms", kConnectTimeout.count()}}));
  const auto aborted = testing::abort_during(
      driver, [&] { return driver.recover(); }, 200ms);
  ASSERT_FALSE(aborted.returned_before_abort);
  ASSERT_FALSE(aborted.result);
  EXPECT_EQ(aborted.result.error().code, ErrorCode::kRefused);
  EXPECT_EQ(aborted.result.error().message,
            "aborted: an e-stop or shutdown pre-empted recover (connecting to 127.0.0.1:" +
                std::to_string(unanswered.port()) + ")");
  EXPECT_LT(aborted.abort_to_return, kConnectTimeout / 5);
  testing::print_abort_figure("xarm recover, connecting to a control box that does not answer", aborted,
                              kConnectTimeout);
}

TEST_F(XarmDriverTest, AnAbortEndsARecoverWaitingForReportsOrRepliesAndTheNextRecoverWorks) {
  constexpr auto kConnectTimeout = 5000ms;
  constexpr auto kRequestTimeout = 3000ms;
  XarmDriver driver;
  ASSERT_TRUE(driver.configure(driver_params(
      sim_, {{"connect_timeout_ms", kConnectTimeout.count()}, {"request_timeout_ms", kRequestTimeout.count()}})));
  ASSERT_TRUE(driver.connect());
  DriverLoop loop(driver, kDof);
  ASSERT_TRUE(loop.wait_for(has_feedback));

  // Every reply dropped: recover waits for its clean_err (request_timeout_ms + 1 s).
  ASSERT_TRUE(sim_.control({{"op", "drop_replies"}, {"count", 100000}})["ok"].get<bool>());
  const auto unanswered = loop.paused([&] {
    return testing::abort_during(
        driver, [&] { return driver.recover(); }, 200ms);
  });
  ASSERT_FALSE(unanswered.returned_before_abort);
  ASSERT_FALSE(unanswered.result);
  EXPECT_EQ(unanswered.result.error().message,
            "aborted: an e-stop or shutdown pre-empted recover (waiting for clean_err)");
  EXPECT_LT(unanswered.abort_to_return, kRequestTimeout / 5);
  testing::print_abort_figure("xarm recover, waiting for a reply", unanswered, kRequestTimeout + 1000ms);
  ASSERT_TRUE(sim_.control({{"op", "drop_replies"}, {"count", 0}})["ok"].get<bool>());

  // No reports: the link is lost, and recover reconnects and waits for the first report.
  ASSERT_TRUE(sim_.control({{"op", "silence"}, {"on", true}})["ok"].get<bool>());
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kDisconnected; }));
  const auto silent = loop.paused([&] {
    return testing::abort_during(
        driver, [&] { return driver.recover(); }, 200ms);
  });
  ASSERT_FALSE(silent.returned_before_abort);
  ASSERT_FALSE(silent.result);
  EXPECT_EQ(silent.result.error().message,
            "aborted: an e-stop or shutdown pre-empted recover (waiting for the first report)");
  EXPECT_LT(silent.abort_to_return, kConnectTimeout / 5);
  testing::print_abort_figure("xarm recover, waiting for the first report", silent, kConnectTimeout);

  // A request that came before a recover started is not that recover's.
  ASSERT_TRUE(sim_.control({{"op", "silence"}, {"on", false}})["ok"].get<bool>());
  driver.abort_maintenance();
  const auto recovered = loop.paused([&] { return driver.recover(); });
  ASSERT_TRUE(recovered) << recovered.error().message;
  EXPECT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kOk; }));
}

TEST_F(XarmDriverTest, StrayFramesAreCountedDroppedRepliesTimeOutAndBrokenFramingReconnects) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kDof);
  ASSERT_TRUE(loop.wait_for(has_feedback));
  ASSERT_TRUE(sim_.control({{"op", "garbage"}, {"kind", "frame"}})["ok"].get<bool>());
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& /*l*/) { return diagnostic(driver_, "unmatched_replies") != "0"; }));
  ASSERT_TRUE(sim_.control({{"op", "drop_replies"}, {"count", 1}})["ok"].get<bool>());
  const auto dropped = driver_.call("get_state", nlohmann::json::object());
  ASSERT_FALSE(dropped);
  EXPECT_EQ(dropped.error().code, ErrorCode::kTimeout);
  EXPECT_NE(dropped.error().message.find("no reply to get_state"), std::string::npos) << dropped.error().message;
  EXPECT_TRUE(driver_.call("get_state", nlohmann::json::object()));
  EXPECT_NE(loop.last_read(), IoResult::kDisconnected);

  ASSERT_TRUE(sim_.control({{"op", "garbage"}, {"kind", "bytes"}})["ok"].get<bool>());
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kDisconnected; }));
  EXPECT_NE(loop.fault_text().find("lost its framing"), std::string::npos) << loop.fault_text();
  const auto recovered = loop.paused([&] { return driver_.recover(); });
  EXPECT_TRUE(recovered) << recovered.error().message;
}

TEST(XarmReports, TheRealtimeReportGivesVelocitiesAndTorques) {
  const std::uint16_t realtime_port = XarmSimProcess::free_port();
  XarmSimProcess sim({"--quiet", "--realtime-report-port", std::to_string(realtime_port)});
  XarmDriver driver;
  ASSERT_TRUE(driver.configure(driver_params(sim, {{"report", {{"kind", "realtime"}, {"port", realtime_port}}}})));
  ASSERT_TRUE(driver.connect());
  DriverLoop loop(driver, kDof);
  ASSERT_TRUE(loop.wait_for(has_feedback));
  Joints target = measured(loop);
  target[0] += 0.5;
  loop.set_command(position_frame(target));
  EXPECT_TRUE(loop.wait_for([](DriverLoop& l) { return l.feedback().joints[0].velocity_rad_s > 0.3; }))
      << loop.feedback().joints[0].velocity_rad_s;
  EXPECT_NE(diagnostic(driver, "report").find("realtime report on port " + std::to_string(realtime_port)),
            std::string::npos);
}

}  // namespace
}  // namespace robotd::xarm
