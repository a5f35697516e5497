#include "sim_driver.hpp"

#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "maintenance_abort.hpp"

namespace robotd::sim {
namespace {

using driver::CommandFrame;
using driver::IoResult;
using driver::JointCommand;
using driver::JointCommandKind;
using nlohmann::json;

constexpr std::int64_t kTickNs = 1'000'000;
constexpr std::size_t kArmJoints = 6;

json arm_params() {
  return json::parse(R"({
    "model": "robotd simulated 6-joint arm",
    "joints": [
      {"name": "base", "position_min_rad": -2.5, "position_max_rad": 2.5},
      {"name": "shoulder"}, {"name": "elbow"}, {"name": "wrist_1"}, {"name": "wrist_2"}, {"name": "wrist_3"}
    ],
    "imu": true
  })");
}

CommandFrame position_frame(double position_rad, std::size_t joint_count = kArmJoints) {
  CommandFrame frame;
  frame.joint_count = joint_count;
  for (std::size_t i = 0; i < joint_count; ++i) {
    frame.joints[i] = JointCommand{.kind = JointCommandKind::kPosition, .owned = true, .position_rad = position_rad};
  }
  return frame;
}

class SimDriverTest : public ::testing::Test {
 protected:
  void start(const json& params = arm_params()) {
    const Result<void> configured = driver_.configure(params);
    ASSERT_TRUE(configured.ok()) << configured.error().message;
    ASSERT_TRUE(driver_.connect().ok());
  }

  IoResult read() {
    now_ns_ += kTickNs;
    return driver_.read_at(now_ns_, feedback_, fault_);
  }

  /// robotd's loop on a simulated 1 kHz clock: read, then write `command`.
  void run(const CommandFrame& command, double seconds) {
    const auto ticks = std::lround(seconds * 1e9 / static_cast<double>(kTickNs));
    for (long tick = 0; tick < ticks; ++tick) {
      ASSERT_EQ(read(), IoResult::kOk) << fault_.text.data();
      ASSERT_EQ(driver_.write(command, fault_), IoResult::kOk) << fault_.text.data();
    }
  }

  /// Calls `op` while another thread plays robotd's loop, writing `command` every millisecond:
  /// write() decides a disable of the motors at its tick.
  Result<json> call_while_writing(const std::string& op, const json& args, const CommandFrame& command) {
    std::atomic<bool> done{false};
    std::thread loop([&] {
      driver::FaultInfo fault;
      while (!done.load()) {
        (void)driver_.write(command, fault);
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
    });
    Result<json> result = driver_.call(op, args);
    done.store(true);
    loop.join();
    return result;
  }

  json call(const std::string& op, const json& args = json::object()) {
    Result<json> result = driver_.call(op, args);
    EXPECT_TRUE(result.ok()) << op << ": " << result.error().message;
    return result.ok() ? result.value() : json();
  }

  std::string diagnostic(const std::string& key) const {
    for (const auto& [name, value] : driver_.diagnostics()) {
      if (name == key) return value;
    }
    return "(no " + key + ")";
  }

  SimDriver driver_;
  std::int64_t now_ns_ = 5'000'000'000;
  driver::Feedback feedback_;
  driver::FaultInfo fault_;
};

TEST_F(SimDriverTest, DescribeReportsJointsLimitsCapabilitiesAndOps) {
  start();
  const driver::DeviceDescription description = driver_.describe();
  EXPECT_EQ(description.model, "robotd simulated 6-joint arm");
  EXPECT_EQ(description.native_rate_hz, 1000);
  ASSERT_EQ(description.joints.size(), kArmJoints);
  EXPECT_EQ(description.joints[1].name, "shoulder");
  EXPECT_EQ(description.joints[0].limits.position_max_rad, 2.5);
  EXPECT_EQ(description.joints[1].limits.effort_max_nm, 50);
  EXPECT_EQ(description.joints[1].default_kp, 100);
  EXPECT_EQ(description.joints[1].default_kd, 5);
  EXPECT_TRUE(description.supports_torque);
  EXPECT_TRUE(description.supports_damping);
  EXPECT_TRUE(description.supports_zero_torque);
  EXPECT_TRUE(description.has_imu);
  std::string op_names;
  std::string needing_free_motors;
  for (const driver::OpDescription& op : description.ops) {
    op_names += op.name + " ";
    if (op.needs_free_motors) needing_free_motors += op.name + " ";
    EXPECT_FALSE(op.help.empty()) << op.name;
  }
  EXPECT_EQ(op_names,
            "motors stop_feedback estop_input disconnect raise_fault set_external_torque set_imu stall "
            "slow_maintenance command_latency state ");
  // The fault injections model what happens to a robot whoever holds it; only the motors act on the joints.
  EXPECT_EQ(needing_free_motors, "motors ");
}

TEST_F(SimDriverTest, ConfigureRejectsInvalidParamsNamingTheKey) {
  const Result<void> configured = driver_.configure(json{{"joint_count", 2}, {"imu", 1}});
  ASSERT_FALSE(configured.ok());
  EXPECT_EQ(configured.error().code, ErrorCode::kInvalidArgument);
  EXPECT_EQ(configured.error().message, "imu: expected true or false, got 1");
}

TEST_F(SimDriverTest, ConnectIsRefusedBeforeConfigure) {
  const Result<void> connected = driver_.connect();
  ASSERT_FALSE(connected.ok());
  EXPECT_EQ(connected.error().code, ErrorCode::kRefused);
}

TEST_F(SimDriverTest, ReadAndWriteReportNotConnectedBeforeConnect) {
  ASSERT_TRUE(driver_.configure(arm_params()).ok());
  EXPECT_EQ(read(), IoResult::kDisconnected);
  EXPECT_EQ(fault_.code, kNotConnectedFaultCode);
  fault_.clear();
  EXPECT_EQ(driver_.write(position_frame(0), fault_), IoResult::kDisconnected);
  EXPECT_EQ(fault_.code, kNotConnectedFaultCode);
}

TEST_F(SimDriverTest, WriteReadLoopReachesAPositionTarget) {
  start();
  run(position_frame(0.8), 1.0);
  ASSERT_EQ(read(), IoResult::kOk);
  ASSERT_EQ(feedback_.joint_count, kArmJoints);
  for (std::size_t i = 0; i < kArmJoints; ++i) {
    EXPECT_NEAR(feedback_.joints[i].position_rad, 0.8, 1e-4) << i;
    EXPECT_NEAR(feedback_.joints[i].velocity_rad_s, 0, 1e-3) << i;
  }
}

TEST_F(SimDriverTest, ReadAdvancesOnTheMonotonicClock) {
  start();
  call("set_external_torque", {{"joint", 0}, {"torque_nm", -2.0}});
  for (int i = 0; i < 10; ++i) {
    ASSERT_EQ(driver_.read(feedback_, fault_), IoResult::kOk);
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  EXPECT_LT(feedback_.joints[0].position_rad, 0);
  EXPECT_LT(feedback_.joints[0].velocity_rad_s, 0);
  EXPECT_EQ(feedback_.joints[1].position_rad, 0);
}

TEST_F(SimDriverTest, UncommandedJointsAreUnpoweredAndFallUnderLoad) {
  start();
  call("set_external_torque", {{"joint", "shoulder"}, {"torque_nm", -2.0}});
  for (int tick = 0; tick < 2000; ++tick) ASSERT_EQ(read(), IoResult::kOk);
  EXPECT_EQ(feedback_.joints[1].position_rad, -3.0);
  EXPECT_EQ(feedback_.joints[1].effort_nm, 0);
  EXPECT_EQ(feedback_.joints[2].position_rad, 0);
}

TEST_F(SimDriverTest, EstopFlagDampsEveryJointWhateverTheCommand) {
  start();
  call("set_external_torque", {{"joint", "shoulder"}, {"torque_nm", -2.0}});
  CommandFrame estopped = position_frame(1.0);
  estopped.estop = true;
  run(estopped, 0.5);
  ASSERT_EQ(read(), IoResult::kOk);
  EXPECT_NEAR(feedback_.joints[1].velocity_rad_s, -2.0 / (5 + 0.5), 1e-3);
  EXPECT_NEAR(feedback_.joints[0].position_rad, 0, 1e-9);
  const json joint = call("state")["joints"][1];
  EXPECT_EQ(joint["kp"], 0);
  EXPECT_EQ(joint["kd"], 5);
  EXPECT_EQ(diagnostic("estop"), "engaged");

  run(position_frame(1.0), 1.0);
  EXPECT_EQ(diagnostic("estop"), "clear");
  EXPECT_NEAR(feedback_.joints[0].position_rad, 1.0, 1e-3);
}

TEST_F(SimDriverTest, ImpedanceCommandAppliesFeedForwardTorqueAndClampsGains) {
  start();
  CommandFrame frame;
  frame.joint_count = kArmJoints;
  frame.joints[0] = JointCommand{.kind = JointCommandKind::kImpedance, .torque_nm = 3.0};
  frame.joints[1] = JointCommand{.kind = JointCommandKind::kImpedance, .position_rad = 0.2, .kp = 1e4, .kd = 1e3};
  run(frame, 0.01);
  ASSERT_EQ(read(), IoResult::kOk);
  EXPECT_EQ(feedback_.joints[0].effort_nm, 3.0);
  EXPECT_GT(feedback_.joints[0].velocity_rad_s, 0);
  const json shoulder = call("state")["joints"][1];
  EXPECT_EQ(shoulder["command"], "impedance");
  EXPECT_EQ(shoulder["kp"], 500);
  EXPECT_EQ(shoulder["kd"], 50);
}

TEST_F(SimDriverTest, StopFeedbackReportsNoNewDataWhileTheSimulationRuns) {
  start();
  run(position_frame(0), 0.01);
  call("stop_feedback", {{"enabled", true}});
  EXPECT_EQ(diagnostic("feedback"), "stopped");
  for (int tick = 0; tick < 500; ++tick) {
    ASSERT_EQ(read(), IoResult::kNoNewData);
    ASSERT_EQ(driver_.write(position_frame(0.5), fault_), IoResult::kOk);
  }
  EXPECT_NEAR(feedback_.joints[0].position_rad, 0, 1e-6);
  call("stop_feedback", {{"enabled", false}});
  ASSERT_EQ(read(), IoResult::kOk);
  EXPECT_NEAR(feedback_.joints[0].position_rad, 0.5, 0.01);
  EXPECT_EQ(diagnostic("feedback"), "streaming");
}

TEST_F(SimDriverTest, EstopInputShowsInTheFeedbackWhilePressed) {
  start();
  ASSERT_EQ(read(), IoResult::kOk);
  EXPECT_FALSE(feedback_.estop_input);
  call("estop_input", {{"pressed", true}});
  ASSERT_EQ(read(), IoResult::kOk);
  EXPECT_TRUE(feedback_.estop_input);
  call("estop_input", {{"pressed", false}});
  ASSERT_EQ(read(), IoResult::kOk);
  EXPECT_FALSE(feedback_.estop_input);
  EXPECT_FALSE(driver_.call("estop_input", json::object()).ok()) << "pressed is required";
}

TEST_F(SimDriverTest, InjectedDisconnectReportsLinkLostUntilRecoverWithoutAPositionJump) {
  start();
  run(position_frame(0.7), 1.0);
  call("disconnect");
  EXPECT_EQ(read(), IoResult::kDisconnected);
  EXPECT_EQ(fault_.code, kLinkLostFaultCode);
  EXPECT_STREQ(fault_.text.data(), "simulated link lost (injected)");
  fault_.clear();
  EXPECT_EQ(driver_.write(position_frame(0.7), fault_), IoResult::kDisconnected);
  EXPECT_STREQ(fault_.text.data(), "simulated link lost (injected)");
  EXPECT_EQ(diagnostic("link"), "disconnected");
  for (int tick = 0; tick < 100; ++tick) ASSERT_EQ(read(), IoResult::kDisconnected);
  const double position_before_recover = call("state")["joints"][2]["position_rad"];

  ASSERT_TRUE(driver_.recover().ok());
  ASSERT_EQ(read(), IoResult::kOk);
  EXPECT_NEAR(position_before_recover, 0.7, 1e-3);
  EXPECT_NEAR(feedback_.joints[2].position_rad, position_before_recover, 1e-6);
  EXPECT_EQ(diagnostic("link"), "connected");
}

TEST_F(SimDriverTest, TimedDisconnectRefusesRecoverUntilTheOutageIsOver) {
  start();
  call("disconnect", {{"for_ms", 150}});
  EXPECT_EQ(read(), IoResult::kDisconnected);
  const Result<void> early = driver_.recover();
  ASSERT_FALSE(early.ok());
  EXPECT_EQ(early.error().code, ErrorCode::kNotAvailable);
  EXPECT_NE(early.error().message.find("simulated link still down"), std::string::npos) << early.error().message;
  EXPECT_EQ(read(), IoResult::kDisconnected);

  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  ASSERT_TRUE(driver_.recover().ok());
  EXPECT_EQ(read(), IoResult::kOk);
}

TEST_F(SimDriverTest, InjectedFaultReportsItsCodeAndTextUntilRecover) {
  start();
  run(position_frame(-0.4), 1.0);
  call("raise_fault", {{"code", 42}, {"text", "joint 3 over temperature"}});
  EXPECT_EQ(read(), IoResult::kFault);
  EXPECT_EQ(fault_.code, 42);
  EXPECT_STREQ(fault_.text.data(), "joint 3 over temperature");
  EXPECT_EQ(driver_.write(position_frame(-0.4), fault_), IoResult::kFault);
  EXPECT_EQ(diagnostic("injected_fault"), "code 42: joint 3 over temperature");
  // The controller in fault still takes frames: robotd's e-stop reaches it.
  CommandFrame estopped = position_frame(-0.4);
  estopped.estop = true;
  EXPECT_EQ(driver_.write(estopped, fault_), IoResult::kFault);
  EXPECT_EQ(read(), IoResult::kFault);
  EXPECT_EQ(diagnostic("estop"), "engaged");
  EXPECT_EQ(call("state")["injected_fault"]["code"], 42);
  const double position_before_recover = call("state")["joints"][0]["position_rad"];

  ASSERT_TRUE(driver_.recover().ok());
  ASSERT_EQ(read(), IoResult::kOk);
  EXPECT_NEAR(feedback_.joints[0].position_rad, position_before_recover, 1e-6);
  EXPECT_NEAR(position_before_recover, -0.4, 1e-3);
  EXPECT_EQ(diagnostic("injected_fault"), "none");
}

TEST_F(SimDriverTest, RecoverDoesNotResumeTheCommandFromBeforeTheFault) {
  start();
  run(position_frame(0.3), 0.1);
  call("raise_fault", {{"code", 7}, {"text", "overcurrent"}});
  ASSERT_EQ(read(), IoResult::kFault);
  ASSERT_TRUE(driver_.recover().ok());
  ASSERT_EQ(read(), IoResult::kOk);
  EXPECT_EQ(call("state")["joints"][0]["command"], "none");
  EXPECT_EQ(diagnostic("modes"), "none:6");
}

TEST_F(SimDriverTest, AbortMaintenanceEndsASlowRecoverOrResetZeroAndTheNextOneWorks) {
  start();
  constexpr auto kSlow = std::chrono::milliseconds(5000);
  call("slow_maintenance", {{"ms", kSlow.count()}});
  const auto recovering = testing::abort_during(
      driver_, [this] { return driver_.recover(); }, std::chrono::milliseconds(100));
  ASSERT_FALSE(recovering.returned_before_abort);
  ASSERT_FALSE(recovering.result.ok());
  EXPECT_EQ(recovering.result.error().code, ErrorCode::kRefused);
  EXPECT_EQ(recovering.result.error().message.rfind("aborted: an e-stop or shutdown pre-empted recover", 0), 0u)
      << recovering.result.error().message;
  EXPECT_LT(recovering.abort_to_return, kSlow / 5);
  testing::print_abort_figure("sim recover (slow_maintenance 5000 ms)", recovering, kSlow);

  call("slow_maintenance", {{"ms", kSlow.count()}});
  const auto zeroing = testing::abort_during(
      driver_, [this] { return driver_.reset_zero({}); }, std::chrono::milliseconds(100));
  ASSERT_FALSE(zeroing.returned_before_abort);
  ASSERT_FALSE(zeroing.result.ok());
  EXPECT_EQ(zeroing.result.error().message.rfind("aborted: an e-stop or shutdown pre-empted reset_zero", 0), 0u)
      << zeroing.result.error().message;
  EXPECT_LT(zeroing.abort_to_return, kSlow / 5);
  testing::print_abort_figure("sim reset_zero (slow_maintenance 5000 ms)", zeroing, kSlow);

  // A request that came before a recover() started is not that recover's: it waits and succeeds.
  call("slow_maintenance", {{"ms", 200}});
  driver_.abort_maintenance();
  const auto started = std::chrono::steady_clock::now();
  const Result<void> recovered = driver_.recover();
  ASSERT_TRUE(recovered.ok()) << recovered.error().message;
  EXPECT_GE(std::chrono::steady_clock::now() - started, std::chrono::milliseconds(200));
  EXPECT_EQ(read(), IoResult::kOk);
  driver_.abort_maintenance();
  EXPECT_TRUE(driver_.reset_zero({}).ok());
}

// The motors op models a vendor's enable/disable: write() decides a disable from its tick's
// commands, never while robotd makes a joint work (a session, or the KEEP or DAMPING one left) or
// under the e-stop, since disabled motors let go.
TEST_F(SimDriverTest, DisablingTheMotorsWaitsUntilRobotdLetsGoOfEveryJoint) {
  start();
  const json off = {{"enabled", false}};
  const auto refused_with = [&](const CommandFrame& command, const std::string& why) {
    const Result<json> disabled = call_while_writing("motors", off, command);
    ASSERT_FALSE(disabled.ok()) << why;
    EXPECT_EQ(disabled.error().code, ErrorCode::kRefused);
    EXPECT_NE(disabled.error().message.find(why), std::string::npos) << disabled.error().message;
    EXPECT_EQ(diagnostic("motors"), "enabled");
  };
  CommandFrame estop;
  estop.joint_count = kArmJoints;
  estop.estop = true;
  refused_with(estop, "robotd's e-stop damps every joint");
  refused_with(position_frame(0.2), "joint 'base' is held by a session");
  CommandFrame left_behind;  // what a session's fallbacks leave: nobody owns the joints
  left_behind.joint_count = kArmJoints;
  left_behind.joints[2] = JointCommand{.kind = JointCommandKind::kPosition, .position_rad = 0.2};  // KEEP
  refused_with(left_behind, "robotd still holds joint 'elbow' (the KEEP or DAMPING a session left it in)");
  left_behind.joints[2] = JointCommand{.kind = JointCommandKind::kImpedance, .kd = 5};  // DAMPING
  refused_with(left_behind, "robotd still holds joint 'elbow'");

  left_behind.joints[2] = JointCommand{.kind = JointCommandKind::kImpedance};  // ZERO_TORQUE
  const Result<json> disabled = call_while_writing("motors", off, left_behind);
  ASSERT_TRUE(disabled.ok()) << disabled.error().message;
  EXPECT_EQ(disabled.value(), json({{"motors", "disabled"}}));
  EXPECT_EQ(diagnostic("motors"), "disabled");
  EXPECT_EQ(call("state")["motors"], "disabled");

  // Disabled motors apply no torque, not even the e-stop's damping: the loaded shoulder coasts
  // (damped, it would sink at 2 / (5 + 0.5) = 0.36 rad/s).
  call("set_external_torque", {{"joint", "shoulder"}, {"torque_nm", -2.0}});
  CommandFrame holding = estop;
  holding.joints[1] = JointCommand{.kind = JointCommandKind::kPosition};
  run(holding, 0.1);
  EXPECT_LT(feedback_.joints[1].velocity_rad_s, -1.0);
  EXPECT_EQ(feedback_.joints[1].effort_nm, 0);

  // A session taking a joint enables them, as the op does.
  run(position_frame(0), 0.002);
  EXPECT_EQ(diagnostic("motors"), "enabled");
  ASSERT_TRUE(call_while_writing("motors", off, CommandFrame{}).ok());
  EXPECT_EQ(call("motors", {{"enabled", true}}), json({{"motors", "enabled"}}));
  EXPECT_EQ(diagnostic("motors"), "enabled");
}

// A controller slow to answer: slow_maintenance makes the next motors op wait, and the
// diagnostics say so meanwhile.
TEST_F(SimDriverTest, SlowMaintenanceDelaysTheNextMotorsOp) {
  start();
  call("slow_maintenance", {{"ms", 300}});
  const auto started = std::chrono::steady_clock::now();
  std::atomic<bool> answered{false};
  std::thread enabling([&] {
    call("motors", {{"enabled", true}});
    answered.store(true);
  });
  bool seen_switching = false;
  while (!seen_switching && !answered.load()) {
    seen_switching = diagnostic("motors").find("switching") != std::string::npos;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  enabling.join();
  EXPECT_TRUE(seen_switching) << "the diagnostics never showed the motors op waiting";
  EXPECT_GE(std::chrono::steady_clock::now() - started, std::chrono::milliseconds(300));
  EXPECT_EQ(diagnostic("motors"), "enabled");
  const auto again = std::chrono::steady_clock::now();
  call("motors", {{"enabled", true}});
  EXPECT_LT(std::chrono::steady_clock::now() - again, std::chrono::milliseconds(300)) << "only the next op waits";
}

TEST_F(SimDriverTest, DisconnectDisablesTheMotors) {
  start();
  EXPECT_EQ(diagnostic("motors"), "enabled");
  driver_.disconnect();
  EXPECT_EQ(diagnostic("motors"), "disabled");
  EXPECT_EQ(diagnostic("link"), "disconnected");
  EXPECT_EQ(read(), IoResult::kDisconnected);
  EXPECT_EQ(fault_.code, kNotConnectedFaultCode);
}

TEST_F(SimDriverTest, ResetZeroMakesAJointReadZeroWhereItStands) {
  start();
  CommandFrame frame = position_frame(0);
  frame.joints[1].position_rad = 1.0;
  run(frame, 1.0);
  const std::array<int, 1> shoulder{1};
  ASSERT_TRUE(driver_.reset_zero(shoulder).ok());
  // Commands are in the reported frame: holding where the joint stands is now a target of 0.
  ASSERT_EQ(driver_.write(position_frame(0), fault_), IoResult::kOk);
  ASSERT_EQ(read(), IoResult::kOk);
  EXPECT_NEAR(feedback_.joints[1].position_rad, 0, 1e-6);
  EXPECT_NEAR(call("state")["joints"][1]["zero_offset_rad"].get<double>(), 1.0, 1e-3);

  run(position_frame(0), 0.5);
  EXPECT_NEAR(feedback_.joints[1].position_rad, 0, 1e-6);
  EXPECT_NEAR(feedback_.joints[2].position_rad, 0, 1e-6);
}

// robotd stops writing while reset_zero runs (maintenance): the target written before it still
// means where it was meant, so the joint holds still, and only reads differently.
TEST_F(SimDriverTest, ResetZeroLeavesAHeldJointWhereItStands) {
  start();
  CommandFrame frame = position_frame(0);
  frame.joints[1].position_rad = 0.3;
  run(frame, 1.0);
  ASSERT_TRUE(driver_.reset_zero({}).ok());
  for (int tick = 0; tick < 500; ++tick) {
    ASSERT_EQ(read(), IoResult::kOk);
    ASSERT_NEAR(feedback_.joints[1].position_rad, 0, 1e-3) << "tick " << tick;
  }
}

TEST_F(SimDriverTest, ResetZeroOfNoListedJointsZeroesEveryJoint) {
  start();
  run(position_frame(-0.6), 1.0);
  ASSERT_TRUE(driver_.reset_zero({}).ok());
  ASSERT_EQ(driver_.write(position_frame(0), fault_), IoResult::kOk);
  ASSERT_EQ(read(), IoResult::kOk);
  for (std::size_t i = 0; i < kArmJoints; ++i) EXPECT_NEAR(feedback_.joints[i].position_rad, 0, 1e-6) << i;
}

TEST_F(SimDriverTest, HardStopsFollowTheReportedZero) {
  start();
  CommandFrame frame = position_frame(0);
  frame.joints[0].position_rad = 1.0;
  run(frame, 1.0);
  const std::array<int, 1> base{0};
  ASSERT_TRUE(driver_.reset_zero(base).ok());
  frame.joints[0].position_rad = 3.0;  // beyond the base's 2.5 rad limit in the reported frame
  run(frame, 2.0);
  EXPECT_EQ(feedback_.joints[0].position_rad, 2.5);
}

TEST_F(SimDriverTest, ResetZeroRejectsAnOutOfRangeJoint) {
  start();
  const std::array<int, 2> joints{0, 6};
  const Result<void> reset = driver_.reset_zero(joints);
  ASSERT_FALSE(reset.ok());
  EXPECT_EQ(reset.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(reset.error().message.find("joint index 6"), std::string::npos) << reset.error().message;
  ASSERT_EQ(read(), IoResult::kOk);
  EXPECT_EQ(call("state")["joints"][0]["zero_offset_rad"], 0);
}

TEST_F(SimDriverTest, StateOpReportsJointsCommandsAndGains) {
  start();
  CommandFrame frame = position_frame(0.25, 2);
  frame.joints[1].kp = 40;
  frame.joints[1].kd = 2;
  run(frame, 1.0);
  const json state = call("state");
  ASSERT_EQ(state["joints"].size(), kArmJoints);
  const json& base = state["joints"][0];
  EXPECT_EQ(base["name"], "base");
  EXPECT_NEAR(base["position_rad"].get<double>(), 0.25, 1e-4);
  EXPECT_NEAR(base["velocity_rad_s"].get<double>(), 0, 1e-3);
  EXPECT_NEAR(base["torque_nm"].get<double>(), 0, 1e-2);
  EXPECT_EQ(base["command"], "position");
  EXPECT_EQ(base["kp"], 100);
  EXPECT_EQ(base["kd"], 5);
  EXPECT_EQ(state["joints"][1]["kp"], 40);
  EXPECT_EQ(state["joints"][1]["kd"], 2);
  EXPECT_EQ(state["joints"][2]["command"], "none");
  EXPECT_EQ(state["estop"], false);
  EXPECT_EQ(state["link"], "connected");
  EXPECT_EQ(state["feedback"], "streaming");
  EXPECT_TRUE(state["injected_fault"].is_null());
  EXPECT_TRUE(driver_.call("state", nullptr).ok());
}

TEST_F(SimDriverTest, DiagnosticsCountCommandKinds) {
  start();
  EXPECT_EQ(diagnostic("modes"), "none:6");
  CommandFrame frame;
  frame.joint_count = 4;
  for (std::size_t i = 0; i < 4; ++i) frame.joints[i].kind = JointCommandKind::kImpedance;
  run(frame, 0.002);
  EXPECT_EQ(diagnostic("modes"), "impedance:4,none:2");
  run(position_frame(0), 0.002);
  EXPECT_EQ(diagnostic("modes"), "position:6");
}

TEST_F(SimDriverTest, SetExternalTorqueByNameOrIndexLoadsOnlyThatJoint) {
  start();
  EXPECT_EQ(call("set_external_torque", {{"joint", "elbow"}, {"torque_nm", 1.5}})["joint"], "elbow");
  EXPECT_EQ(call("set_external_torque", {{"joint", 4}, {"torque_nm", -0.5}})["joint"], "wrist_2");
  run(position_frame(0), 1.0);
  EXPECT_NEAR(feedback_.joints[2].position_rad, 1.5 / 100, 1e-4);
  EXPECT_NEAR(feedback_.joints[4].position_rad, -0.5 / 100, 1e-4);
  EXPECT_NEAR(feedback_.joints[3].position_rad, 0, 1e-9);
  EXPECT_EQ(call("state")["joints"][2]["external_torque_nm"], 1.5);
}

TEST_F(SimDriverTest, ImuReportsAStillBase) {
  start();
  ASSERT_EQ(read(), IoResult::kOk);
  ASSERT_TRUE(feedback_.has_imu);
  EXPECT_EQ(feedback_.imu.orientation_xyzw, (std::array<double, 4>{0, 0, 0, 1}));
  EXPECT_EQ(feedback_.imu.angular_velocity_rad_s, (std::array<double, 3>{0, 0, 0}));
  EXPECT_EQ(feedback_.imu.linear_acceleration_m_s2, (std::array<double, 3>{0, 0, 9.81}));
}

TEST_F(SimDriverTest, WithoutImuFeedbackHasNone) {
  start(json{{"joint_count", 2}});
  ASSERT_EQ(read(), IoResult::kOk);
  EXPECT_FALSE(feedback_.has_imu);
  EXPECT_EQ(feedback_.imu.linear_acceleration_m_s2, (std::array<double, 3>{0, 0, 0}));
}

TEST_F(SimDriverTest, CommandLatencyIsWriteTimeMinusTheClientsSendTime) {
  start();
  CommandFrame frame;
  frame.joint_count = 6;
  for (int i = 0; i < 10; ++i) {
    // write() stamps with the real CLOCK_MONOTONIC: a command "sent" 2 ms ago arrives ≥ 2 ms late.
    timespec now{};
    clock_gettime(CLOCK_MONOTONIC, &now);
    frame.newest_command_sent_ns = static_cast<std::int64_t>(now.tv_sec) * 1'000'000'000 + now.tv_nsec - 2'000'000;
    ASSERT_EQ(driver_.write(frame, fault_), IoResult::kOk);
  }
  frame.newest_command_sent_ns = 0;  // ticks without a new command are not samples
  ASSERT_EQ(driver_.write(frame, fault_), IoResult::kOk);

  const json latency = call("command_latency", {{"samples", true}, {"reset", true}});
  EXPECT_EQ(latency["count"], 10);
  EXPECT_EQ(latency["samples_ns"].size(), 10U);
  EXPECT_GE(latency["p50_us"].get<double>(), 2000.0);
  EXPECT_LT(latency["max_us"].get<double>(), 100'000.0);
  EXPECT_EQ(call("command_latency")["count"], 0) << "reset must start a new measurement";
}

TEST_F(SimDriverTest, UnknownOpIsAnInvalidArgumentListingTheOps) {
  start();
  const Result<json> result = driver_.call("levitate", json::object());
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().code, ErrorCode::kInvalidArgument);
  EXPECT_EQ(result.error().message,
            R"(unknown op "levitate" (the sim driver has: motors, stop_feedback, estop_input, disconnect, )"
            R"(raise_fault, set_external_torque, set_imu, stall, slow_maintenance, command_latency, state))");
}

TEST_F(SimDriverTest, BadOpArgumentsAreInvalidArgumentsNamingOpAndExpectation) {
  start();
  const struct {
    const char* op;
    const char* args;
    const char* error;
  } cases[] = {
      {"stop_feedback", "{}", "stop_feedback: args.enabled: missing; expected true or false"},
      {"stop_feedback", R"({"enabled": "yes"})", R"(stop_feedback: args.enabled: expected true or false, got "yes")"},
      {"raise_fault", R"({"code": 0, "text": "x"})", "raise_fault: args.code: expected an integer other than 0"},
      {"raise_fault", R"({"code": 3, "text": ""})", "raise_fault: args.text: expected 1..159 characters, got 0"},
      {"set_external_torque", R"({"joint": "knee", "torque_nm": 1})",
       R"(set_external_torque: args.joint: no joint is named "knee")"},
      {"set_external_torque", R"({"joint": 6, "torque_nm": 1})",
       "set_external_torque: args.joint: expected an integer in 0..5, got 6"},
      {"set_external_torque", R"({"joint": 1.5, "torque_nm": 1})",
       "set_external_torque: args.joint: expected a joint name or an index 0..5, got 1.5"},
      {"state", R"({"verbose": true})", R"(state: args.verbose: unknown key (this op takes no arguments))"},
      {"disconnect", "[]", "disconnect: args: expected an object, got []"},
      {"disconnect", R"({"for_ms": -1})", "disconnect: args.for_ms: expected an integer in 0..600000, got -1"},
      {"slow_maintenance", R"({"ms": 0})", "slow_maintenance: args.ms: expected an integer in 1..60000, got 0"},
      {"motors", "{}", "motors: args.enabled: missing; expected true or false"},
  };
  for (const auto& test_case : cases) {
    const Result<json> result = driver_.call(test_case.op, json::parse(test_case.args));
    ASSERT_FALSE(result.ok()) << test_case.op << " " << test_case.args;
    EXPECT_EQ(result.error().code, ErrorCode::kInvalidArgument);
    EXPECT_EQ(result.error().message.rfind(test_case.error, 0), 0u) << result.error().message;
    EXPECT_NE(result.error().message.find("(expects {"), std::string::npos) << result.error().message;
  }
  EXPECT_EQ(diagnostic("link"), "connected");
  EXPECT_EQ(diagnostic("injected_fault"), "none");
}

TEST_F(SimDriverTest, StateReadsDuringTheLoopSeeConsistentSnapshots) {
  start(json{{"joint_count", 6}});
  std::atomic<bool> loop_done{false};
  std::atomic<int> reads{0};
  int inconsistent = 0;
  std::thread reader([&] {
    while (!loop_done.load()) {
      const Result<json> state = driver_.call("state", json::object());
      const json& joints = state.value()["joints"];
      for (const json& joint : joints) inconsistent += joint["position_rad"] != joints[0]["position_rad"] ? 1 : 0;
      driver_.diagnostics();
      reads.fetch_add(1);
    }
  });
  const CommandFrame frame = position_frame(1.0);
  bool loop_ok = true;
  for (int tick = 0; loop_ok && (tick < 2000 || (reads.load() < 50 && tick < 200'000)); ++tick) {
    now_ns_ += kTickNs;
    loop_ok =
        driver_.read_at(now_ns_, feedback_, fault_) == IoResult::kOk && driver_.write(frame, fault_) == IoResult::kOk;
  }
  loop_done.store(true);
  reader.join();
  EXPECT_TRUE(loop_ok) << fault_.text.data();
  EXPECT_GE(reads.load(), 50);
  EXPECT_EQ(inconsistent, 0);
}

}  // namespace
}  // namespace robotd::sim
