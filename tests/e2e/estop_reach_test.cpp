// End to end through a real robotd process: the e-stop reaches the simulated arm in every state
// it can be in, and /estop says so ("reached 'arm' in X ms"), or says it could not and why
// ("NOT confirmed on 'arm' (…)") where the link is down. No latency is asserted here: the figures
// are bench/estop_latency.py's (docs/safety.md, "Measured e-stop latency").
#include <atomic>
#include <chrono>
#include <future>
#include <regex>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "robotd_fixture.hpp"

namespace robotd::testing {
namespace {

using namespace std::chrono_literals;

constexpr auto kSlowMaintenance = 5000ms;     // what the sim's recover or reset_zero would take unaborted
constexpr double kConfirmationWindowMs = 50;  // /estop waits this long for the loop

class EstopReachTest : public RobotdTest {
 protected:
  /// robotd with the test arm; it reconnects only when asked (recover), and, with `patient`,
  /// faults a silent driver only after 60 s.
  void start(bool patient = false) {
    nlohmann::json overrides{{"reconnect_interval_ms", 0}};
    if (patient) overrides["feedback_timeout_ms"] = 60000;
    start_robotd(sim_arm_config(domain_.id(), nullptr, overrides));
  }

  /// Engages the e-stop of the arm; robotd's reply.
  std::string engage() {
    auto engaged = client().estop("arm", "estop reach test");
    EXPECT_TRUE(engaged) << engaged.error().message;
    return engaged ? engaged.value().message : "";
  }

  /// The reply says the loop wrote the e-stop frame to the arm within the confirmation window.
  static void expect_reached(const std::string& reply) {
    std::smatch found;
    ASSERT_TRUE(std::regex_search(reply, found, std::regex("reached 'arm' in ([0-9.]+) ms"))) << reply;
    EXPECT_LE(std::stod(found[1].str()), kConfirmationWindowMs) << reply;
    EXPECT_EQ(reply.find("NOT confirmed"), std::string::npos) << reply;
  }

  /// Resets the e-stop and waits until the loop has seen the reset.
  void reset() {
    auto reset = client().reset_estop("arm");
    ASSERT_TRUE(reset) << reset.error().message;
    DeviceStatus status = device_status();
    for (int i = 0; i < 100 && status.estop_engaged; ++i) status = device_status();
    ASSERT_FALSE(status.estop_engaged) << "the loop never saw the reset";
  }

  /// The simulated arm shows the e-stop frame from its next physics step (its next read()), a
  /// tick after the write() robotd timed; waits for it well beyond that.
  bool sim_took_the_estop() {
    for (int i = 0; i < 200; ++i) {
      if (sim_state()["estop"].get<bool>()) return true;
      std::this_thread::sleep_for(5ms);
    }
    return false;
  }
};

TEST_F(EstopReachTest, ReachesARunningArmIdleAndWhileASessionStreamsAt1kHz) {
  start();
  expect_reached(engage());
  EXPECT_TRUE(sim_took_the_estop());
  reset();

  SessionRequest request;
  request.device = "arm";
  request.timeout = 2s;
  auto session = client().request_control(request);
  ASSERT_TRUE(session) << session.error().message;
  std::atomic<bool> streaming{true};
  std::atomic<int> sent{0};
  std::thread stream([&] {
    auto next = std::chrono::steady_clock::now();
    while (streaming.load()) {
      next += 1ms;
      std::this_thread::sleep_until(next);
      if (session.value().send_positions({0.1F, 0.1F, 0.1F, 0.1F, 0.1F, 0.1F})) sent.fetch_add(1);
    }
  });
  while (sent.load() < 200) std::this_thread::sleep_for(10ms);
  for (int i = 0; i < 3; ++i) {
    expect_reached(engage());
    EXPECT_TRUE(sim_took_the_estop());
    reset();
  }
  streaming.store(false);
  stream.join();
}

TEST_F(EstopReachTest, ReachesAnArmInFaultAndIsNotConfirmedBehindALostLink) {
  start();
  call_device("arm", "raise_fault", {{"code", 7}, {"text", "overcurrent"}});
  ASSERT_EQ(wait_for_state("arm", DeviceState::kFault).state, DeviceState::kFault);
  // A controller in fault still takes frames over its link.
  expect_reached(engage());
  EXPECT_TRUE(sim_took_the_estop());
  reset();
  ASSERT_TRUE(client().device_call("arm", "recover"));

  call_device("arm", "disconnect");
  ASSERT_EQ(wait_for_state("arm", DeviceState::kFault).state, DeviceState::kFault);
  const std::string reply = engage();
  EXPECT_NE(reply.find("NOT confirmed on 'arm' (FAULT: simulated link lost (injected)): robotd cannot reach it now "
                       "and keeps sending the e-stop every tick"),
            std::string::npos)
      << reply;
  EXPECT_EQ(reply.find("reached"), std::string::npos) << reply;
  EXPECT_TRUE(device_status().estop_engaged) << "latched whether or not it reached the arm";
}

TEST_F(EstopReachTest, AbortsASlowRecoverAndThenReachesTheArm) {
  start();
  call_device("arm", "slow_maintenance", {{"ms", kSlowMaintenance.count()}});
  const auto started = std::chrono::steady_clock::now();
  auto recovering = std::async(std::launch::async, [&] { return client().device_call("arm", "recover"); });
  ASSERT_EQ(wait_for_state("arm", DeviceState::kMaintenance).state, DeviceState::kMaintenance);
  expect_reached(engage());
  const auto recovered = recovering.get();
  const auto took = std::chrono::steady_clock::now() - started;
  ASSERT_FALSE(recovered) << "the recover was not aborted";
  EXPECT_NE(recovered.error().message.find("aborted: the e-stop of 'arm' is engaged"), std::string::npos)
      << recovered.error().message;
  EXPECT_LT(took, kSlowMaintenance / 2) << "the recover ran its course instead of giving way";
  EXPECT_TRUE(sim_took_the_estop());
  EXPECT_EQ(wait_for_state("arm", DeviceState::kEstop).state, DeviceState::kEstop);
}

TEST_F(EstopReachTest, AbortsASlowResetZeroAndThenReachesTheArm) {
  start();
  call_device("arm", "slow_maintenance", {{"ms", kSlowMaintenance.count()}});
  const auto started = std::chrono::steady_clock::now();
  auto zeroing = std::async(std::launch::async, [&] { return client().reset_zero("arm", {}); });
  ASSERT_EQ(wait_for_state("arm", DeviceState::kMaintenance).state, DeviceState::kMaintenance);
  expect_reached(engage());
  const auto zeroed = zeroing.get();
  ASSERT_FALSE(zeroed) << "the reset_zero was not aborted";
  EXPECT_NE(zeroed.error().message.find("aborted: the e-stop of 'arm' is engaged"), std::string::npos)
      << zeroed.error().message;
  EXPECT_LT(std::chrono::steady_clock::now() - started, kSlowMaintenance / 2);
  EXPECT_TRUE(sim_took_the_estop());
}

// Before any feedback (CONNECTING) the loop has nothing measured; the same holds after a
// re-initialisation until the driver reports again. The e-stop goes out all the same.
TEST_F(EstopReachTest, ReachesAnArmThatHasGivenNoFeedbackSinceItWasReinitialised) {
  start(/*patient=*/true);
  call_device("arm", "stop_feedback", {{"enabled", true}});
  const auto zeroed = client().reset_zero("arm", {}, 200ms);  // re-initialises; then no feedback comes
  ASSERT_FALSE(zeroed);
  EXPECT_NE(zeroed.error().message.find("gave no feedback"), std::string::npos) << zeroed.error().message;
  ASSERT_EQ(device_status().state, DeviceState::kMaintenance) << "expected no feedback since the re-initialisation";
  expect_reached(engage());
  EXPECT_TRUE(sim_took_the_estop());
  reset();
  call_device("arm", "stop_feedback", {{"enabled", false}});
  EXPECT_EQ(wait_for_state("arm", DeviceState::kRunning).state, DeviceState::kRunning);
}

}  // namespace
}  // namespace robotd::testing
