// The PAROL6 driver against robotd-parol6-sim on a pseudo-terminal: a real serial line, a real
// simulator process, and a 1 kHz thread that calls read()/write() the way robotd's loop does.
#include "driver/parol6_driver.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <thread>

#include <gtest/gtest.h>

#include "codec/joint_units.hpp"
#include "driver_loop.hpp"
#include "kinematics/parol6_kinematics.hpp"
#include "maintenance_abort.hpp"
#include "parol6_sim_process.hpp"
#include "robotd/driver/json_reader.hpp"
#include "robotd/driver/monotonic_clock.hpp"

namespace robotd::parol6 {
namespace {

using namespace std::chrono_literals;
using driver::IoResult;
using testing::DriverLoop;
using testing::joints_near;
using testing::Parol6SimProcess;
using testing::position_frame;

nlohmann::json driver_params(const std::string& pty) { return {{"serial", {{"device", pty}, {"baud", 3000000}}}}; }

JointVector standby_rad() {
  JointVector q{};
  for (int j = 0; j < kJoints; ++j) {
    q[static_cast<std::size_t>(j)] = steps_to_rad(j, joint_units()[static_cast<std::size_t>(j)].standby_steps);
  }
  return q;
}

class Parol6DriverTest : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_TRUE(driver_.configure(driver_params(sim_.pty_path()))); }
  Parol6SimProcess sim_{Parol6SimProcess::unique_path("parol6-driver"), {"--homed", "--homing-ms", "600"}};
  Parol6Driver driver_;
};

TEST(Parol6Configs, ShippedExamplesParse) {
  for (const char* file : {"config/examples/parol6.json", "config/examples/parol6-sim.json", "config/robotd.json"}) {
    std::ifstream in(std::string(ROBOTD_SOURCE_DIR) + "/" + file);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::vector<std::string> errors;
    const auto config = parse_json_with_comments(text, file, errors);
    ASSERT_TRUE(config) << join_errors(errors);
    for (const auto& device : config->at("devices")) {
      if (device.at("driver") != "parol6") continue;
      const auto params = parse_parol6_params(device.at("params"));
      EXPECT_TRUE(params) << file << ": " << params.error().message;
    }
  }
}

TEST(Parol6Params, BadParamsAreNamed) {
  Parol6Driver driver;
  const auto configured = driver.configure({{"serial", {{"device", "/dev/ttyACM0"}, {"baud", 12345}}},
                                            {"exchange_rate_hz", 5},
                                            {"joints", {{"joint7", {{"velocity_max_rad_s", 1}}}}},
                                            {"gripper_id", 16}});
  ASSERT_FALSE(configured);
  const std::string& message = configured.error().message;
  for (const char* key : {"serial.baud", "exchange_rate_hz", "joint7", "gripper_id"}) {
    EXPECT_NE(message.find(key), std::string::npos) << key << " in: " << message;
  }
}

TEST(Parol6Params, DescribeNamesTheArmModel) {
  Parol6Driver driver;
  ASSERT_TRUE(driver.configure(driver_params("/tmp/robotd-parol6-nothing-here")));
  EXPECT_EQ(driver.describe().kinematic_model, "parol6");
}

TEST_F(Parol6DriverTest, ConnectFailsClearlyWithoutABoard) {
  Parol6Driver lonely;
  ASSERT_TRUE(lonely.configure(driver_params("/tmp/robotd-parol6-nothing-here")));
  const auto connected = lonely.connect();
  ASSERT_FALSE(connected);
  EXPECT_NE(connected.error().message.find("does not exist"), std::string::npos) << connected.error().message;

  ASSERT_TRUE(sim_.control({{"op", "silence"}, {"ms", 3000}})["ok"].get<bool>());
  const auto silent = driver_.connect();
  ASSERT_FALSE(silent);
  EXPECT_EQ(silent.error().code, ErrorCode::kNotAvailable);
  EXPECT_NE(silent.error().message.find("no answer from the PAROL6 board"), std::string::npos)
      << silent.error().message;
}

TEST_F(Parol6DriverTest, StreamedPositionsMoveTheSteppersSmoothly) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kJoints);
  const JointVector start = standby_rad();
  ASSERT_TRUE(loop.wait_for([&](DriverLoop& l) { return joints_near(l.feedback(), start, 1e-3); }));
  // A 1 kHz ramp like robotd's limiter makes: 0.3 rad on J1 over 1 s.
  const auto t0 = std::chrono::steady_clock::now();
  double worst_lag = 0;
  for (;;) {
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (t > 1.2) break;
    JointVector target = start;
    target[0] += 0.3 * std::min(t, 1.0);
    loop.set_command(position_frame(target));
    if (t > 0.1 && t < 1.0)
      worst_lag = std::max(worst_lag, std::fabs(loop.feedback().joints[0].position_rad - target[0]));
    std::this_thread::sleep_for(1ms);
  }
  JointVector end = start;
  end[0] += 0.3;
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& l) { return joints_near(l.feedback(), end, 2e-3); }));
  // The board is fed the target one exchange ahead with its speed: it follows within about
  // one exchange of motion (0.3 rad/s × 10 ms = 3 mrad) plus a reply's age.
  EXPECT_LT(worst_lag, 0.05)
      << "lag behind the ramp (about 5 mrad on a quiet machine; the test thread is not real-time)";
  std::printf("[ measured ] J1 following a 0.3 rad/s ramp streamed at 1 kHz: worst lag %.2f mrad\n", worst_lag * 1e3);
  EXPECT_NEAR(loop.feedback().joints[0].velocity_rad_s, 0.0, 0.05);
  EXPECT_TRUE(loop.feedback().has_end_pose);
}

TEST_F(Parol6DriverTest, WithoutASessionTheBoardIsLeftIdle) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kJoints);
  loop.set_command(position_frame(standby_rad(), /*owned=*/false));
  std::this_thread::sleep_for(100ms);
  const nlohmann::json state = sim_.control({{"op", "state"}});
  EXPECT_EQ(state["command"], 255) << state.dump();
}

TEST_F(Parol6DriverTest, EstopInputIsReportedAndDisablesTheBoard) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kJoints);
  loop.set_command(position_frame(standby_rad()));
  ASSERT_TRUE(sim_.control({{"op", "estop"}, {"pressed", true}})["ok"].get<bool>());
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.feedback().estop_input; }));
  EXPECT_TRUE(loop.wait_for([&](DriverLoop&) {
    return sim_.control({{"op", "state"}})["command"] == 102;
  })) << "DISABLE while the E-stop input is pressed";
  ASSERT_TRUE(sim_.control({{"op", "estop"}, {"pressed", false}})["ok"].get<bool>());
  EXPECT_TRUE(loop.wait_for([](DriverLoop& l) { return !l.feedback().estop_input; }));
}

// robotd counts an e-stop frame as delivered when write() returns, so it must not wait for the
// next 100 Hz exchange. No read() here: nothing else would send a frame.
TEST_F(Parol6DriverTest, AnEstopGoesOutOnTheTickItArrivesNotAtTheNextExchange) {
  ASSERT_TRUE(driver_.connect());
  driver::FaultInfo fault;
  driver::CommandFrame frame = position_frame(standby_rad());
  frame.tick_deadline_ns = driver::monotonic_now_ns();
  ASSERT_EQ(driver_.write(frame, fault), IoResult::kOk);  // an exchange: the next is 5 to 10 ms later
  frame.estop = true;
  frame.tick_deadline_ns += 1'000'000;
  ASSERT_EQ(driver_.write(frame, fault), IoResult::kOk);
  bool disabled = false;
  for (int i = 0; i < 200 && !disabled; ++i) {
    disabled = sim_.control({{"op", "state"}})["command"] == 102;
    if (!disabled) std::this_thread::sleep_for(5ms);
  }
  EXPECT_TRUE(disabled) << "the board never got DISABLE from the e-stop frame";
}

TEST_F(Parol6DriverTest, HomeRunsTheBoardsSequence) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kJoints);
  const auto homed = driver_.call("home", {{"wait", true}});
  ASSERT_TRUE(homed) << homed.error().message;
  EXPECT_TRUE(homed.value()["homed"].get<bool>());
  EXPECT_TRUE(joints_near(loop.feedback(), standby_rad(), 1e-3));
}

TEST_F(Parol6DriverTest, JogAndMovesRunAndStopAtTheirEnd) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kJoints);
  const JointVector start = standby_rad();
  ASSERT_TRUE(loop.wait_for([&](DriverLoop& l) { return joints_near(l.feedback(), start, 1e-3); }));
  const auto jog = driver_.call("jog", {{"joint", 4}, {"velocity_rad_s", 0.5}, {"duration_s", 0.4}});
  ASSERT_TRUE(jog) << jog.error().message;
  JointVector jogged = start;
  jogged[3] += 0.2;
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& l) { return joints_near(l.feedback(), jogged, 3e-3); }))
      << loop.feedback().joints[3].position_rad;

  JointVector target = start;
  target[1] -= 0.2;
  target[2] += 0.2;
  const auto move = driver_.call("move_joints", {{"joints_rad", target}, {"duration_s", 0.6}});
  ASSERT_TRUE(move) << move.error().message;
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& l) { return joints_near(l.feedback(), target, 3e-3); }));

  const auto tool = driver_.call("fk", nullptr);
  ASSERT_TRUE(tool);
  nlohmann::json pose = tool.value()["tool"];
  pose["z_m"] = pose["z_m"].get<double>() + 0.02;
  pose["duration_s"] = 0.8;
  const auto line = driver_.call("move_cart", pose);
  ASSERT_TRUE(line) << line.error().message;
  EXPECT_TRUE(loop.wait_for([&](DriverLoop&) {
    const auto now = driver_.call("fk", nullptr);
    return now && std::fabs(now.value()["tool"]["z_m"].get<double>() - pose["z_m"].get<double>()) < 0.001;
  }));
}

TEST_F(Parol6DriverTest, CartesianJogMovesTheToolAlongAnAxisOfEitherFrame) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kJoints);
  JointVector start = standby_rad();
  ASSERT_TRUE(loop.wait_for([&](DriverLoop& l) { return joints_near(l.feedback(), start, 1e-3); }));
  start[1] -= 0.2;  // away from the standby pose's wrist alignment
  start[2] += 0.2;
  ASSERT_TRUE(driver_.call("move_joints", {{"joints_rad", start}, {"duration_s", 0.6}}));
  ASSERT_TRUE(loop.wait_for([&](DriverLoop& l) { return joints_near(l.feedback(), start, 2e-4); }));
  const auto tool_now = [&] {
    const auto fk = driver_.call("fk", nullptr);
    return fk ? fk.value()["tool"] : nlohmann::json{};
  };
  const nlohmann::json before = tool_now();

  const auto up = driver_.call("cart_jog", {{"axis", "z"}, {"velocity", 0.02}, {"duration_s", 0.5}});
  ASSERT_TRUE(up) << up.error().message;
  EXPECT_TRUE(loop.wait_for([&](DriverLoop&) {
    const auto tool = tool_now();
    return !tool.empty() && std::fabs(tool["z_m"].get<double>() - (before["z_m"].get<double>() + 0.01)) < 5e-4 &&
           std::fabs(tool["x_m"].get<double>() - before["x_m"].get<double>()) < 5e-4 &&
           std::fabs(tool["y_m"].get<double>() - before["y_m"].get<double>()) < 5e-4;
  })) << before.dump()
      << " → " << tool_now().dump();

  // About the tool's own z axis (the pose's first angle, roll) the tool point stays where it is.
  const nlohmann::json raised = tool_now();
  const auto turned =
      driver_.call("cart_jog", {{"axis", "rz"}, {"velocity", -0.3}, {"duration_s", 0.5}, {"frame", "tool"}});
  ASSERT_TRUE(turned) << turned.error().message;
  EXPECT_TRUE(loop.wait_for([&](DriverLoop&) {
    const auto tool = tool_now();
    return !tool.empty() &&
           std::fabs(tool["roll_rad"].get<double>() - (raised["roll_rad"].get<double>() - 0.15)) < 2e-3 &&
           std::fabs(tool["x_m"].get<double>() - raised["x_m"].get<double>()) < 0.001 &&
           std::fabs(tool["z_m"].get<double>() - raised["z_m"].get<double>()) < 0.001;
  })) << raised.dump()
      << " → " << tool_now().dump();

  const auto too_fast = driver_.call("cart_jog", {{"axis", "x"}, {"velocity", 0.1}});
  ASSERT_FALSE(too_fast);
  EXPECT_NE(too_fast.error().message.find("args.velocity"), std::string::npos) << too_fast.error().message;
  const auto bad_axis = driver_.call("cart_jog", {{"axis", "w"}, {"velocity", 0.01}});
  ASSERT_FALSE(bad_axis);
  EXPECT_NE(bad_axis.error().message.find("args.axis"), std::string::npos) << bad_axis.error().message;
}

TEST_F(Parol6DriverTest, MovePoseReachesThePoseWithEitherProfile) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kJoints);
  const JointVector start = standby_rad();
  ASSERT_TRUE(loop.wait_for([&](DriverLoop& l) { return joints_near(l.feedback(), start, 1e-3); }));
  JointVector elsewhere = start;
  elsewhere[0] -= 0.3;
  elsewhere[1] += 0.2;
  elsewhere[4] += 0.3;
  const Pose target = forward_kinematics(elsewhere);
  for (const char* profile : {"trap", "poly"}) {
    nlohmann::json args{{"x_m", target.x_m},
                        {"y_m", target.y_m},
                        {"z_m", target.z_m},
                        {"roll_rad", target.roll_rad},
                        {"pitch_rad", target.pitch_rad},
                        {"yaw_rad", target.yaw_rad},
                        {"duration_s", 1.0},
                        {"profile", profile}};
    const auto moved = driver_.call("move_pose", args);
    ASSERT_TRUE(moved) << profile << ": " << moved.error().message;
    EXPECT_TRUE(loop.wait_for([&](DriverLoop&) {
      const auto tool = driver_.call("fk", nullptr);
      return tool && std::fabs(tool.value()["tool"]["x_m"].get<double>() - target.x_m) < 5e-4 &&
             std::fabs(tool.value()["tool"]["z_m"].get<double>() - target.z_m) < 5e-4;
    })) << profile;
    ASSERT_TRUE(driver_.call("move_joints", {{"joints_rad", start}, {"duration_s", 0.8}}));
    ASSERT_TRUE(loop.wait_for([&](DriverLoop& l) { return joints_near(l.feedback(), start, 3e-3); }));
  }
  const auto unreachable = driver_.call(
      "move_pose", {{"x_m", 0.9}, {"y_m", 0}, {"z_m", 0.2}, {"roll_rad", 0}, {"pitch_rad", 0}, {"yaw_rad", 0}});
  ASSERT_FALSE(unreachable);
  EXPECT_NE(unreachable.error().message.find("no joint solution"), std::string::npos) << unreachable.error().message;
}

TEST_F(Parol6DriverTest, MovesAreRefusedWhileASessionDrives) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kJoints);
  loop.set_command(position_frame(standby_rad()));
  std::this_thread::sleep_for(50ms);
  const auto refused = driver_.call("jog", {{"joint", 1}, {"velocity_rad_s", 0.1}});
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("session"), std::string::npos) << refused.error().message;
}

// The ops that move the joints or switch what the board does with them need free motors; the
// stop, the I/O, the gripper (not one of robotd's joints) and the queries do not.
TEST_F(Parol6DriverTest, TheOpsThatActOnTheJointsNeedFreeMotors) {
  EXPECT_EQ(testing::ops_needing_free_motors(driver_.describe()),
            (std::vector<std::string>{"home", "jog", "cart_jog", "move_joints", "move_pose", "move_cart", "enable",
                                      "disable", "clear_error"}));
}

// Under robotd's e-stop the board is disabled every frame and enabled at the reset, so a one-shot
// (disable included) would be dropped or undone: every one is refused until the reset. After it,
// disable reaches the board.
TEST_F(Parol6DriverTest, OneShotsAreRefusedUnderTheEstopAndDisableWorksAfterItsReset) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kJoints);
  const auto board_enabled = [&] { return sim_.control({{"op", "state"}})["enabled"].get<bool>(); };
  driver::CommandFrame estop = position_frame(standby_rad(), /*owned=*/false);
  estop.estop = true;
  loop.set_command(estop);
  ASSERT_TRUE(loop.wait_for([&](DriverLoop& /*l*/) { return !board_enabled(); })) << "the e-stop's DISABLE";
  for (const char* op : {"disable", "enable", "clear_error", "home"}) {
    const auto refused = driver_.call(op, nlohmann::json::object());
    ASSERT_FALSE(refused) << op;
    EXPECT_EQ(refused.error().code, ErrorCode::kRefused);
    EXPECT_NE(refused.error().message.find("robotd's e-stop is engaged"), std::string::npos) << refused.error().message;
  }
  loop.set_command(position_frame(standby_rad(), /*owned=*/false));
  ASSERT_TRUE(loop.wait_for([&](DriverLoop& /*l*/) { return board_enabled(); })) << "the reset's ENABLE";
  const auto disabled = driver_.call("disable", nlohmann::json::object());
  ASSERT_TRUE(disabled) << disabled.error().message;
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& /*l*/) { return !board_enabled(); }));
}

TEST_F(Parol6DriverTest, GripperAndOutputsReachTheBoard) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kJoints);
  ASSERT_TRUE(driver_.call("output", {{"out1", true}}));
  ASSERT_TRUE(driver_.call("gripper_calibrate", nullptr));
  // Like the commander's Gripper_cal(): wait for the calibration before the first move (a data
  // pack that reaches the gripper while it calibrates is not acted on, and the board sends a
  // data pack only when a field changes).
  ASSERT_TRUE(loop.wait_for([&](DriverLoop&) {
    const auto gripper = driver_.call("gripper_state", nullptr);
    return gripper && gripper.value()["answered"].get<bool>() && gripper.value()["calibrated"].get<bool>();
  }));
  ASSERT_TRUE(driver_.call("gripper", {{"position", 200}, {"speed", 255}, {"current_a", 0.5}}));
  EXPECT_TRUE(loop.wait_for([&](DriverLoop&) {
    const auto io = driver_.call("io", nullptr);
    return io && io.value()["out1"].get<bool>();
  }));
  EXPECT_TRUE(loop.wait_for(
      [&](DriverLoop&) {
        const auto gripper = driver_.call("gripper_state", nullptr);
        return gripper && gripper.value()["position"].get<int>() >= 195;
      },
      10s))
      << driver_.call("gripper_state", nullptr).value().dump() << sim_.control({{"op", "state"}})["gripper"].dump();
  const auto bad = driver_.call("gripper", {{"position", 300}});
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("args.position"), std::string::npos) << bad.error().message;
}

TEST_F(Parol6DriverTest, GripperCurrentTakesTheCommandersRangeWithItsCautions) {
  ASSERT_TRUE(driver_.connect());
  const auto normal = driver_.call("gripper", {{"position", 10}, {"current_a", 0.5}});
  ASSERT_TRUE(normal);
  EXPECT_FALSE(normal.value().contains("warning")) << normal.value().dump();
  const auto strong = driver_.call("gripper", {{"position", 10}, {"speed", 200}, {"current_a", 1.3}});
  ASSERT_TRUE(strong) << "1300 mA is the top of the gripper's range, not an error";
  EXPECT_NE(strong.value()["warning"].get<std::string>().find("above 700 mA"), std::string::npos)
      << strong.value().dump();
  const auto weak = driver_.call("gripper", {{"position", 10}, {"current_a", 0.0}});
  ASSERT_TRUE(weak);
  EXPECT_NE(weak.value()["warning"].get<std::string>().find("below 150 mA"), std::string::npos) << weak.value().dump();
  const auto too_much = driver_.call("gripper", {{"position", 10}, {"current_a", 1.4}});
  ASSERT_FALSE(too_much);
  EXPECT_NE(too_much.error().message.find("args.current_a"), std::string::npos) << too_much.error().message;
}

TEST_F(Parol6DriverTest, ALostByteCostsOneFrameNotTheLink) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kJoints);
  std::this_thread::sleep_for(100ms);
  ASSERT_TRUE(sim_.control({{"op", "garbage"}, {"bytes", 300}})["ok"].get<bool>());
  std::this_thread::sleep_for(300ms);
  EXPECT_NE(loop.last_read(), IoResult::kDisconnected) << loop.fault_text();
  const auto state = driver_.call("state", nullptr);
  ASSERT_TRUE(state);
  EXPECT_GT(state.value()["bytes_discarded"].get<std::uint64_t>(), 0U) << state.value().dump();
}

TEST_F(Parol6DriverTest, SilentBoardIsALostLinkAndRecoverReconnects) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kJoints);
  ASSERT_TRUE(sim_.control({{"op", "silence"}, {"ms", 1500}})["ok"].get<bool>());
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kDisconnected; }));
  EXPECT_NE(loop.fault_text().find("no reply from the board"), std::string::npos) << loop.fault_text();
  std::this_thread::sleep_for(1600ms);
  const auto back = loop.paused([&] { return driver_.recover(); });
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kOk; }));
}

TEST_F(Parol6DriverTest, AnAbortEndsARecoverWaitingForASilentBoardAndTheNextRecoverWorks) {
  constexpr auto kConnectTimeout = 5000ms;
  Parol6Driver driver;
  nlohmann::json params = driver_params(sim_.pty_path());
  params["connect_timeout_ms"] = kConnectTimeout.count();
  ASSERT_TRUE(driver.configure(params));
  ASSERT_TRUE(driver.connect());
  DriverLoop loop(driver, kJoints);
  ASSERT_TRUE(sim_.control({{"op", "silence"}, {"ms", 20000}})["ok"].get<bool>());
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kDisconnected; }));
  const auto recovering = loop.paused([&] {
    return testing::abort_during(
        driver, [&] { return driver.recover(); }, 200ms);
  });
  ASSERT_FALSE(recovering.returned_before_abort);
  ASSERT_FALSE(recovering.result);
  EXPECT_EQ(recovering.result.error().code, ErrorCode::kRefused);
  EXPECT_EQ(recovering.result.error().message,
            "aborted: an e-stop or shutdown pre-empted recover (waiting for the board's first reply)");
  EXPECT_LT(recovering.abort_to_return, kConnectTimeout / 5);
  testing::print_abort_figure("parol6 recover, waiting for a silent board", recovering, kConnectTimeout);

  ASSERT_TRUE(sim_.control({{"op", "silence"}, {"ms", 0}})["ok"].get<bool>());
  driver.abort_maintenance();  // before it starts: not that recover's
  const auto recovered = loop.paused([&] { return driver.recover(); });
  ASSERT_TRUE(recovered) << recovered.error().message;
  EXPECT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kOk; }));
}

TEST_F(Parol6DriverTest, KilledSimulatorIsALostLinkAndARestartedOneReconnects) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kJoints);
  sim_.kill_hard();
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kDisconnected; }));
  const auto gone = loop.paused([&] { return driver_.recover(); });
  EXPECT_FALSE(gone);
  sim_.restart();
  const auto back = loop.paused([&] { return driver_.recover(); });
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kOk; }));
}

TEST_F(Parol6DriverTest, DisconnectLeavesTheBoardIdle) {
  ASSERT_TRUE(driver_.connect());
  {
    DriverLoop loop(driver_, kJoints);
    JointVector target = standby_rad();
    target[0] += 0.05;
    loop.set_command(position_frame(target));
    std::this_thread::sleep_for(200ms);
  }
  driver_.disconnect();
  std::this_thread::sleep_for(50ms);
  EXPECT_EQ(sim_.control({{"op", "state"}})["command"], 255) << "the last frame must not keep anything moving";
}

}  // namespace
}  // namespace robotd::parol6
