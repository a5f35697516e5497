// The C++ client's closed loop through a real robotd: run_control_loop gets the arm's ticks, its
// PD law's answers are what moves the arm, and robotd counts them (SessionInfo, robotctl).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "robotd_fixture.hpp"

#if !defined(ROBOTCTL_BINARY) || !defined(EXAMPLE_PD_CONTROL)
#error "ROBOTCTL_BINARY and EXAMPLE_PD_CONTROL must point at the executables under test"
#endif

namespace robotd::testing {
namespace {

using namespace std::chrono_literals;

constexpr double kStep_rad = 0.3;
constexpr double kKp = 20.0;  // N·m/rad
constexpr double kKd = 1.0;   // N·m·s/rad

SessionRequest closed_loop_request() {
  SessionRequest request;
  request.device = "arm";
  request.mode = ControlMode::kTorque;
  request.timeout = 2s;
  request.on_release = Behavior::kDamping;
  request.closed_loop = true;
  request.min_command_success_rate = 0.5F;
  request.on_low_success_rate = LowRateAction::kWarn;
  return request;
}

/// The PD law towards `reference`; records the ticks it was called with and its last error.
struct PdLaw {
  std::vector<double> reference;
  std::vector<std::uint64_t> ticks;
  double worst_error_rad = 1;
  bool stop_when_settled = true;

  Command operator()(const TickState& state) {
    if (reference.empty()) {
      for (const double q : state.position) reference.push_back(q + kStep_rad);
    }
    ticks.push_back(state.tick);
    Command command;
    worst_error_rad = 0;
    for (std::size_t j = 0; j < state.position.size(); ++j) {
      const double error = reference[j] - state.position[j];
      worst_error_rad = std::max(worst_error_rad, std::abs(error));
      command.torques.push_back(static_cast<float>(kKp * error - kKd * state.velocity[j]));
    }
    command.finished =
        stop_when_settled && ticks.size() > 200 && worst_error_rad < 0.01 && std::abs(state.velocity[0]) < 0.05;
    return command;
  }
};

class ClosedLoopClientTest : public RobotdTest {
 protected:
  /// The session's SessionInfo once robotd has counted an answer of it (status comes every 200 ms).
  static SessionInfo counted_info(Session& session) {
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    auto info = session.info(5s);
    while (info && info.value().ticks_answered_in_time + info.value().ticks_answered_late == 0 &&
           std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(50ms);
      info = session.info(5s);
    }
    EXPECT_TRUE(info) << info.error().message;
    return info ? info.value() : SessionInfo{};
  }
};

TEST_F(ClosedLoopClientTest, PdLawGetsNewerTicksAndItsAnswersMoveTheArmAndAreCounted) {
  start_robotd();
  auto session = client().request_control(closed_loop_request());
  ASSERT_TRUE(session) << session.error().message;

  PdLaw law;
  auto report = session.value().run_control_loop(std::ref(law), {.duration = 30s, .state_timeout = 5s});
  ASSERT_TRUE(report) << report.error().message;
  // (A loop, not views::iota: clang 14, which builds the sanitizer stages, cannot use it with
  // libstdc++ 12.)
  std::size_t consecutive = 0;
  for (std::size_t i = 1; i < law.ticks.size(); ++i) {
    if (law.ticks[i] == law.ticks[i - 1] + 1) ++consecutive;
  }
  std::printf("[ measured ] %llu ticks seen, %zu the one after the previous, %llu skipped\n",
              static_cast<unsigned long long>(report.value().ticks_seen), consecutive,
              static_cast<unsigned long long>(report.value().ticks_skipped));

  // The law finished once the arm stood at its reference: only the law's torques command it.
  EXPECT_TRUE(report.value().finished) << "the arm never settled at the PD law's reference";
  EXPECT_LT(law.worst_error_rad, 0.01);
  EXPECT_EQ(report.value().ticks_seen, law.ticks.size());
  EXPECT_EQ(report.value().ticks_answered, law.ticks.size());
  EXPECT_TRUE(std::ranges::is_sorted(law.ticks));
  EXPECT_EQ(std::ranges::adjacent_find(law.ticks), law.ticks.end()) << "a tick came twice";
  EXPECT_EQ(report.value().last_tick - report.value().first_tick + 1,
            report.value().ticks_seen + report.value().ticks_skipped);
  EXPECT_GT(consecutive, 0U) << "the law never got the tick after the one it answered";

  const SessionInfo info = counted_info(session.value());
  EXPECT_TRUE(info.closed_loop);
  EXPECT_GT(info.ticks_answered_in_time + info.ticks_answered_late, 0U);
  EXPECT_GE(info.ticks_to_answer, info.ticks_answered_in_time + info.ticks_answered_late);
  EXPECT_FLOAT_EQ(info.min_command_success_rate, 0.5F);
  EXPECT_EQ(info.on_low_success_rate, LowRateAction::kWarn);
}

TEST_F(ClosedLoopClientTest, RobotctlSessionsShowsTheSessionsAnswersInTime) {
  start_robotd();
  auto session = client().request_control(closed_loop_request());
  ASSERT_TRUE(session) << session.error().message;
  std::atomic<bool> stop{false};
  PdLaw law;
  law.stop_when_settled = false;
  std::jthread loop(
      [&] { (void)session.value().run_control_loop(std::ref(law), {.stop = &stop, .state_timeout = 5s}); });

  // Until robotd has counted answers and robotctl shows them.
  std::string table;
  const auto deadline = std::chrono::steady_clock::now() + 20s;
  while (std::chrono::steady_clock::now() < deadline) {
    ChildProcess robotctl("/usr/bin/env",
                          {"ROBOTD_DOMAIN_ID=" + std::to_string(domain_.id()), ROBOTCTL_BINARY, "sessions"});
    table.clear();
    while (auto line = robotctl.read_line(10s)) table += *line + "\n";
    if (table.find("ANSWERS IN TIME") != std::string::npos && table.find("% (in time ") != std::string::npos) break;
    std::this_thread::sleep_for(100ms);
  }
  stop.store(true);
  loop.join();
  EXPECT_NE(table.find("ANSWERS IN TIME"), std::string::npos) << table;
  EXPECT_NE(table.find("% (in time "), std::string::npos) << table;
  EXPECT_NE(table.find("; min 50.0 % WARN)"), std::string::npos) << table;
}

TEST_F(ClosedLoopClientTest, SendAlignedStreamsPositionsThatMoveTheArm) {
  start_robotd();
  SessionRequest request;
  request.device = "arm";
  auto session = client().request_control(request);
  ASSERT_TRUE(session) << session.error().message;
  const std::vector<float> target{0.3F, -0.2F, 0.1F, 0.0F, 0.2F, -0.1F};
  const auto deadline = std::chrono::steady_clock::now() + 10s;
  bool arrived = false;
  while (!arrived && std::chrono::steady_clock::now() < deadline) {
    Command command;
    command.positions = target;
    ASSERT_TRUE(session.value().send_aligned(command));
    arrived = max_error(joint_state(), target) < 0.01;
  }
  EXPECT_TRUE(arrived) << "the arm did not reach the aligned stream's target";
  EXPECT_GT(device_status().commands.accepted, 0U);
}

TEST_F(ClosedLoopClientTest, ThePdExampleBringsEveryJointToItsReference) {
  start_robotd();
  ChildProcess example("/usr/bin/env", {"ROBOTD_DOMAIN_ID=" + std::to_string(domain_.id()), EXAMPLE_PD_CONTROL});
  std::vector<std::string> lines;
  while (auto line = example.read_line(30s)) lines.push_back(*line);
  ASSERT_EQ(lines.size(), 8U) << "the example printed " << lines.size() << " lines";
  EXPECT_NE(lines[0].find(" ticks answered (ticks "), std::string::npos) << lines[0];
  for (std::size_t j = 1; j <= 6; ++j) {
    const double position = std::stod(lines[j].substr(lines[j].find(':') + 1));
    EXPECT_NEAR(position, kStep_rad, 0.02) << lines[j];  // the test arm starts at 0
  }
  EXPECT_EQ(lines[7].rfind("robotd: ", 0), 0U) << lines[7];
}

}  // namespace
}  // namespace robotd::testing
