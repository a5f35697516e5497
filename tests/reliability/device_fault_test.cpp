// Device faults through robotd, for every vendor driver against its simulator: the link cut
// mid-motion, a device that stops answering, garbage and broken framing, and the device's own
// error code. Each case measures, from robotd's log stamps, how long robotd took to latch the
// FAULT and to be RUNNING again, checks that the simulated arm next to it kept its loop, and that
// the vendor's arm does not jump to the stale target once it is back. docs/reliability.md has
// the table of what these print ("[ measured ]" lines).
#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "hightorque_sim_process.hpp"
#include "log_times.hpp"
#include "parol6_sim_process.hpp"
#include "piper_sim_process.hpp"
#include "realman_sim_process.hpp"
#include "robotd_fixture.hpp"
#include "xarm_sim_process.hpp"

namespace robotd::testing {
namespace {

using namespace std::chrono_literals;

enum class Fault { kLinkCut, kSilence, kGarbage, kBrokenFraming, kErrorCode };

const char* to_string(Fault fault) {
  switch (fault) {
    case Fault::kLinkCut:
      return "LinkCut";
    case Fault::kSilence:
      return "Silence";
    case Fault::kGarbage:
      return "Garbage";
    case Fault::kBrokenFraming:
      return "BrokenFraming";
    case Fault::kErrorCode:
      return "ErrorCode";
  }
  return "?";
}

/// What robotd is expected to do about an injected fault.
enum class Outcome {
  kReconnects,    // FAULT, then RUNNING by itself once the device is back (reconnect with backoff)
  kNeedsRecover,  // FAULT until a client calls recover once the cause is gone
  kKeepsRunning,  // the bad input is dropped and counted; the device stays RUNNING
};

struct Injection {
  nlohmann::json request;  // to the simulator's control channel
  nlohmann::json undo;     // null: the fault ends by itself
  Outcome outcome = Outcome::kReconnects;
  std::string fault_text;  // part of the FAULT's text
};

/// One vendor: its simulator and the driver params that reach it.
struct Rig {
  std::unique_ptr<SimProcess> sim;
  nlohmann::json params;
  nlohmann::json device_settings = nlohmann::json::object();  // merged into the device's config entry
};

std::optional<Injection> piper_fault(Fault fault) {
  switch (fault) {
    case Fault::kLinkCut:
      return Injection{{{"op", "disconnect"}, {"ms", 600}}, nullptr, Outcome::kReconnects, "CAN link closed"};
    case Fault::kSilence:
      return Injection{{{"op", "silence"}, {"ms", 600}}, nullptr, Outcome::kReconnects, "no arm feedback"};
    case Fault::kGarbage:
      return Injection{{{"op", "garbage"}, {"frames", 500}}, nullptr, Outcome::kKeepsRunning, ""};
    case Fault::kErrorCode:
      return Injection{
          {{"op", "raise_error"}, {"arm_status", 7}}, {{"op", "clear_error"}}, Outcome::kNeedsRecover, "collision"};
    case Fault::kBrokenFraming:  // CAN frames arrive whole or not at all
      return std::nullopt;
  }
  return std::nullopt;
}

Rig piper_rig() {
  auto sim = std::make_unique<PiperSimProcess>(PiperSimProcess::unique_path("piper-fault"));
  nlohmann::json params{{"can", {{"transport", "standin"}, {"path", sim->bus_path()}}}};
  return {std::move(sim), params};
}

std::optional<Injection> parol6_fault(Fault fault) {
  switch (fault) {
    case Fault::kLinkCut:
      return Injection{{{"op", "disconnect"}, {"ms", 600}}, nullptr, Outcome::kReconnects, "serial"};
    case Fault::kSilence:
      return Injection{{{"op", "silence"}, {"ms", 600}}, nullptr, Outcome::kReconnects, "no reply from the board"};
    case Fault::kGarbage:
      return Injection{{{"op", "garbage"}, {"bytes", 300}}, nullptr, Outcome::kKeepsRunning, ""};
    case Fault::kBrokenFraming:  // bytes lost mid-frame: truncated frames
      return Injection{{{"op", "drop_bytes"}, {"count", 40}}, nullptr, Outcome::kKeepsRunning, ""};
    case Fault::kErrorCode:  // the board reports no error codes (its e-stop input: Parol6Test)
      return std::nullopt;
  }
  return std::nullopt;
}

Rig parol6_rig() {
  auto sim = std::make_unique<Parol6SimProcess>(Parol6SimProcess::unique_path("parol6-fault"),
                                                std::vector<std::string>{"--homed"});
  // The board's silence and robotd's feedback timeout widened from 50 and 100 ms: under the
  // sanitizers, on a loaded machine, the simulator is sometimes starved that long, and every
  // fault injected here lasts 600 ms. The order stays: the driver names a silent board first.
  nlohmann::json params{{"serial", {{"device", sim->pty_path()}, {"baud", 3000000}}}, {"reply_timeout_ms", 250}};
  return {std::move(sim), params, {{"feedback_timeout_ms", 400}}};
}

std::optional<Injection> realman_fault(Fault fault) {
  switch (fault) {
    case Fault::kLinkCut:
      // An orderly close or a reset, as the kernel decides: both name the TCP connection.
      return Injection{{{"op", "disconnect"}}, nullptr, Outcome::kReconnects, "TCP connection"};
    case Fault::kSilence:
      return Injection{{{"op", "silence"}, {"on", true}},
                       {{"op", "silence"}, {"on", false}},
                       Outcome::kReconnects,
                       "no real-time push"};
    case Fault::kGarbage:
      return Injection{{{"op", "garbage"}}, nullptr, Outcome::kKeepsRunning, ""};
    case Fault::kErrorCode:
      return Injection{{{"op", "raise_error"}, {"code", 0x1007}}, nullptr, Outcome::kNeedsRecover, "0x1007"};
    case Fault::kBrokenFraming:  // a line that is not JSON is the garbage case
      return std::nullopt;
  }
  return std::nullopt;
}

Rig realman_rig() {
  auto sim = std::make_unique<RealmanSimProcess>(std::vector<std::string>{"--quiet"});
  nlohmann::json params{
      {"model", "RM65"}, {"host", "127.0.0.1"}, {"port", sim->port()}, {"push", {{"ip", "127.0.0.1"}, {"port", 0}}}};
  return {std::move(sim), params};
}

std::optional<Injection> xarm_fault(Fault fault) {
  switch (fault) {
    case Fault::kLinkCut:
      return Injection{{{"op", "disconnect"}}, nullptr, Outcome::kReconnects, "the control box closed the"};
    case Fault::kSilence:
      return Injection{{{"op", "silence"}, {"on", true}},
                       {{"op", "silence"}, {"on", false}},
                       Outcome::kReconnects,
                       "no report from the control box"};
    case Fault::kGarbage:
      return Injection{{{"op", "garbage"}, {"kind", "frame"}}, nullptr, Outcome::kKeepsRunning, ""};
    case Fault::kBrokenFraming:
      return Injection{{{"op", "garbage"}, {"kind", "bytes"}}, nullptr, Outcome::kReconnects, "lost its framing"};
    case Fault::kErrorCode:
      return Injection{{{"op", "error"}, {"code", 22}}, nullptr, Outcome::kNeedsRecover, "C22 self-collision"};
  }
  return std::nullopt;
}

Rig xarm_rig() {
  auto sim = std::make_unique<XarmSimProcess>(std::vector<std::string>{"--quiet"});
  nlohmann::json params{{"model", "xarm6"},
                        {"host", "127.0.0.1"},
                        {"port", sim->port()},
                        {"report", {{"kind", "real"}, {"port", sim->report_port()}}}};
  return {std::move(sim), params};
}

std::optional<Injection> hightorque_fault(Fault fault) {
  switch (fault) {
    case Fault::kLinkCut:
      return Injection{
          {{"op", "disconnect"}, {"bus", 0}, {"for_ms", 600}}, nullptr, Outcome::kReconnects, "bus 'legs'"};
    case Fault::kSilence:
      return Injection{
          {{"op", "silence"}, {"bus", 0}, {"for_ms", 600}}, nullptr, Outcome::kReconnects, "no motor answered"};
    case Fault::kGarbage:
      return Injection{{{"op", "garbage"}, {"bus", 0}, {"count", 200}}, nullptr, Outcome::kKeepsRunning, ""};
    case Fault::kErrorCode:
      return Injection{{{"op", "set_fault"}, {"bus", 0}, {"motor", 1}, {"code", 0x14}},
                       {{"op", "clear_fault"}, {"bus", 0}, {"motor", 1}},
                       Outcome::kNeedsRecover,
                       "m1 (bus 'legs' id 1)"};
    case Fault::kBrokenFraming:  // CAN frames arrive whole or not at all
      return std::nullopt;
  }
  return std::nullopt;
}

Rig hightorque_rig() {
  auto sim = std::make_unique<HighTorqueSimProcess>(
      std::vector<HighTorqueSimProcess::Link>{HighTorqueSimProcess::standin("1-3")},
      std::vector<std::string>{"--quiet"});
  nlohmann::json motors = nlohmann::json::array();
  for (int id = 1; id <= 3; ++id) motors.push_back({{"name", "m" + std::to_string(id)}, {"bus", "legs"}, {"id", id}});
  nlohmann::json params{
      {"buses", {{{"name", "legs"}, {"can", {{"transport", "standin"}, {"path", sim->bus_path(0)}}}}}},
      {"motor_defaults",
       {{"position_min_rad", -1.5},
        {"position_max_rad", 1.5},
        {"velocity_max_rad_s", 2.0},
        {"default_kp", 40},
        {"default_kd", 1.0},
        {"kp_max", 300},
        {"kd_max", 20},
        {"effort_max_nm", 30}}},
      {"motors", motors}};
  return {std::move(sim), params};
}

Rig make_rig(const std::string& driver) {
  if (driver == "piper") return piper_rig();
  if (driver == "parol6") return parol6_rig();
  if (driver == "realman") return realman_rig();
  if (driver == "xarm") return xarm_rig();
  return hightorque_rig();
}

/// What injects `fault` into `driver`'s simulator; nullopt where the protocol has no such fault.
std::optional<Injection> injection_for(const std::string& driver, Fault fault) {
  if (driver == "piper") return piper_fault(fault);
  if (driver == "parol6") return parol6_fault(fault);
  if (driver == "realman") return realman_fault(fault);
  if (driver == "xarm") return xarm_fault(fault);
  return hightorque_fault(fault);
}

struct Case {
  std::string driver;
  Fault fault;
};

class DeviceFaultTest : public RobotdTest, public ::testing::WithParamInterface<Case> {
 protected:
  void SetUp() override {
    rig_ = make_rig(GetParam().driver);
    nlohmann::json device = vendor_device(GetParam().driver, rig_.params);
    device.update(rig_.device_settings);
    start_with_device(device, /*with_sim_arm=*/true);
  }
  const std::string& driver() const { return GetParam().driver; }
  double joint0() { return joint_state(driver()).position[0]; }
  /// The stamp of robotd's first log line about this device containing `what` since `since`.
  std::optional<WallTime> logged(const std::string& what, WallTime since) {
    const std::string needle = "device '" + driver() + "': " + what;
    const auto deadline = std::chrono::steady_clock::now() + 5s;
    while (true) {
      if (auto stamp = logged_at(robotd_->log(), needle, since)) return stamp;
      if (std::chrono::steady_clock::now() > deadline) return std::nullopt;
      std::this_thread::sleep_for(5ms);
    }
  }

  Rig rig_;
};

TEST_P(DeviceFaultTest, IsReportedOthersKeepTheirLoopAndTheArmDoesNotJumpWhenBack) {
  const std::optional<Injection> injection = injection_for(driver(), GetParam().fault);
  ASSERT_TRUE(injection.has_value());
  Session session = acquire_device(driver(), {0});
  const double start = joint0();
  const double target = start + 0.55;  // far: robotd ramps towards it, so the fault comes mid-motion
  ASSERT_TRUE(session.send_positions({static_cast<float>(target)}));
  ASSERT_TRUE(wait_for_joints([&](const JointState& s) { return s.position[0] > start + 0.1; }, 5s, driver()));

  const DeviceStatus arm_before = device_status("arm");
  const WallTime injected = std::chrono::system_clock::now();
  ASSERT_TRUE(rig_.sim->control(injection->request)["ok"].get<bool>()) << injection->request.dump();

  std::string line = "[ measured ] " + driver() + " " + to_string(GetParam().fault) + ": ";
  if (injection->outcome == Outcome::kKeepsRunning) {
    std::this_thread::sleep_for(500ms);
    EXPECT_FALSE(logged_at(robotd_->log(), "device '" + driver() + "': FAULT", injected)) << robotd_->log();
    const DeviceStatus status = device_status(driver());
    EXPECT_EQ(status.state, DeviceState::kRunning) << status.fault_text;
    EXPECT_TRUE(
        wait_for_joints([&](const JointState& s) { return std::fabs(s.position[0] - target) < 0.02; }, 10s, driver()))
        << "the motion did not go on through the garbage";
    line += "dropped, stayed RUNNING and reached its target";
  } else {
    const auto faulted = logged("FAULT", injected);
    ASSERT_TRUE(faulted) << "no FAULT logged: " << robotd_->log();
    const std::string log = robotd_->log();
    const std::size_t at = log.find("device '" + driver() + "': FAULT");
    EXPECT_NE(log.find(injection->fault_text, at), std::string::npos)
        << "the FAULT should say \"" << injection->fault_text << "\": " << log.substr(at, 300);
    line += "FAULT after " + std::to_string(std::lround(milliseconds_between(injected, *faulted))) + " ms";

    // The simulated arm next to it is served throughout.
    std::this_thread::sleep_for(300ms);
    const DeviceStatus arm_after = device_status("arm");
    EXPECT_EQ(arm_after.state, DeviceState::kRunning);
    // Its loop kept ticking and it still publishes (how many ticks is reported, not asserted).
    EXPECT_GT(arm_after.loop.ticks, arm_before.loop.ticks);
    EXPECT_GE(joint_state("arm").header.stamp.to_ns(), arm_before.header.stamp.to_ns());
    const auto arm_overruns = arm_after.loop.overruns - arm_before.loop.overruns;
    // Reported, not asserted: this VM is not PREEMPT_RT and is shared, and this test runs under ASan.
    line += "; arm: +" + std::to_string(arm_after.loop.ticks - arm_before.loop.ticks) + " ticks, " +
            std::to_string(arm_overruns) + " overruns, period p99 " +
            std::to_string(std::lround(arm_after.loop.period_p99_us)) + " µs, joint states published " +
            std::to_string(arm_before.joint_states_published) + " -> " +
            std::to_string(arm_after.joint_states_published);

    if (!injection->undo.is_null()) {
      ASSERT_TRUE(rig_.sim->control(injection->undo)["ok"].get<bool>()) << injection->undo.dump();
    }
    const WallTime cleared = std::chrono::system_clock::now();
    if (injection->outcome == Outcome::kNeedsRecover) {
      const auto recovered = client().device_call(driver(), "recover");
      ASSERT_TRUE(recovered) << recovered.error().message;
      const auto back = logged("recovered", cleared);
      ASSERT_TRUE(back) << robotd_->log();
      line += "; recover took " + std::to_string(std::lround(milliseconds_between(cleared, *back))) + " ms";
    } else {
      const auto back = logged("reconnected", injected);
      ASSERT_TRUE(back) << "not reconnected: " << robotd_->log();
      line += "; reconnected " + std::to_string(std::lround(milliseconds_between(injected, *back))) +
              " ms after the fault began";
    }
    ASSERT_EQ(wait_for_state(driver(), DeviceState::kRunning, 10s).state, DeviceState::kRunning)
        << robotd_->log() << "simulator: " << rig_.sim->control({{"op", "state"}}).dump();
    // A motor that went limp with its fault may still coast, and the hold robotd takes up after
    // the recover settles it at the position measured then; once it is at rest (still for 200 ms)
    // it must stay there, short of the target it had when the fault came.
    double at_rest = joint0();
    bool settled = false;
    for (const auto give_up = std::chrono::steady_clock::now() + 5s;
         !settled && std::chrono::steady_clock::now() < give_up;) {
      std::this_thread::sleep_for(200ms);
      const double now = joint0();
      settled = std::fabs(now - at_rest) < 0.002;
      at_rest = now;
    }
    EXPECT_TRUE(settled) << "the joint never came to rest";
    std::this_thread::sleep_for(500ms);
    EXPECT_NEAR(joint0(), at_rest, 0.01) << "the arm moved once back";
    EXPECT_GT(std::fabs(at_rest - target), 0.05) << "the stale target was resumed";
  }
  std::cout << line << "\n";
}

/// Every fault each vendor's protocol can have.
std::vector<Case> applicable_cases() {
  std::vector<Case> cases;
  for (const char* driver : {"piper", "parol6", "realman", "xarm", "hightorque"}) {
    for (const Fault fault :
         {Fault::kLinkCut, Fault::kSilence, Fault::kGarbage, Fault::kBrokenFraming, Fault::kErrorCode}) {
      if (injection_for(driver, fault)) cases.push_back({driver, fault});
    }
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Vendors, DeviceFaultTest, ::testing::ValuesIn(applicable_cases()),
                         [](const ::testing::TestParamInfo<Case>& test) {
                           return test.param.driver + to_string(test.param.fault);
                         });

}  // namespace
}  // namespace robotd::testing
