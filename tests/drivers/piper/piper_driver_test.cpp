// The PiPER driver against robotd-piper-sim over the stand-in CAN bus: real sockets, a real
// simulator process, and a 1 kHz thread that calls read()/write() the way robotd's loop does.
#include "driver/piper_driver.hpp"

#include <chrono>
#include <cmath>
#include <fstream>
#include <iterator>
#include <thread>

#include <gtest/gtest.h>

#include "driver/piper_ops.hpp"
#include "driver_loop.hpp"
#include "kinematics/piper_kinematics.hpp"
#include "maintenance_abort.hpp"
#include "piper_sim_process.hpp"

namespace robotd::piper {
namespace {

using namespace std::chrono_literals;
using driver::IoResult;
using driver::JointCommandKind;
using testing::DriverLoop;
using testing::PiperSimProcess;

nlohmann::json driver_params(const std::string& bus_path, const nlohmann::json& extra = nlohmann::json::object()) {
  nlohmann::json params{{"can", {{"transport", "standin"}, {"path", bus_path}}}, {"feedback_timeout_ms", 100}};
  params.update(extra);
  return params;
}

using testing::kPiperDeviceJoints;

driver::CommandFrame positions(const std::array<double, 6>& q, bool owned = true) {
  driver::CommandFrame frame;
  frame.joint_count = kPiperDeviceJoints;
  for (std::size_t j = 0; j < 6; ++j)
    frame.joints[j] = {.kind = JointCommandKind::kPosition, .owned = owned, .position_rad = q[j]};
  return frame;
}

class PiperDriverTest : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_TRUE(driver_.configure(driver_params(sim_.bus_path()))); }

  PiperSimProcess sim_{PiperSimProcess::unique_path("piper-driver")};
  PiperDriver driver_;
};

TEST_F(PiperDriverTest, ConnectChecksFeedbackAndReadsTheFirmware) {
  ASSERT_TRUE(driver_.connect());
  const driver::Diagnostics diagnostics = driver_.diagnostics();
  const auto firmware =
      std::find_if(diagnostics.begin(), diagnostics.end(), [](const auto& kv) { return kv.first == "firmware"; });
  ASSERT_NE(firmware, diagnostics.end());
  EXPECT_EQ(firmware->second, "S-V1.8-2");
  const driver::DeviceDescription description = driver_.describe();
  ASSERT_EQ(description.joints.size(), 7U);
  EXPECT_EQ(description.joints[6].name, "gripper");
  EXPECT_NEAR(description.joints[0].limits.position_max_rad, 2.6179, 1e-9);
  EXPECT_NEAR(description.joints[2].limits.position_min_rad, -2.967, 1e-9);
  EXPECT_TRUE(description.has_end_pose);
  EXPECT_EQ(description.kinematic_model, "piper");
  driver_.disconnect();
}

TEST_F(PiperDriverTest, TheKinematicModelFollowsTheDhVariant) {
  PiperDriver plain;
  ASSERT_TRUE(plain.configure(driver_params(sim_.bus_path(), {{"dh", "plain"}})));
  EXPECT_EQ(plain.describe().kinematic_model, "piper_plain_dh");
}

// The ops that act on the joints robotd drives need free motors: robotd refuses them while a
// session holds one. The queries do not.
TEST_F(PiperDriverTest, TheOpsThatActOnTheJointsNeedFreeMotors) {
  EXPECT_EQ(testing::ops_needing_free_motors(driver_.describe()),
            (std::vector<std::string>{"end_pose", "move_c", "mode", "gripper", "enable", "disable", "master_slave",
                                      "master_home", "set_joint_limits", "set_max_speed", "joint_config", "set_max_acc",
                                      "param_config", "set_end_limits", "set_crash_protection", "set_gripper_params"}));
}

TEST_F(PiperDriverTest, ConnectSaysWhatIsWrongWhenNothingListens) {
  PiperDriver lonely;
  ASSERT_TRUE(lonely.configure(driver_params("/tmp/robotd-piper-nobody-here.sock")));
  const auto connected = lonely.connect();
  ASSERT_FALSE(connected);
  EXPECT_EQ(connected.error().code, ErrorCode::kNotAvailable);
  EXPECT_NE(connected.error().message.find("no CAN bus at /tmp/robotd-piper-nobody-here.sock"), std::string::npos)
      << connected.error().message;
}

TEST_F(PiperDriverTest, ConnectSaysWhenTheBusIsSilent) {
  ASSERT_TRUE(sim_.control({{"op", "silence"}, {"ms", 3000}})["ok"].get<bool>());
  std::this_thread::sleep_for(20ms);
  const auto connected = driver_.connect();
  ASSERT_FALSE(connected);
  EXPECT_EQ(connected.error().code, ErrorCode::kNotAvailable);
  EXPECT_NE(connected.error().message.find("no frames on"), std::string::npos) << connected.error().message;
  EXPECT_NE(connected.error().message.find("powered on"), std::string::npos) << connected.error().message;
}

TEST_F(PiperDriverTest, ConfigureRejectsBadParamsWithTheirPath) {
  PiperDriver driver;
  const auto configured = driver.configure({{"can", {{"transport", "standin"}, {"path", "/tmp/x.sock"}}},
                                            {"command_rate_hz", 2000},
                                            {"joints", {{"joint9", {{"kp_max", 1}}}}},
                                            {"firmware", "latest"},
                                            {"sped_percent", 50}});
  ASSERT_FALSE(configured);
  const std::string& message = configured.error().message;
  EXPECT_NE(message.find("command_rate_hz"), std::string::npos) << message;
  EXPECT_NE(message.find("joint9"), std::string::npos) << message;
  EXPECT_NE(message.find("firmware"), std::string::npos) << message;
  EXPECT_NE(message.find("sped_percent"), std::string::npos) << message;
  const auto missing = driver.configure(nlohmann::json::object());
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("can"), std::string::npos) << missing.error().message;
}

// DAMPING and KEEP hold an arm joint with its default gains: 0 would let it go while robotd
// reports them, so configure() refuses it, naming the joint.
TEST_F(PiperDriverTest, ConfigureRefusesDefaultGainsThatWouldNotHoldAJoint) {
  PiperDriver driver;
  const auto configured = driver.configure(
      driver_params(sim_.bus_path(), {{"joints", {{"joint3", {{"default_kd", 0}}}, {"joint5", {{"default_kp", 0}}}}}}));
  ASSERT_FALSE(configured);
  const std::string& message = configured.error().message;
  EXPECT_NE(message.find("joints.joint3.default_kd: expected more than 0 for joint3, got 0"), std::string::npos)
      << message;
  EXPECT_NE(message.find("joints.joint5.default_kp: expected more than 0 for joint5, got 0"), std::string::npos)
      << message;
  EXPECT_TRUE(driver.configure(driver_params(sim_.bus_path(), {{"joints", {{"gripper", {{"default_kd", 0}}}}}})))
      << "the gripper is position-controlled: it has no damping to lose";
}

// The shipped configs' PiPER params are valid (robotd --check-config cannot see driver params).
TEST(PiperConfigs, ShippedExamplesAndTheDefaultConfigParse) {
  for (const char* file : {"config/examples/piper.json", "config/examples/piper-sim.json", "config/robotd.json"}) {
    std::ifstream in(std::string(ROBOTD_SOURCE_DIR) + "/" + file);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::vector<std::string> errors;
    const auto config = parse_json_with_comments(text, file, errors);
    ASSERT_TRUE(config) << join_errors(errors);
    int piper_devices = 0;
    for (const auto& device : config->at("devices")) {
      if (device.at("driver") != "piper") continue;
      ++piper_devices;
      const auto params = parse_piper_params(device.at("params"));
      EXPECT_TRUE(params) << file << ": " << params.error().message;
    }
    EXPECT_EQ(piper_devices, 1) << file;
  }
}

TEST_F(PiperDriverTest, StreamedPositionsEnableTheArmAndMoveIt) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kPiperDeviceJoints);
  const std::array<double, 6> target{0.3, 0.4, -0.5, 0.2, -0.3, 0.6};
  loop.set_command(positions(target));
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& l) {
    const driver::Feedback feedback = l.feedback();
    for (std::size_t j = 0; j < 6; ++j) {
      if (std::fabs(feedback.joints[j].position_rad - target[j]) > 0.002) return false;
    }
    return true;
  })) << "feedback: "
      << loop.feedback().joints[0].position_rad;
  const nlohmann::json state = sim_.control({{"op", "state"}});
  EXPECT_TRUE(state["joints"][0]["enabled"].get<bool>()) << state.dump();
  EXPECT_EQ(state["move_mode"].get<int>(), 1) << state.dump();  // MOVE J
  EXPECT_EQ(loop.last_write(), IoResult::kOk);
  const driver::Feedback feedback = loop.feedback();
  EXPECT_TRUE(feedback.has_end_pose);
  const CartesianPose fk = forward_kinematics(target, DhVariant::kOffset);
  EXPECT_NEAR(feedback.end_pose.position_m[0], fk.x_m, 0.002);
}

TEST_F(PiperDriverTest, ImpedanceCommandsDriveTheArmInMitMode) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kPiperDeviceJoints);
  driver::CommandFrame frame = positions({0, 0, 0, 0, 0, 0});
  frame.joints[5] = {.kind = JointCommandKind::kImpedance, .owned = true, .position_rad = 0.5, .kp = 10, .kd = 0.8};
  loop.set_command(frame);
  EXPECT_TRUE(loop.wait_for([](DriverLoop& l) { return std::fabs(l.feedback().joints[5].position_rad - 0.5) < 0.02; }))
      << loop.feedback().joints[5].position_rad;
  const nlohmann::json state = sim_.control({{"op", "state"}});
  EXPECT_TRUE(state["mit"].get<bool>()) << state.dump();
}

TEST_F(PiperDriverTest, EstopStopsTheArmAndResetResumesIt) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kPiperDeviceJoints);
  loop.set_command(positions({0.2, 0.2, -0.2, 0, 0, 0}));
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return std::fabs(l.feedback().joints[0].position_rad - 0.2) < 0.01; }));
  driver::CommandFrame stopped = positions({0.2, 0.2, -0.2, 0, 0, 0});
  stopped.estop = true;
  loop.set_command(stopped);
  EXPECT_TRUE(loop.wait_for([&](DriverLoop&) { return sim_.control({{"op", "state"}})["estop"].get<bool>(); }));
  EXPECT_EQ(loop.last_write(), IoResult::kOk) << "robotd's own e-stop is not a fault: " << loop.fault_text();

  loop.set_command(positions({0.3, 0.2, -0.2, 0, 0, 0}));
  EXPECT_TRUE(loop.wait_for([](DriverLoop& l) { return std::fabs(l.feedback().joints[0].position_rad - 0.3) < 0.01; }))
      << "resumed, re-enabled and moving again";
  EXPECT_FALSE(sim_.control({{"op", "state"}})["estop"].get<bool>());
  EXPECT_EQ(loop.write_faults(), 0) << "the arm's e-stop until it took the resume is robotd's own, not a fault: "
                                    << loop.fault_text();
}

TEST_F(PiperDriverTest, ArmFaultIsReportedWithItsTextAndRecoverClearsIt) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kPiperDeviceJoints);
  loop.set_command(positions({0, 0, 0, 0, 0, 0}));
  ASSERT_TRUE(sim_.control({{"op", "raise_error"}, {"arm_status", 7}})["ok"].get<bool>());
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_write() == IoResult::kFault; }));
  EXPECT_NE(loop.fault_text().find("collision"), std::string::npos) << loop.fault_text();
  EXPECT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kOk; }))
      << "joint states keep flowing during an arm fault";

  const auto recovered = loop.paused([&] { return driver_.recover(); });
  ASSERT_TRUE(recovered) << recovered.error().message;
  EXPECT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_write() == IoResult::kOk; }));
}

TEST_F(PiperDriverTest, DriverFaultBitsNameTheJointAndTheProblem) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kPiperDeviceJoints);
  loop.set_command(positions({0, 0, 0, 0, 0, 0}));
  ASSERT_TRUE(sim_.control({{"op", "raise_error"}, {"joint", 3}, {"driver_status_bits", 0x04}})["ok"].get<bool>());
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_write() == IoResult::kFault; }));
  EXPECT_NE(loop.fault_text().find("joint 3"), std::string::npos) << loop.fault_text();
  EXPECT_NE(loop.fault_text().find("over-current"), std::string::npos) << loop.fault_text();
}

TEST_F(PiperDriverTest, SilentArmIsALostLinkAndRecoverWaitsForItsReturn) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kPiperDeviceJoints);
  const auto silent_until = std::chrono::steady_clock::now() + 2s;
  ASSERT_TRUE(sim_.control({{"op", "silence"}, {"ms", 2000}})["ok"].get<bool>());
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kDisconnected; }));
  EXPECT_NE(loop.fault_text().find("no arm feedback"), std::string::npos) << loop.fault_text();
  const auto early = loop.paused([&] { return driver_.recover(); });  // waits up to connect_timeout_ms (500)
  ASSERT_FALSE(early) << "recovered while the arm was still silent";
  EXPECT_NE(early.error().message.find("no frames on"), std::string::npos) << early.error().message;
  std::this_thread::sleep_until(silent_until + 100ms);
  const auto later = loop.paused([&] { return driver_.recover(); });
  ASSERT_TRUE(later) << later.error().message;
  EXPECT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() != IoResult::kDisconnected; }));
}

TEST_F(PiperDriverTest, AnAbortEndsARecoverOrResetZeroWaitingForTheArmAndTheNextOnesWork) {
  constexpr auto kConnectTimeout = 5000ms;
  constexpr auto kReplyTimeout = 3000ms;
  PiperDriver driver;
  ASSERT_TRUE(driver.configure(driver_params(sim_.bus_path(), {{"connect_timeout_ms", kConnectTimeout.count()},
                                                               {"reply_timeout_ms", kReplyTimeout.count()}})));
  ASSERT_TRUE(driver.connect());
  DriverLoop loop(driver, kPiperDeviceJoints);
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kOk; }));

  // No acknowledge: reset_zero waits reply_timeout_ms for each joint's.
  ASSERT_TRUE(sim_.control({{"op", "drop_replies"}, {"enabled", true}})["ok"].get<bool>());
  const auto zeroing = loop.paused([&] {
    return testing::abort_during(
        driver, [&] { return driver.reset_zero(std::array{4}); }, 200ms);
  });
  ASSERT_FALSE(zeroing.returned_before_abort);
  ASSERT_FALSE(zeroing.result);
  EXPECT_EQ(zeroing.result.error().code, ErrorCode::kRefused);
  EXPECT_EQ(zeroing.result.error().message.rfind(
                "aborted: an e-stop or shutdown pre-empted reset_zero (waiting for the acknowledge of 0x", 0),
            0U)
      << zeroing.result.error().message;
  EXPECT_LT(zeroing.abort_to_return, kReplyTimeout / 5);
  testing::print_abort_figure("piper reset_zero, waiting for an acknowledge", zeroing, kReplyTimeout);
  ASSERT_TRUE(sim_.control({{"op", "drop_replies"}, {"enabled", false}})["ok"].get<bool>());
  driver.abort_maintenance();  // before it starts: not that reset_zero's
  const auto zeroed = loop.paused([&] { return driver.reset_zero(std::array{4}); });
  ASSERT_TRUE(zeroed) << zeroed.error().message;

  // A silent arm: the link is lost, and recover reconnects and waits for its feedback.
  ASSERT_TRUE(sim_.control({{"op", "silence"}, {"ms", 20000}})["ok"].get<bool>());
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kDisconnected; }));
  const auto recovering = loop.paused([&] {
    return testing::abort_during(
        driver, [&] { return driver.recover(); }, 200ms);
  });
  ASSERT_FALSE(recovering.returned_before_abort);
  ASSERT_FALSE(recovering.result);
  EXPECT_EQ(recovering.result.error().message,
            "aborted: an e-stop or shutdown pre-empted recover (waiting for the arm's feedback)");
  EXPECT_LT(recovering.abort_to_return, kConnectTimeout / 5);
  testing::print_abort_figure("piper recover, waiting for a silent arm", recovering, kConnectTimeout);
  ASSERT_TRUE(sim_.control({{"op", "silence"}, {"ms", 0}})["ok"].get<bool>());
  driver.abort_maintenance();
  const auto recovered = loop.paused([&] { return driver.recover(); });
  ASSERT_TRUE(recovered) << recovered.error().message;
  EXPECT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kOk; }));
}

TEST_F(PiperDriverTest, KilledSimulatorIsALostLinkAndARestartedOneReconnects) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kPiperDeviceJoints);
  sim_.kill_hard();
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kDisconnected; }));
  EXPECT_NE(loop.fault_text().find("CAN link closed"), std::string::npos) << loop.fault_text();
  const auto while_gone = loop.paused([&] { return driver_.recover(); });
  ASSERT_FALSE(while_gone);
  EXPECT_EQ(while_gone.error().code, ErrorCode::kNotAvailable);
  sim_.restart();
  const auto back = loop.paused([&] { return driver_.recover(); });
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_TRUE(loop.wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kOk; }));
}

TEST_F(PiperDriverTest, CanBusErrorIsAFaultThatNamesTheError) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kPiperDeviceJoints);
  ASSERT_TRUE(sim_.control({{"op", "bus_error"}})["ok"].get<bool>());
  // One kFault read: robotd's loop latches it (the test loop keeps its text).
  ASSERT_TRUE(loop.wait_for([](DriverLoop& l) { return l.fault_text().find("CAN bus error") != std::string::npos; }))
      << loop.fault_text();
  EXPECT_NE(loop.fault_text().find("CAN bus error on stand-in"), std::string::npos) << loop.fault_text();
  EXPECT_NE(loop.fault_text().find("bus off"), std::string::npos) << loop.fault_text();
}

TEST_F(PiperDriverTest, GarbageOnTheBusIsCountedNotFatal) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kPiperDeviceJoints);
  ASSERT_TRUE(sim_.control({{"op", "garbage"}, {"frames", 500}})["ok"].get<bool>());
  std::this_thread::sleep_for(200ms);
  EXPECT_NE(loop.last_read(), IoResult::kDisconnected);
  const auto fps = driver_.call("can_fps", nullptr);
  ASSERT_TRUE(fps) << fps.error().message;
  EXPECT_GT(fps.value()["unknown_frames"].get<std::uint64_t>(), 0U) << fps.value().dump();
}

TEST_F(PiperDriverTest, QueriesReturnWhatTheArmHolds) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kPiperDeviceJoints);
  const auto limits = driver_.call("limits", nullptr);
  ASSERT_TRUE(limits) << limits.error().message;
  ASSERT_EQ(limits.value()["joints"].size(), 6U) << limits.value().dump();
  EXPECT_NEAR(limits.value()["joints"][0]["max_angle_rad"].get<double>(), 2.618, 0.002) << limits.value().dump();
  for (const char* op : {"acc_limits", "firmware", "end_limits", "crash_protection", "gripper_params", "state", "fk",
                         "can_fps", "master_commands"}) {
    const auto reply = driver_.call(op, nlohmann::json::object());
    EXPECT_TRUE(reply) << op << ": " << reply.error().message;
  }
  const auto firmware = driver_.call("firmware", nullptr);
  ASSERT_TRUE(firmware);
  EXPECT_EQ(firmware.value()["software_version"], "S-V1.8-2") << firmware.value().dump();
  const auto fk = driver_.call("fk", {{"joints_rad", {0, 0, 0, 0, 0, 0}}});
  ASSERT_TRUE(fk);
  EXPECT_NEAR(fk.value()["flange"]["x_m"].get<double>(), 0.056128, 1e-5) << fk.value().dump();
  EXPECT_NEAR(fk.value()["flange"]["z_m"].get<double>(), 0.213266, 1e-5) << fk.value().dump();
  ASSERT_EQ(fk.value()["links"].size(), 6U) << "every link's pose, as GetFK";
  EXPECT_NEAR(fk.value()["links"][0]["z_m"].get<double>(), 0.123, 1e-9);  // link 1: the base's d1
  EXPECT_EQ(fk.value()["links"][5], fk.value()["flange"]);
}

TEST_F(PiperDriverTest, SettingsAreAcknowledgedAndReadBack) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kPiperDeviceJoints);
  const auto crash = driver_.call("set_crash_protection", {{"levels", {1, 2, 3, 4, 5, 6}}});
  ASSERT_TRUE(crash) << crash.error().message;
  const auto levels = driver_.call("crash_protection", nullptr);
  ASSERT_TRUE(levels);
  EXPECT_EQ(levels.value()["levels"], nlohmann::json({1, 2, 3, 4, 5, 6}));
  const auto limits = driver_.call("set_joint_limits", {{"joint", 4}, {"max_angle_rad", 1.5}, {"min_angle_rad", -1.5}});
  ASSERT_TRUE(limits) << limits.error().message;
  const auto read_back = driver_.call("limits", nullptr);
  ASSERT_TRUE(read_back);
  EXPECT_NEAR(read_back.value()["joints"][3]["max_angle_rad"].get<double>(), 1.5, 0.002) << read_back.value().dump();
  for (const auto& [op, args] : std::vector<std::pair<std::string, nlohmann::json>>{
           {"set_max_speed", {{"joint", "all"}, {"max_speed_rad_s", 2.0}}},
           {"joint_config", {{"joint", "all"}, {"clear_error", true}}},
           {"set_max_acc", {{"joint", 2}, {"max_acc_rad_s2", 3.0}}},
           {"param_config", {{"payload", "half"}}},
           {"set_end_limits", {{"max_linear_velocity_m_s", 0.5}}},
           {"set_gripper_params", {{"max_range_mm", 100}}}}) {
    const auto reply = driver_.call(op, args);
    EXPECT_TRUE(reply) << op << ": " << reply.error().message;
  }
  const auto gripper = driver_.call("gripper_params", nullptr);
  ASSERT_TRUE(gripper);
  EXPECT_EQ(gripper.value()["max_range_mm"], 100);
  // reset_zero is maintenance: robotd pauses the loop and the driver reads the acknowledge itself.
  const auto zeroed = loop.paused([&] { return driver_.reset_zero(std::array{4}); });
  ASSERT_TRUE(zeroed) << zeroed.error().message;
}

// At connect the driver reads each joint's limits from the arm (0x472 → 0x473, the SDK's
// PiperInit); the arm's narrower range wins over the config, a wider one never does.
TEST_F(PiperDriverTest, TheArmsNarrowerLimitsNarrowTheConfigAtConnect) {
  ASSERT_TRUE(driver_.connect());
  {
    DriverLoop loop(driver_, kPiperDeviceJoints);
    const auto narrowed =
        driver_.call("set_joint_limits", {{"joint", 1}, {"max_angle_rad", 1.0}, {"max_speed_rad_s", 1.5}});
    ASSERT_TRUE(narrowed) << narrowed.error().message;
  }
  driver_.disconnect();
  ASSERT_TRUE(driver_.connect());
  const driver::DeviceDescription description = driver_.describe();
  EXPECT_NEAR(description.joints[0].limits.position_max_rad, 1.0, 0.002);
  EXPECT_NEAR(description.joints[0].limits.position_min_rad, -2.618, 0.002) << "the arm's own, as configured";
  EXPECT_NEAR(description.joints[0].limits.velocity_max_rad_s, 1.5, 0.002);
  EXPECT_NEAR(description.joints[1].limits.position_max_rad, 3.14, 0.002) << "unchanged joints keep the config";
  const driver::Diagnostics diagnostics = driver_.diagnostics();
  const auto note =
      std::find_if(diagnostics.begin(), diagnostics.end(), [](const auto& kv) { return kv.first == "arm_limits"; });
  ASSERT_NE(note, diagnostics.end());
  EXPECT_NE(note->second.find("joint1 max 2.618→1.000 rad"), std::string::npos) << note->second;
  driver_.disconnect();

  PiperDriver narrow_config;  // a config narrower than the arm stays as it is
  ASSERT_TRUE(
      narrow_config.configure(driver_params(sim_.bus_path(), {{"joints", {{"joint1", {{"position_max_rad", 0.5}}}}}})));
  ASSERT_TRUE(narrow_config.connect());
  EXPECT_NEAR(narrow_config.describe().joints[0].limits.position_max_rad, 0.5, 1e-9);
  narrow_config.disconnect();
}

// SetSDKJointLimitParam and SetSDKGripperRangeParam as ops: they narrow the limits the driver
// describes (robotd takes them after the op), never widen them, keep a joint's narrowing
// across a reconnect, and the gripper op is range-checked against the narrowed stroke.
TEST_F(PiperDriverTest, SdkLimitOpsNarrowTheDescribedLimitsAtRunTimeAndNeverWidenThem) {
  ASSERT_TRUE(driver_.connect());
  {
    DriverLoop loop(driver_, kPiperDeviceJoints);
    const auto narrowed = driver_.call("sdk_joint_limit", {{"joint", "j1"}, {"min_rad", -1.0}, {"max_rad", 0.5}});
    ASSERT_TRUE(narrowed) << narrowed.error().message;
    EXPECT_EQ(narrowed.value()["joint"], "joint1");
    driver::DeviceDescription description = driver_.describe();
    EXPECT_DOUBLE_EQ(description.joints[0].limits.position_min_rad, -1.0);
    EXPECT_DOUBLE_EQ(description.joints[0].limits.position_max_rad, 0.5);
    EXPECT_NEAR(description.joints[1].limits.position_max_rad, 3.14, 1e-9) << "other joints keep theirs";

    const auto widened = driver_.call("sdk_joint_limit", {{"joint", "j1"}, {"min_rad", -1.0}, {"max_rad", 1.0}});
    ASSERT_FALSE(widened);
    EXPECT_NE(widened.error().message.find("robotd only narrows limits at run time"), std::string::npos)
        << widened.error().message;
    EXPECT_NE(widened.error().message.find("restart robotd"), std::string::npos) << widened.error().message;
    const auto empty = driver_.call("sdk_joint_limit", {{"joint", 2}, {"min_rad", 1.0}, {"max_rad", 1.0}});
    ASSERT_FALSE(empty);
    EXPECT_NE(empty.error().message.find("must be below max"), std::string::npos) << empty.error().message;
    const auto bad_joint = driver_.call("sdk_joint_limit", {{"joint", "j7"}, {"min_rad", 0}, {"max_rad", 1}});
    ASSERT_FALSE(bad_joint);
    EXPECT_NE(bad_joint.error().message.find("j6"), std::string::npos) << bad_joint.error().message;
    description = driver_.describe();
    EXPECT_DOUBLE_EQ(description.joints[0].limits.position_max_rad, 0.5) << "a refusal changes nothing";

    const auto gripper = driver_.call("sdk_gripper_range", {{"min_m", 0.0}, {"max_m", 0.04}});
    ASSERT_TRUE(gripper) << gripper.error().message;
    EXPECT_DOUBLE_EQ(driver_.describe().joints[6].limits.position_max_rad, 0.04);
    const auto wider_gripper = driver_.call("sdk_gripper_range", {{"min_m", 0.0}, {"max_m", 0.07}});
    ASSERT_FALSE(wider_gripper);
    EXPECT_NE(wider_gripper.error().message.find("robotd only narrows"), std::string::npos);
    const auto beyond = driver_.call("gripper", {{"stroke_m", 0.05}});
    ASSERT_FALSE(beyond) << "the gripper op is held to the narrowed stroke";
    EXPECT_NE(beyond.error().message.find("0.04"), std::string::npos) << beyond.error().message;
  }
  driver_.disconnect();
  ASSERT_TRUE(driver_.connect());  // the arm's limits are read again: the narrowing stays
  EXPECT_DOUBLE_EQ(driver_.describe().joints[0].limits.position_max_rad, 0.5);
  EXPECT_DOUBLE_EQ(driver_.describe().joints[0].limits.position_min_rad, -1.0);
  driver_.disconnect();
}

TEST_F(PiperDriverTest, OpsRejectBadArgumentsWithUsage) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kPiperDeviceJoints);
  const auto bad_joint = driver_.call("set_max_acc", {{"joint", 9}, {"max_acc_rad_s2", 1}});
  ASSERT_FALSE(bad_joint);
  EXPECT_EQ(bad_joint.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(bad_joint.error().message.find("args.joint"), std::string::npos) << bad_joint.error().message;
  EXPECT_NE(bad_joint.error().message.find("expects"), std::string::npos) << bad_joint.error().message;
  const auto bad_levels = driver_.call("set_crash_protection", {{"levels", {1, 2}}});
  ASSERT_FALSE(bad_levels);
  EXPECT_NE(bad_levels.error().message.find("expected 6 levels, got 2"), std::string::npos);
  const auto typo = driver_.call("end_pose", {{"x", 0.1}});
  ASSERT_FALSE(typo);
  EXPECT_NE(typo.error().message.find("x_m"), std::string::npos) << typo.error().message;
  const auto unknown = driver_.call("fly", nullptr);
  ASSERT_FALSE(unknown);
  EXPECT_NE(unknown.error().message.find("end_pose"), std::string::npos) << "lists the ops";
}

// EnableFkCal / DisableFkCal at run time: the flange pose stops and resumes without a reconnect.
TEST_F(PiperDriverTest, FkCalculationTurnsOffAndOnAtRunTime) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kPiperDeviceJoints);
  EXPECT_TRUE(loop.wait_for([](DriverLoop& l) { return l.feedback().has_end_pose; }));
  const auto off = driver_.call("fk_calculation", {{"enabled", false}});
  ASSERT_TRUE(off) << off.error().message;
  EXPECT_EQ(off.value()["enabled"], false);
  EXPECT_TRUE(loop.wait_for([](DriverLoop& l) { return !l.feedback().has_end_pose; }));
  const auto asked = driver_.call("fk_calculation", nlohmann::json::object());
  ASSERT_TRUE(asked);
  EXPECT_EQ(asked.value()["enabled"], false) << "without \"enabled\" the op answers the setting in force";
  ASSERT_TRUE(driver_.call("fk_calculation", {{"enabled", true}}));
  EXPECT_TRUE(loop.wait_for([](DriverLoop& l) { return l.feedback().has_end_pose; }));
}

// ArmParamEnquiryAndConfig query 0x03 goes out; the index comes from the status that follows.
TEST_F(PiperDriverTest, TrajectoryIndexQueryIsSentAndAnswered) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kPiperDeviceJoints);
  const auto index = driver_.call("trajectory_index", nullptr);
  ASSERT_TRUE(index) << index.error().message;
  EXPECT_EQ(index.value()["trajectory_index"], 0);
  EXPECT_EQ(sim_.control({{"op", "state"}})["frames_received"].value("0x477", 0), 1);
  const auto firmware = driver_.call("firmware", nullptr);
  ASSERT_TRUE(firmware);
  EXPECT_EQ(firmware.value()["protocol"], "V2") << "GetCurrentProtocolVersion";
}

// The ops refuse, with the codec's text, a value the arm does not take before sending anything:
// at a speed unit of 0.5 mrad/s per count, 3 rad/s is 6000 counts, beyond the SDK's 0 … 3000.
TEST_F(PiperDriverTest, OpsRefuseWhatTheArmDoesNotTake) {
  PiperDriver fine_units;
  ASSERT_TRUE(
      fine_units.configure(driver_params(sim_.bus_path(), {{"units", {{"max_speed_rad_s_per_count", 0.0005}}}})));
  ASSERT_TRUE(fine_units.connect());
  DriverLoop loop(fine_units, kPiperDeviceJoints);
  const auto refused = fine_units.call("set_max_speed", {{"joint", 1}, {"max_speed_rad_s", 3.0}});
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().code, ErrorCode::kInvalidArgument);
  EXPECT_EQ(refused.error().message,
            "set_max_speed: 0x474 max joint speed must be 0 … 3000 counts (0 … 3 rad/s at the SDK's unit)");
  EXPECT_EQ(sim_.control({{"op", "state"}})["frames_received"].value("0x474", 0), 0) << "nothing was sent";
}

// ReqMasterArmMoveToHome (0x191): the SDK's three modes, byte for byte; anything else refused.
TEST_F(PiperDriverTest, MasterHomeSendsTheLeaderArmRequest) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kPiperDeviceJoints);
  const auto sent = driver_.call("master_home", {{"mode", "leader_to_zero"}});
  ASSERT_TRUE(sent) << sent.error().message;
  EXPECT_EQ(sent.value()["sent"], "ReqMasterArmMoveToHome");
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& /*l*/) {
    return sim_.control({{"op", "state"}})["frames_received"].value("0x191", 0) == 1;
  }));
  const auto unknown = driver_.call("master_home", {{"mode", "home"}});
  ASSERT_FALSE(unknown);
  EXPECT_NE(unknown.error().message.find("leader_to_zero"), std::string::npos) << unknown.error().message;
}

TEST_F(PiperDriverTest, EndPoseMovesTheArmAndSessionsComeFirst) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kPiperDeviceJoints);
  const CartesianPose target = forward_kinematics({0.2, 0.6, -0.8, 0.1, 0.3, 0.2}, DhVariant::kOffset);
  nlohmann::json args = to_json(target);
  ASSERT_TRUE(driver_.call("enable", nullptr));
  const auto moved = driver_.call("end_pose", args);
  ASSERT_TRUE(moved) << moved.error().message;
  EXPECT_TRUE(loop.wait_for(
      [&](DriverLoop& l) {
        const driver::Feedback f = l.feedback();
        return std::fabs(f.end_pose.position_m[0] - target.x_m) < 0.001 &&
               std::fabs(f.end_pose.position_m[2] - target.z_m) < 0.001;
      },
      10s))
      << loop.feedback().end_pose.position_m[0];

  const auto joint_frames = [&] { return sim_.control({{"op", "state"}})["frames_received"].value("0x155", 0); };
  const int joint_frames_before = joint_frames();
  loop.set_command(positions({0.2, 0.6, -0.8, 0.1, 0.3, 0.2}));
  // The session's joints stream: the driver's write() has seen them.
  ASSERT_TRUE(loop.wait_for([&](DriverLoop& /*l*/) { return joint_frames() > joint_frames_before; }));
  const auto refused = driver_.call("end_pose", args);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().code, ErrorCode::kRefused);
  EXPECT_NE(refused.error().message.find("session"), std::string::npos) << refused.error().message;
}

// disable drops the arm, so write() decides it at its tick, from that tick's commands: refused
// under the e-stop, for a session's joint and while robotd's stream still holds a joint (the KEEP
// a session left); a free arm is disabled. Streaming then stays off until a session takes joints
// again, so enabling the arm holds it where it is.
TEST_F(PiperDriverTest, DisableIsDecidedAtTheTickAndNeverDropsAJointRobotdHolds) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kPiperDeviceJoints);
  const auto enabled_joints = [&] {
    const nlohmann::json state = sim_.control({{"op", "state"}});
    int count = 0;
    for (const auto& joint : state["joints"]) count += joint["enabled"].get<bool>() ? 1 : 0;
    return count;
  };
  const auto frames_received = [&](const char* id) {
    return sim_.control({{"op", "state"}})["frames_received"].value(id, 0);
  };
  const auto refused_with = [&](const std::string& why) {
    const auto disabled = driver_.call("disable", nullptr);
    ASSERT_FALSE(disabled) << why;
    EXPECT_EQ(disabled.error().code, ErrorCode::kRefused);
    EXPECT_NE(disabled.error().message.find(why), std::string::npos) << disabled.error().message;
  };
  driver::CommandFrame estop;
  estop.joint_count = kPiperDeviceJoints;
  estop.estop = true;
  loop.set_command(estop);
  std::this_thread::sleep_for(20ms);
  refused_with("disable: robotd's e-stop is engaged");

  loop.set_command(positions({0.1, 0, 0, 0, 0, 0}));  // a session: the arm is enabled for it
  ASSERT_TRUE(loop.wait_for([&](DriverLoop& /*l*/) { return enabled_joints() == 6; }));
  refused_with("a session owns joints of this arm");
  loop.set_command(positions({0.1, 0, 0, 0, 0, 0}, /*owned=*/false));  // the KEEP it left
  refused_with("robotd still holds joint 1 (the KEEP or DAMPING a session left it in)");
  EXPECT_EQ(enabled_joints(), 6);

  driver::CommandFrame let_go;  // released with ZERO_TORQUE: nothing holds the arm
  let_go.joint_count = kPiperDeviceJoints;
  for (std::size_t j = 0; j < 6; ++j) let_go.joints[j].kind = JointCommandKind::kImpedance;
  loop.set_command(let_go);
  std::this_thread::sleep_for(20ms);
  const auto disabled = driver_.call("disable", nullptr);
  ASSERT_TRUE(disabled) << disabled.error().message;
  EXPECT_EQ(disabled.value()["enabled"], nlohmann::json::array({false, false, false, false, false, false}));
  EXPECT_EQ(enabled_joints(), 0);

  const auto enabled = driver_.call("enable", nullptr);
  ASSERT_TRUE(enabled) << enabled.error().message;
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& /*l*/) { return enabled_joints() == 6; }));
  const int mit_frames = frames_received("0x15A");
  std::this_thread::sleep_for(100ms);
  EXPECT_EQ(frames_received("0x15A"), mit_frames) << "robotd streamed to the arm an op took";
  const int joint_frames = frames_received("0x155");
  loop.set_command(positions({0, 0, 0, 0, 0, 0}));
  EXPECT_TRUE(loop.wait_for([&](DriverLoop& /*l*/) { return frames_received("0x155") > joint_frames; }))
      << "a session's stream did not resume";
}

TEST_F(PiperDriverTest, GripperFollowsItsJointAndItsOp) {
  ASSERT_TRUE(driver_.connect());
  DriverLoop loop(driver_, kPiperDeviceJoints);
  driver::CommandFrame frame = positions({0, 0, 0, 0, 0, 0});
  frame.joints[6] = {.kind = JointCommandKind::kPosition, .owned = true, .position_rad = 0.03};
  loop.set_command(frame);
  EXPECT_TRUE(loop.wait_for([](DriverLoop& l) {
    return std::fabs(l.feedback().joints[6].position_rad - 0.03) < 0.001;
  })) << loop.feedback().joints[6].position_rad;
  loop.set_command(positions({0, 0, 0, 0, 0, 0}, /*owned=*/false));
  std::this_thread::sleep_for(20ms);
  const auto opened = driver_.call("gripper", {{"stroke_m", 0.05}, {"effort_nm", 1.5}});
  ASSERT_TRUE(opened) << opened.error().message;
  EXPECT_TRUE(
      loop.wait_for([](DriverLoop& l) { return std::fabs(l.feedback().joints[6].position_rad - 0.05) < 0.001; }));
}

}  // namespace
}  // namespace robotd::piper
