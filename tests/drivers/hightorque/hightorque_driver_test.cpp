// The HighTorque driver without robotd: its params checked key by key, then the driver against
// robotd-hightorque-sim over real file descriptors (two CAN-FD stand-in buses, or two USB-CDC
// board ptys) and robotd-imu-sim's pty, called at 1 kHz the way robotd's loop calls it.
#include "driver/hightorque_driver.hpp"

#include <chrono>
#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "driver_loop.hpp"
#include "hightorque_sim_process.hpp"
#include "imu_sim_process.hpp"
#include "maintenance_abort.hpp"
#include "robotd/driver/json_reader.hpp"

namespace robotd::hightorque {
namespace {

using namespace std::chrono_literals;
using driver::IoResult;
using testing::diagnostic;
using testing::DriverLoop;
using testing::HighTorqueSimProcess;
using testing::ImuSimProcess;
using testing::joints_near;
using testing::position_frame;

// Two buses: "a" carries motors 1-3, "b" motors 1-2. Joint 0 is mounted reversed with an offset.
constexpr std::size_t kJoints = 5;
constexpr double kJoint0Offset = 0.2;

nlohmann::json motor_entry(const std::string& name, const std::string& bus, int id) {
  return {{"name", name}, {"bus", bus}, {"id", id}};
}

nlohmann::json valid_params(const std::vector<nlohmann::json>& buses) {
  nlohmann::json motors =
      nlohmann::json::array({motor_entry("a1", "a", 1), motor_entry("a2", "a", 2), motor_entry("a3", "a", 3),
                             motor_entry("b1", "b", 1), motor_entry("b2", "b", 2)});
  motors[0]["direction"] = -1;
  motors[0]["zero_offset_rad"] = kJoint0Offset;
  return {{"model", "two test buses"},
          {"motor_defaults",
           {{"position_min_rad", -1.5},
            {"position_max_rad", 1.5},
            {"velocity_max_rad_s", 10.0},
            {"kp_max", 300},
            {"kd_max", 20},
            {"default_kp", 40},
            {"default_kd", 1.0},
            {"effort_max_nm", 30}}},
          {"motors", motors},
          {"buses", buses}};
}

nlohmann::json placeholder_buses() {
  return nlohmann::json::array({{{"name", "a"}, {"can", {{"transport", "standin"}, {"path", "/tmp/unused-a"}}}},
                                {{"name", "b"}, {"can", {{"transport", "standin"}, {"path", "/tmp/unused-b"}}}}});
}

/// Every joint within 0.01 rad of its target and at rest.
bool settled_at(const driver::Feedback& feedback, const std::vector<double>& target) {
  for (std::size_t j = 0; j < target.size(); ++j) {
    if (std::fabs(feedback.joints[j].velocity_rad_s) > 0.02) return false;
  }
  return joints_near(feedback, target, 0.01);
}

/// configure()'s error for `params`, or "" when it was accepted.
std::string configure_error(const nlohmann::json& params) {
  HighTorqueDriver driver;
  const auto configured = driver.configure(params);
  return configured ? std::string() : configured.error().message;
}

TEST(HighTorqueParams, EachMistakeNamesItsKeyAndWhatIsExpected) {
  ASSERT_EQ(configure_error(valid_params(placeholder_buses())), "");
  struct Case {
    const char* what;
    nlohmann::json params;
    std::vector<std::string> expected;
  };
  std::vector<Case> cases;
  auto with = [](auto change) {
    nlohmann::json params = valid_params(placeholder_buses());
    change(params);
    return params;
  };
  cases.push_back({"direction 0",
                   with([](auto& p) { p["motors"][1]["direction"] = 0; }),
                   {"motors[1].direction", "expected 1 or -1"}});
  cases.push_back({"an unknown bus",
                   with([](auto& p) { p["motors"][2]["bus"] = "c"; }),
                   {"motors[2].bus", "no bus named \"c\"", "a, b"}});
  cases.push_back({"an id used twice",
                   with([](auto& p) { p["motors"][2]["id"] = 1; }),
                   {"motors[2].id", "used twice on bus \"a\""}});
  cases.push_back({"a name used twice",
                   with([](auto& p) { p["motors"][4]["name"] = "a1"; }),
                   {"motors[4].name", "\"a1\" is used by another motor"}});
  cases.push_back({"a bus without motors",
                   with([](auto& p) {
                     p["buses"].push_back({{"name", "c"}, {"can", {{"transport", "standin"}, {"path", "/tmp/c"}}}});
                   }),
                   {"bus \"c\" has no motor"}});
  cases.push_back({"a default kp above kp_max",
                   with([](auto& p) { p["motors"][3]["default_kp"] = 400; }),
                   {"motors[3].default_kp", "at most kp_max"}});
  cases.push_back({"inverted limits",
                   with([](auto& p) {
                     p["motors"][0]["position_min_rad"] = 1.0;
                     p["motors"][0]["position_max_rad"] = -1.0;
                   }),
                   {"motors[0].position_min_rad", "less than position_max_rad"}});
  cases.push_back({"a motor model nobody defined",
                   with([](auto& p) { p["motors"][0]["model"] = "9999_1"; }),
                   {"motors[0].model", "no motor model \"9999_1\""}});
  cases.push_back({"a misspelt key", with([](auto& p) { p["motor_timout_ms"] = 100; }), {"motor_timout_ms"}});
  cases.push_back({"a damping gain of 0 (DAMPING would free-wheel)",
                   with([](auto& p) { p["motors"][2]["default_kd"] = 0; }),
                   {"motors[2].default_kd", "expected more than 0 for joint \"a3\"", "free-wheel"}});
  cases.push_back({"a holding stiffness of 0 for every motor",
                   with([](auto& p) { p["motor_defaults"]["default_kp"] = 0; }),
                   {"motor_defaults.default_kp", "expected more than 0 for every motor"}});
  cases.push_back({"a motor watchdog too long to brake a falling robot",
                   with([](auto& p) { p["motor_timeout_ms"] = 5000; }),
                   {"motor_timeout_ms", "expected 20..1000", "or 0 to disarm", "got 5000"}});
  cases.push_back({"a motor watchdog shorter than normal jitter",
                   with([](auto& p) { p["motor_timeout_ms"] = 5; }),
                   {"motor_timeout_ms", "expected 20..1000", "got 5"}});
  cases.push_back({"an IMU without its serial line",
                   with([](auto& p) {
                     p["imu"] = {{"source", "yesense"}};
                   }),
                   {"imu", "serial"}});
  for (const Case& c : cases) {
    const std::string error = configure_error(c.params);
    ASSERT_NE(error, "") << c.what << " was accepted";
    for (const std::string& part : c.expected) {
      EXPECT_NE(error.find(part), std::string::npos) << c.what << ": \"" << error << "\" lacks \"" << part << "\"";
    }
  }
}

// The shipped configs' HighTorque params pass the driver's checks (robotd --check-config cannot
// see driver params), the default config's PI Plus included.
TEST(HighTorqueConfigs, ShippedExamplesAndTheDefaultConfigParse) {
  for (const char* file :
       {"config/examples/hightorque.json", "config/examples/hightorque-sim.json", "config/robotd.json"}) {
    std::ifstream in(std::string(ROBOTD_SOURCE_DIR) + "/" + file);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::vector<std::string> errors;
    const auto config = parse_json_with_comments(text, file, errors);
    ASSERT_TRUE(config) << join_errors(errors);
    // The examples are one device entry; robotd.json has a list of them.
    const nlohmann::json devices =
        config->contains("devices") ? config->at("devices") : nlohmann::json::array({*config});
    int hightorque_devices = 0;
    for (const auto& device : devices) {
      if (device.at("driver") != "hightorque") continue;
      ++hightorque_devices;
      const auto params = parse_hightorque_params(device.at("params"));
      EXPECT_TRUE(params) << file << ": " << params.error().message;
    }
    EXPECT_EQ(hightorque_devices, 1) << file;
  }
}

// Without default gains a motor still holds in DAMPING and KEEP (kd 1.0, kp 40); disarming the
// motors' own watchdog is a config decision that the diagnostics shout about.
TEST(HighTorqueParams, DefaultGainsHoldAndADisarmedWatchdogIsShownLoudly) {
  nlohmann::json params = valid_params(placeholder_buses());
  params["motor_defaults"].erase("default_kp");
  params["motor_defaults"].erase("default_kd");
  params["motor_timeout_ms"] = 0;
  HighTorqueDriver driver;
  const auto configured = driver.configure(params);
  ASSERT_TRUE(configured) << configured.error().message;
  for (const driver::JointDescription& joint : driver.describe().joints) {
    EXPECT_EQ(joint.default_kp, 40) << joint.name;
    EXPECT_EQ(joint.default_kd, 1.0) << joint.name;
  }
  EXPECT_EQ(diagnostic(driver, "motor_watchdog").rfind("DISARMED by params.motor_timeout_ms = 0", 0), 0U)
      << diagnostic(driver, "motor_watchdog");
  params["motor_timeout_ms"] = 200;
  ASSERT_TRUE(driver.configure(params));
  EXPECT_EQ(diagnostic(driver, "motor_watchdog"), "armed: a motor brakes 200 ms after its last command");
}

/// A frame that commands `joint` only; every other motor is left uncommanded.
driver::CommandFrame one_joint(std::size_t joint, const driver::JointCommand& command) {
  driver::CommandFrame frame;
  frame.joint_count = kJoints;
  frame.joints[joint] = command;
  return frame;
}

/// The driver on the simulator's two buses, either transport, optionally with an IMU.
class HighTorqueDriverTest : public ::testing::TestWithParam<HighTorqueSimProcess::Link::Kind> {
 protected:
  static std::vector<HighTorqueSimProcess::Link> links() {
    if (GetParam() == HighTorqueSimProcess::Link::Kind::kBoard) {
      return {HighTorqueSimProcess::board("1-3"), HighTorqueSimProcess::board("1-2")};
    }
    return {HighTorqueSimProcess::standin("1-3"), HighTorqueSimProcess::standin("1-2")};
  }
  nlohmann::json bus_entry(std::size_t index, const std::string& name) const {
    if (GetParam() == HighTorqueSimProcess::Link::Kind::kBoard) {
      return {{"name", name}, {"board", {{"device", sim_.bus_path(index)}, {"baud", 4000000}}}};
    }
    return {{"name", name}, {"can", {{"transport", "standin"}, {"path", sim_.bus_path(index)}}}};
  }
  nlohmann::json params() const {
    nlohmann::json params = valid_params({bus_entry(0, "a"), bus_entry(1, "b")});
    params["feedback_timeout_ms"] = 50;
    if (GetParam() == HighTorqueSimProcess::Link::Kind::kBoard) {
      // The simulator's board motors speak the 5047_36's torque unit (the CAN-FD ones N·m).
      params["motor_models"] = {{"5047_36", {{"torque_per_unit", 0.004938}, {"gain_factor", 1.0}}}};
      params["motor_defaults"]["model"] = "5047_36";
    }
    return params;
  }
  void bring_up(const nlohmann::json& configured) {
    ASSERT_TRUE(driver_.configure(configured));
    const auto connected = driver_.connect();
    ASSERT_TRUE(connected) << connected.error().message;
    loop_ = std::make_unique<DriverLoop>(driver_, kJoints);
    ASSERT_TRUE(loop_->wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kOk; }));
  }
  void TearDown() override {
    loop_.reset();
    driver_.disconnect();
  }
  nlohmann::json sim_motor(std::size_t bus, int id) const { return sim_.motor_state(bus, id); }
  std::uint64_t ticks() {
    return driver_.call("state", nlohmann::json::object()).value()["ticks"].get<std::uint64_t>();
  }
  /// Sets `frame` and waits until the loop has written it for at least ten ticks.
  void command_and_settle(const driver::CommandFrame& frame) {
    loop_->set_command(frame);
    const std::uint64_t from = ticks();
    ASSERT_TRUE(loop_->wait_for([&](DriverLoop& /*l*/) { return ticks() >= from + 20; }));
  }
  bool sim_ok(const nlohmann::json& request) const { return sim_.control(request)["ok"].get<bool>(); }

  HighTorqueSimProcess sim_{links(), {"--quiet"}};
  HighTorqueDriver driver_;
  std::unique_ptr<DriverLoop> loop_;
};

TEST_P(HighTorqueDriverTest, DescribeTellsTheJointMapAndTheOps) {
  ASSERT_TRUE(driver_.configure(params()));
  const driver::DeviceDescription description = driver_.describe();
  ASSERT_EQ(description.joints.size(), kJoints);
  EXPECT_EQ(description.joints[3].name, "b1");
  EXPECT_DOUBLE_EQ(description.joints[0].zero_position_rad, kJoint0Offset);
  EXPECT_DOUBLE_EQ(description.joints[2].limits.position_max_rad, 1.5);
  EXPECT_DOUBLE_EQ(description.joints[4].default_kp, 40);
  EXPECT_FALSE(description.has_imu);
  std::vector<std::string> ops;
  ops.reserve(description.ops.size());
  for (const auto& op : description.ops) ops.push_back(op.name);
  EXPECT_EQ(ops, (std::vector<std::string>{"state", "motor_info", "set_motor_timeout", "reboot_motor"}));
  // The two that act on the motors need them free; a reboot is still decided at its tick too.
  EXPECT_EQ(testing::ops_needing_free_motors(description),
            (std::vector<std::string>{"set_motor_timeout", "reboot_motor"}));
}

// Joint targets become MIT frames through the joint map (direction, zero offset), every bus
// carries a frame each tick, and the feedback comes back in the joint frame.
TEST_P(HighTorqueDriverTest, PositionTargetsReachEachMotorThroughTheJointMap) {
  ASSERT_NO_FATAL_FAILURE(bring_up(params()));
  const std::vector<double> target{0.5, -0.3, 0.2, 0.4, -0.1};
  loop_->set_command(position_frame(target));
  ASSERT_TRUE(loop_->wait_for([&](DriverLoop& l) { return settled_at(l.feedback(), target); }))
      << "feedback never settled at the targets";
  // Joint 0 = −motor + 0.2, so the motor itself sits at −(0.5 − 0.2).
  EXPECT_NEAR(sim_motor(0, 1)["position_rad"].get<double>(), -0.3, 0.01);
  EXPECT_NEAR(sim_motor(1, 1)["position_rad"].get<double>(), 0.4, 0.01);
  EXPECT_NEAR(sim_motor(1, 2)["kp"].get<double>(), 40, 0.5) << "a position command without gains uses the defaults";

  const nlohmann::json before = sim_.state();
  std::this_thread::sleep_for(1s);
  const nlohmann::json after = sim_.state();
  for (std::size_t b = 0; b < 2; ++b) {
    const auto frames = after["buses"][b]["frames_received"].get<std::uint64_t>() -
                        before["buses"][b]["frames_received"].get<std::uint64_t>();
    EXPECT_GT(frames, 800U) << "bus " << b << " should see about one frame per 1 ms tick";
  }
  EXPECT_EQ(diagnostic(driver_, "link"), "up");
}

// A motor that stops answering is a fault naming it; once it answers again recover() clears it.
TEST_P(HighTorqueDriverTest, ASilentMotorIsAFaultThatNamesIt) {
  ASSERT_NO_FATAL_FAILURE(bring_up(params()));
  ASSERT_TRUE(sim_ok({{"op", "mute"}, {"bus", 1}, {"motor", 2}, {"on", true}}));
  ASSERT_TRUE(loop_->wait_for([](DriverLoop& l) { return l.last_write() == IoResult::kFault; }, 2s));
  EXPECT_NE(loop_->fault_text().find("motor b2 (bus 'b' id 2) silent"), std::string::npos) << loop_->fault_text();
  ASSERT_TRUE(sim_ok({{"op", "mute"}, {"bus", 1}, {"motor", 2}, {"on", false}}));
  ASSERT_TRUE(loop_->wait_for([](DriverLoop& l) { return l.last_write() == IoResult::kOk; }, 2s));
}

// A motor's own fault code arrives as text; recover() clears it once the cause is gone.
TEST_P(HighTorqueDriverTest, AMotorFaultIsReportedAndRecovered) {
  ASSERT_NO_FATAL_FAILURE(bring_up(params()));
  ASSERT_TRUE(sim_ok({{"op", "set_fault"}, {"bus", 0}, {"motor", 3}, {"code", 0x14}}));
  ASSERT_TRUE(loop_->wait_for([](DriverLoop& l) { return l.last_write() == IoResult::kFault; }, 2s));
  EXPECT_NE(loop_->fault_text().find("motor a3 (bus 'a' id 3)"), std::string::npos) << loop_->fault_text();
  const auto refused = loop_->paused([&] { return driver_.recover(); });
  ASSERT_FALSE(refused) << "the motor still reports its fault";
  EXPECT_NE(refused.error().message.find("a3"), std::string::npos) << refused.error().message;
  ASSERT_TRUE(sim_ok({{"op", "clear_fault"}, {"bus", 0}, {"motor", 3}}));
  const auto recovered = loop_->paused([&] { return driver_.recover(); });
  ASSERT_TRUE(recovered) << recovered.error().message;
  EXPECT_TRUE(loop_->wait_for([](DriverLoop& l) { return l.last_write() == IoResult::kOk; }, 2s))
      << loop_->fault_text();
}

// Garbage on a bus is dropped and counted; the motors keep being served.
TEST_P(HighTorqueDriverTest, GarbageOnABusIsDroppedAndTheMotorsStayServed) {
  ASSERT_NO_FATAL_FAILURE(bring_up(params()));
  ASSERT_TRUE(sim_ok({{"op", "garbage"}, {"bus", 0}, {"count", 20}}));
  // CAN-FD frames that decode to nothing are dropped; the board's junk bytes are skipped.
  const char* counted = GetParam() == HighTorqueSimProcess::Link::Kind::kBoard ? "skipped 0 bytes" : "dropped 0";
  ASSERT_TRUE(loop_->wait_for(
      [&](DriverLoop&) { return diagnostic(driver_, "bus.a.frames").find(counted) == std::string::npos; }, 2s))
      << diagnostic(driver_, "bus.a.frames");
  std::this_thread::sleep_for(200ms);
  EXPECT_EQ(loop_->last_read(), IoResult::kOk) << loop_->fault_text();
  EXPECT_EQ(loop_->last_write(), IoResult::kOk) << loop_->fault_text();
}

// A bus cut mid-motion is a lost link naming the bus; recover() reconnects once the bus is back,
// and the motors report where they really are — the feedback does not jump.
TEST_P(HighTorqueDriverTest, ALostBusIsReportedAndRecoverReconnectsWithoutAJump) {
  ASSERT_NO_FATAL_FAILURE(bring_up(params()));
  const std::vector<double> target{0.4, 0.1, -0.2, 0.3, 0.0};
  loop_->set_command(position_frame(target));
  ASSERT_TRUE(loop_->wait_for([&](DriverLoop& l) { return settled_at(l.feedback(), target); }));
  ASSERT_TRUE(sim_ok({{"op", "disconnect"}, {"bus", 1}, {"for_ms", 300}}));
  ASSERT_TRUE(loop_->wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kDisconnected; }, 2s));
  EXPECT_NE(loop_->fault_text().find("bus 'b'"), std::string::npos) << loop_->fault_text();
  Result<void> recovered = make_error(ErrorCode::kNotAvailable, "not tried");
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  while (!recovered && std::chrono::steady_clock::now() < deadline) {
    recovered = loop_->paused([&] { return driver_.recover(); });
    if (!recovered) std::this_thread::sleep_for(100ms);
  }
  ASSERT_TRUE(recovered) << recovered.error().message;
  ASSERT_TRUE(loop_->wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kOk; }, 2s));
  EXPECT_TRUE(joints_near(loop_->feedback(), target, 0.05)) << "the joints moved while the bus was away";
}

TEST_P(HighTorqueDriverTest, OpsReachTheMotors) {
  ASSERT_NO_FATAL_FAILURE(bring_up(params()));
  const auto info = driver_.call("motor_info", {{"motor", "b1"}});
  ASSERT_TRUE(info) << info.error().message;
  // The board reports its motors' firmware (0x0B; the simulator's board motors are at 4.4.6).
  const bool board = GetParam() == HighTorqueSimProcess::Link::Kind::kBoard;
  EXPECT_EQ(info.value()["firmware_version"], board ? "4.4.6" : "0.3.3") << info.value().dump();
  const auto timeout = driver_.call("set_motor_timeout", {{"timeout_ms", 150}});
  ASSERT_TRUE(timeout) << timeout.error().message;
  EXPECT_EQ(diagnostic(driver_, "motor_timeout_ms"), "150");
  const auto bad = driver_.call("motor_info", {{"motor", "nobody"}});
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("nobody"), std::string::npos) << bad.error().message;
}

// reboot_motor is decided by write() from the commands of the tick that would send it: refused
// while a session owns the motor, while robotd still holds it in a session's fallback, and under
// the e-stop. A free motor reboots (on a board bus with its whole port) and gets its own
// watchdog, which a reboot disarms, back.
TEST_P(HighTorqueDriverTest, ARebootIsDecidedAtTheTickThatWouldSendIt) {
  ASSERT_NO_FATAL_FAILURE(bring_up(params()));
  const bool board = GetParam() == HighTorqueSimProcess::Link::Kind::kBoard;
  const auto refused_with = [&](const std::string& why) {
    const auto rebooted = driver_.call("reboot_motor", {{"motor", "a1"}});
    ASSERT_FALSE(rebooted) << why;
    EXPECT_EQ(rebooted.error().code, ErrorCode::kRefused);
    EXPECT_NE(rebooted.error().message.find(why), std::string::npos) << rebooted.error().message;
    EXPECT_EQ(sim_motor(0, 1)["reboots"].get<int>(), 0);
  };
  using Kind = driver::JointCommandKind;
  ASSERT_NO_FATAL_FAILURE(command_and_settle(one_joint(0, {.kind = Kind::kPosition, .owned = true})));
  refused_with("a1 is held by a session; release it first");
  ASSERT_NO_FATAL_FAILURE(command_and_settle(one_joint(0, {.kind = Kind::kImpedance, .owned = false, .kd = 1.0})));
  refused_with("robotd still holds a1 (the KEEP or DAMPING a session left it in)");
  driver::CommandFrame estop = one_joint(0, {.kind = Kind::kImpedance, .owned = false});
  estop.estop = true;
  ASSERT_NO_FATAL_FAILURE(command_and_settle(estop));
  refused_with("robotd's e-stop brakes every motor");
  if (board) {
    ASSERT_NO_FATAL_FAILURE(command_and_settle(one_joint(1, {.kind = Kind::kPosition, .owned = true})));
    refused_with("a2 is held by a session; release it first (a2 shares a1's board port");
  }

  // ZERO_TORQUE left a1 free.
  ASSERT_NO_FATAL_FAILURE(command_and_settle(one_joint(0, {.kind = Kind::kImpedance, .owned = false})));
  const auto rebooted = driver_.call("reboot_motor", {{"motor", "a1"}});
  ASSERT_TRUE(rebooted) << rebooted.error().message;
  EXPECT_EQ(rebooted.value()["rebooted"], board ? nlohmann::json({"a1", "a2", "a3"}) : nlohmann::json({"a1"}));
  EXPECT_TRUE(rebooted.value()["watchdog_rearmed"].get<bool>()) << rebooted.value().dump();
  EXPECT_EQ(sim_motor(0, 1)["reboots"].get<int>(), 1);
  EXPECT_EQ(sim_motor(0, 2)["reboots"].get<int>(), board ? 1 : 0);
  EXPECT_EQ(sim_motor(1, 1)["reboots"].get<int>(), 0);
  EXPECT_TRUE(loop_->wait_for([&](DriverLoop& /*l*/) { return sim_motor(0, 1)["timeout_ms"].get<int>() == 200; }))
      << "the reboot left a1's own watchdog disarmed";
}

// A reboot the loop does not take in time (robotd pauses it for maintenance) is withdrawn: it is
// not sent later, when the loop runs again.
TEST_P(HighTorqueDriverTest, ARebootTheLoopDidNotTakeIsNeverSentLater) {
  nlohmann::json quick = params();
  quick["reply_timeout_ms"] = 100;
  ASSERT_NO_FATAL_FAILURE(bring_up(quick));
  const auto rebooted = loop_->paused([&] { return driver_.call("reboot_motor", {{"motor", "a1"}}); });
  ASSERT_FALSE(rebooted);
  EXPECT_EQ(rebooted.error().code, ErrorCode::kNotAvailable);
  EXPECT_NE(rebooted.error().message.find("did not take the request within 100 ms"), std::string::npos)
      << rebooted.error().message;
  EXPECT_NE(rebooted.error().message.find("nothing was sent"), std::string::npos) << rebooted.error().message;
  const std::uint64_t from = ticks();
  ASSERT_TRUE(loop_->wait_for([&](DriverLoop& /*l*/) { return ticks() >= from + 100; }));
  EXPECT_EQ(sim_motor(0, 1)["reboots"].get<int>(), 0);
}

// Any client may call set_motor_timeout, so it only sets a watchdog that still brakes the robot:
// disarming it (0) or a timeout a robot falls through is refused; the config decides that.
TEST_P(HighTorqueDriverTest, SetMotorTimeoutOnlySetsASafeWatchdog) {
  ASSERT_NO_FATAL_FAILURE(bring_up(params()));
  for (const int timeout_ms : {0, 5000}) {
    const auto refused = driver_.call("set_motor_timeout", {{"timeout_ms", timeout_ms}});
    ASSERT_FALSE(refused) << timeout_ms;
    EXPECT_EQ(refused.error().code, ErrorCode::kInvalidArgument);
    EXPECT_NE(refused.error().message.find("expected an integer in 20..1000"), std::string::npos)
        << refused.error().message;
    EXPECT_NE(refused.error().message.find("only through params.motor_timeout_ms"), std::string::npos)
        << refused.error().message;
  }
  EXPECT_EQ(sim_motor(0, 1)["timeout_ms"].get<int>(), 200);
  EXPECT_EQ(diagnostic(driver_, "motor_timeout_ms"), "200");
  ASSERT_TRUE(driver_.call("set_motor_timeout", {{"timeout_ms", 300}}));
  EXPECT_TRUE(loop_->wait_for([&](DriverLoop& /*l*/) { return sim_motor(1, 2)["timeout_ms"].get<int>() == 300; }));
}

// An e-stop or a shutdown does not wait for maintenance: abort_maintenance() ends a recover() or
// reset_zero() that waits for the motors, and the next recover() works.
TEST_P(HighTorqueDriverTest, AnAbortEndsARecoverOrResetZeroWaitingForTheMotorsAndTheNextRecoverWorks) {
  constexpr auto kSlow = 5000ms;  // zero_settle_ms, reply_timeout_ms and connect_timeout_ms
  nlohmann::json slow = params();
  slow["zero_settle_ms"] = kSlow.count();
  slow["reply_timeout_ms"] = kSlow.count();
  slow["connect_timeout_ms"] = kSlow.count();
  slow["motor_timeout_ms"] = 1000;  // a loop stalled on a busy machine does not trip the motors' watchdog
  ASSERT_NO_FATAL_FAILURE(bring_up(slow));
  const auto abort_after_200ms = [&](auto maintenance) {
    return loop_->paused([&] { return testing::abort_during(driver_, maintenance, 200ms); });
  };
  const auto expect_aborted = [&](const testing::AbortedMaintenance& aborted, const std::string& message,
                                  const std::string& figure) {
    ASSERT_FALSE(aborted.returned_before_abort) << figure;
    ASSERT_FALSE(aborted.result) << figure;
    EXPECT_EQ(aborted.result.error().code, ErrorCode::kRefused);
    EXPECT_EQ(aborted.result.error().message, message);
    EXPECT_LT(aborted.abort_to_return, kSlow / 5) << figure;
    testing::print_abort_figure(figure, aborted, kSlow);
  };
  const std::string transport = GetParam() == HighTorqueSimProcess::Link::Kind::kBoard ? "board" : "CAN-FD";

  // reset_zero first holds the motors at zero torque for zero_settle_ms; aborted there, no zero is set.
  const double zero_before = sim_motor(0, 2)["zero_offset_rad"].get<double>();
  expect_aborted(abort_after_200ms([&] { return driver_.reset_zero({}); }),
                 "aborted: an e-stop or shutdown pre-empted reset_zero (settling before zeroing)",
                 "hightorque reset_zero (" + transport + "), settling");
  EXPECT_EQ(sim_motor(0, 2)["zero_offset_rad"].get<double>(), zero_before);
  // The loop takes over again (the pause is not counted as silence: on the board, where STOP gets
  // no answer, it would be a lost link), and sees the next fault.

  // A fault that stays: recover stops and queries the motor until reply_timeout_ms.
  ASSERT_TRUE(sim_ok({{"op", "set_fault"}, {"bus", 0}, {"motor", 3}, {"code", 0x14}}));
  ASSERT_TRUE(loop_->wait_for(
      [](DriverLoop& l) {
        return l.last_write() == IoResult::kFault && l.fault_text().find("motor a3") != std::string::npos &&
               l.fault_text().find("(0x14)") != std::string::npos;
      },
      2s))
      << loop_->fault_text();
  expect_aborted(abort_after_200ms([&] { return driver_.recover(); }),
                 "aborted: an e-stop or shutdown pre-empted recover (waiting for faults to clear)",
                 "hightorque recover (" + transport + "), a fault that stays");
  ASSERT_TRUE(sim_ok({{"op", "clear_fault"}, {"bus", 0}, {"motor", 3}}));

  // A silent bus is a lost link: recover reconnects and waits for every motor to answer.
  ASSERT_TRUE(sim_ok({{"op", "silence"}, {"bus", 1}, {"for_ms", 30000}}));
  ASSERT_TRUE(loop_->wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kDisconnected; }, 2s));
  // On the board the reconnect waits in the port's start-up, for the board's own answer.
  const std::string waiting = GetParam() == HighTorqueSimProcess::Link::Kind::kBoard
                                  ? "waiting for board serial " + sim_.bus_path(1) + " to answer its start-up"
                                  : "waiting for the motors to answer after the link opened";
  expect_aborted(abort_after_200ms([&] { return driver_.recover(); }),
                 "aborted: an e-stop or shutdown pre-empted recover (" + waiting + ")",
                 "hightorque recover (" + transport + "), a silent bus");

  ASSERT_TRUE(sim_ok({{"op", "silence"}, {"bus", 1}, {"for_ms", 0}}));
  driver_.abort_maintenance();  // before it starts: not that recover's
  const auto recovered = loop_->paused([&] { return driver_.recover(); });
  ASSERT_TRUE(recovered) << recovered.error().message;
  EXPECT_TRUE(loop_->wait_for([](DriverLoop& l) { return l.last_read() == IoResult::kOk; }, 2s));
}

INSTANTIATE_TEST_SUITE_P(Transports, HighTorqueDriverTest,
                         ::testing::Values(HighTorqueSimProcess::Link::Kind::kStandIn,
                                           HighTorqueSimProcess::Link::Kind::kBoard),
                         [](const auto& test_info) {
                           return test_info.param == HighTorqueSimProcess::Link::Kind::kBoard ? "Board"
                                                                                              : "CanFdStandIn";
                         });

// ---- The board's start-up at connect (the SDK's robot.cc / canport.cc) ------------------------

/// The driver on two board ports of a simulator started with `board_args`.
class HighTorqueBoardStartUpTest : public ::testing::Test {
 protected:
  void start(std::vector<std::string> board_args) {
    board_args.emplace_back("--quiet");
    sim_ = std::make_unique<HighTorqueSimProcess>(
        std::vector<HighTorqueSimProcess::Link>{HighTorqueSimProcess::board("1-3"), HighTorqueSimProcess::board("1-2")},
        std::move(board_args));
  }
  nlohmann::json params() const {
    nlohmann::json params = valid_params({{{"name", "a"}, {"board", {{"device", sim_->bus_path(0)}}}},
                                          {{"name", "b"}, {"board", {{"device", sim_->bus_path(1)}}}}});
    params["feedback_timeout_ms"] = 50;
    params["motor_models"] = {{"5047_36", {{"torque_per_unit", 0.004938}, {"gain_factor", 1.0}}}};
    params["motor_defaults"]["model"] = "5047_36";
    return params;
  }
  Result<void> connect() {
    if (auto configured = driver_.configure(params()); !configured) return configured;
    return driver_.connect();
  }
  void run_loop() { loop_ = std::make_unique<DriverLoop>(driver_, kJoints); }
  nlohmann::json bus_state(std::size_t bus) const { return sim_->state()["buses"][bus]; }
  void TearDown() override {
    loop_.reset();
    driver_.disconnect();
  }

  std::unique_ptr<HighTorqueSimProcess> sim_;
  HighTorqueDriver driver_;
  std::unique_ptr<DriverLoop> loop_;
};

// Motors at 4.4.6 (the simulator's default) give function version 5: 0xB0 and 0x0A; the board's
// firmware 4.3 takes the FDCAN reset, three times as the SDK sends it.
TEST_F(HighTorqueBoardStartUpTest, CurrentFirmwareGetsFunctionVersion5AndTheFdcanReset) {
  start({});
  const auto connected = connect();
  ASSERT_TRUE(connected) << connected.error().message;
  for (std::size_t bus = 0; bus < 2; ++bus) {
    EXPECT_EQ(bus_state(bus)["function_version"], 5);
    EXPECT_EQ(bus_state(bus)["fdcan_resets"], 3);
    EXPECT_EQ(bus_state(bus)["bad_frames"], 0);
  }
}

// A motor at 4.2.2 brings its port to function version 3: the 5-parameter 0x93 command and state
// requests without mode and fault (0x06); the other port keeps version 5.
TEST_F(HighTorqueBoardStartUpTest, OlderMotorFirmwareGetsThe5ParameterCommand) {
  start({"--board-motor-firmware", "2:4.2.2", "--board-firmware", "4.0"});
  const auto connected = connect();
  ASSERT_TRUE(connected) << connected.error().message;
  EXPECT_EQ(bus_state(0)["function_version"], 3);
  EXPECT_EQ(bus_state(1)["function_version"], 3) << "the option names motor 2 on every board port";
  EXPECT_EQ(bus_state(0)["fdcan_resets"], 0) << "board firmware 4.0 has no FDCAN reset";
  run_loop();
  const std::vector<double> target{0.5, -0.3, 0.2, 0.4, -0.1};
  loop_->set_command(position_frame(target));
  ASSERT_TRUE(loop_->wait_for([&](DriverLoop& l) { return settled_at(l.feedback(), target); }))
      << "0x93 never moved the motors";
  EXPECT_EQ(bus_state(0)["bad_frames"], 0) << "the board took every packet the driver sent";
}

// Firmware-5 motors take the SDK's "General" constants whatever the config names: kp reaches
// the motor right only with General's gain factor (0.5; the config says 1.0).
TEST_F(HighTorqueBoardStartUpTest, FirmwareFiveMotorsUseTheGeneralConstants) {
  start({"--board-motor-firmware", "5.0.0"});
  const auto connected = connect();
  ASSERT_TRUE(connected) << connected.error().message;
  run_loop();
  const std::vector<double> target{0.5, -0.3, 0.2, 0.4, -0.1};
  loop_->set_command(position_frame(target));
  ASSERT_TRUE(loop_->wait_for([&](DriverLoop& l) { return settled_at(l.feedback(), target); }));
  EXPECT_NEAR(sim_->motor_state(1, 2)["kp"].get<double>(), 40, 0.5);
}

TEST_F(HighTorqueBoardStartUpTest, WhatRobotdCannotDriveIsAClearError) {
  start({"--board-firmware", "3.9"});
  auto connected = connect();
  ASSERT_FALSE(connected);
  EXPECT_NE(connected.error().message.find("robotd needs 4.0 or later"), std::string::npos)
      << connected.error().message;
  start({"--board-motor-firmware", "3:4.1.9"});
  connected = connect();
  ASSERT_FALSE(connected);
  EXPECT_NE(connected.error().message.find("motor 3 has firmware 4.1.9"), std::string::npos)
      << connected.error().message;
}

TEST_F(HighTorqueBoardStartUpTest, ABoardThatDoesNotAnswerIsAClearError) {
  start({});
  ASSERT_TRUE(sim_->control({{"op", "silence"}, {"bus", 0}, {"for_ms", 60000}})["ok"].get<bool>());
  const auto connected = connect();
  ASSERT_FALSE(connected);
  EXPECT_NE(connected.error().message.find("no answer to 0x05"), std::string::npos) << connected.error().message;
}

// The IMU on its own serial line arrives in the same Feedback as the motors.
TEST(HighTorqueDriverImu, TheImuSerialLineFeedsTheFeedback) {
  HighTorqueSimProcess sim({HighTorqueSimProcess::standin("1-3"), HighTorqueSimProcess::standin("1-2")}, {"--quiet"});
  ImuSimProcess imu_sim({}, {"--quiet"});
  nlohmann::json params =
      valid_params({{{"name", "a"}, {"can", {{"transport", "standin"}, {"path", sim.bus_path(0)}}}},
                    {{"name", "b"}, {"can", {{"transport", "standin"}, {"path", sim.bus_path(1)}}}}});
  params["imu"] = {{"source", "yesense"}, {"serial", {{"device", imu_sim.pty_path()}, {"baud", 460800}}}};
  HighTorqueDriver driver;
  ASSERT_TRUE(driver.configure(params));
  EXPECT_TRUE(driver.describe().has_imu);
  const auto connected = driver.connect();
  ASSERT_TRUE(connected) << connected.error().message;
  constexpr double kRoll = 0.3;
  ASSERT_TRUE(imu_sim.control({{"op", "set_orientation"}, {"roll_rad", kRoll}, {"pitch_rad", 0}, {"yaw_rad", 0}})["ok"]
                  .get<bool>());
  {
    DriverLoop loop(driver, kJoints);
    const bool tilted = loop.wait_for(
        [](DriverLoop& l) {
          const driver::Feedback feedback = l.feedback();
          return feedback.has_imu && std::fabs(feedback.imu.orientation_xyzw[0] - std::sin(kRoll / 2)) < 1e-3;
        },
        3s);
    EXPECT_TRUE(tilted) << "no IMU sample with a " << kRoll << " rad roll; " << diagnostic(driver, "imu");
    const driver::Feedback feedback = loop.feedback();
    EXPECT_NEAR(feedback.imu.orientation_xyzw[3], std::cos(kRoll / 2), 1e-3);
    EXPECT_NEAR(std::hypot(feedback.imu.linear_acceleration_m_s2[1], feedback.imu.linear_acceleration_m_s2[2]), 9.80665,
                0.05)
        << "gravity, tilted by the roll";
    EXPECT_EQ(feedback.joint_count, kJoints);
  }
  EXPECT_NE(diagnostic(driver, "imu").find("(up)"), std::string::npos) << diagnostic(driver, "imu");
  driver.disconnect();
}

}  // namespace
}  // namespace robotd::hightorque
