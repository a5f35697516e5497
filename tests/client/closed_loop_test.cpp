// The C++ client's closed-loop API against the test-side DDS peer (tick_peer.hpp) on a private
// domain: next_tick, answer, run_control_loop and how it ends, send_aligned, info.
#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "tick_peer.hpp"
#include "tick_phase.hpp"

namespace robotd::testing {
namespace {

using namespace std::chrono_literals;

// Generous: discovery and delivery on a loaded 2-core machine under a sanitizer.
constexpr auto kPatience = 10s;

class ClosedLoopTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto connected = Client::connect(peer_.client_options());
    ASSERT_TRUE(connected) << connected.error().message;
    client_.emplace(std::move(connected.value()));
    SessionRequest request;
    request.device = std::string(kPeerDevice);
    request.closed_loop = true;
    auto granted = client_->request_control(request);
    ASSERT_TRUE(granted) << granted.error().message;
    session_.emplace(std::move(granted.value()));
    ASSERT_TRUE(peer_.await_tick_reader(kPatience));
  }

  /// Plays the device: writes the first tick, then each next tick once the previous one's answer
  /// arrived (`next(answered)` names it), until stopped. Records the answers.
  std::jthread play_ticks(std::uint64_t first, std::function<std::uint64_t(std::uint64_t)> next) {
    return std::jthread([this, first, next = std::move(next)](const std::stop_token& stop) {
      peer_.write_tick(first);
      while (!stop.stop_requested()) {
        auto command = peer_.next_command(100ms);
        if (!command) continue;
        answers_.push_back(*command);
        peer_.write_tick(next(command->answers_tick));
      }
    });
  }

  TickPeer peer_;
  std::optional<Client> client_;
  std::optional<Session> session_;
  std::vector<ControlCommand> answers_;
};

TEST_F(ClosedLoopTest, NextTickReturnsEachNewerTickOnceAndAnAnswerNamesIt) {
  peer_.write_tick(7);
  auto state = session_->next_tick(kPatience);
  ASSERT_TRUE(state) << state.error().message;
  EXPECT_EQ(state.value().tick, 7U);
  EXPECT_EQ(state.value().position.size(), 6U);
  EXPECT_DOUBLE_EQ(state.value().position[1], 0.007 + 1);

  // Not again, and not an older tick.
  peer_.write_tick(6);
  auto again = session_->next_tick(200ms);
  ASSERT_FALSE(again);
  EXPECT_EQ(again.error().code, ErrorCode::kTimeout);
  EXPECT_NE(again.error().message.find("newer than tick 7"), std::string::npos) << again.error().message;

  peer_.write_tick(8);
  state = session_->next_tick(kPatience);
  ASSERT_TRUE(state) << state.error().message;
  EXPECT_EQ(state.value().tick, 8U);

  Command torques;
  torques.torques = {1, 2, 3, 4, 5, 6};
  ASSERT_TRUE(session_->answer(state.value(), torques));
  const auto answer = peer_.next_command(kPatience);
  ASSERT_TRUE(answer);
  EXPECT_EQ(answer->answers_tick, 8U);
  EXPECT_EQ(answer->uuid, "uuid-of-tick_client");
  EXPECT_EQ(answer->device, kPeerDevice);
  EXPECT_EQ(answer->torques, torques.torques);
  EXPECT_EQ(answer->motor_ids, (std::vector<std::int32_t>{0, 1, 2, 3, 4, 5}));
  EXPECT_GT(answer->sent_steady_ns, 0);

  // A plain command answers no tick.
  ASSERT_TRUE(session_->command(torques));
  const auto plain = peer_.next_command(kPatience);
  ASSERT_TRUE(plain);
  EXPECT_EQ(plain->answers_tick, 0U);
}

TEST_F(ClosedLoopTest, AnAnswerToAnotherDevicesTickIsRefusedAndNothingIsSent) {
  TickState other = TickPeer::tick_state(3);
  other.header.frame_id = "leg";
  const auto refused = session_->answer(other, Command{});
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(refused.error().message.find("'leg'"), std::string::npos) << refused.error().message;
  EXPECT_FALSE(peer_.next_command(300ms));
}

TEST_F(ClosedLoopTest, ControlLoopAnswersEachTickUntilTheLawFinishesAndCountsGaps) {
  // Ticks 1, 2, 3, then 7 (4..6 never reach the client), 8, ...
  auto playing = play_ticks(1, [](std::uint64_t answered) { return answered == 3 ? 7 : answered + 1; });
  std::vector<std::uint64_t> seen;
  auto report = session_->run_control_loop(
      [&](const TickState& state) {
        seen.push_back(state.tick);
        Command command;
        command.torques.assign(6, static_cast<float>(state.tick));
        command.finished = seen.size() == 10;
        return command;
      },
      {.state_timeout = kPatience});
  ASSERT_TRUE(report) << report.error().message;
  EXPECT_TRUE(report.value().finished);
  EXPECT_EQ(report.value().ticks_seen, 10U);
  EXPECT_EQ(report.value().ticks_answered, 10U);
  EXPECT_EQ(report.value().ticks_skipped, 3U);
  EXPECT_EQ(report.value().first_tick, 1U);
  EXPECT_EQ(report.value().last_tick, 13U);
  EXPECT_EQ(seen, (std::vector<std::uint64_t>{1, 2, 3, 7, 8, 9, 10, 11, 12, 13}));

  // Each answer named its tick and carried what the law returned for it; none came after the last.
  std::this_thread::sleep_for(200ms);
  playing.request_stop();
  playing.join();  // answers_ is the player's until then
  ASSERT_GE(answers_.size(), 9U);
  for (std::size_t i = 0; i < answers_.size(); ++i) {
    EXPECT_EQ(answers_[i].answers_tick, seen[i]);
    EXPECT_EQ(answers_[i].torques, std::vector<float>(6, static_cast<float>(seen[i])));
  }
}

TEST_F(ClosedLoopTest, ControlLoopEndsWithATimeoutErrorNamingTheLastTickWhenTicksStop) {
  peer_.write_tick(1);
  int calls = 0;
  auto report = session_->run_control_loop(
      [&](const TickState& /*state*/) {
        ++calls;
        return Command{};
      },
      {.state_timeout = 300ms});
  ASSERT_FALSE(report);
  EXPECT_EQ(report.error().code, ErrorCode::kTimeout);
  EXPECT_EQ(calls, 1);
  EXPECT_NE(report.error().message.find("the last 1; 1 answered"), std::string::npos) << report.error().message;
}

TEST_F(ClosedLoopTest, StopFlagEndsTheLoopAfterTheAnswerToTheTickItWasSetOn) {
  const auto playing = play_ticks(1, [](std::uint64_t answered) { return answered + 1; });
  std::atomic<bool> stop{false};
  auto report = session_->run_control_loop(
      [&](const TickState& state) {
        if (state.tick == 5) stop.store(true);
        return Command{};
      },
      {.stop = &stop, .state_timeout = kPatience});
  ASSERT_TRUE(report) << report.error().message;
  EXPECT_FALSE(report.value().finished);
  EXPECT_EQ(report.value().ticks_seen, 5U);
  EXPECT_EQ(report.value().ticks_answered, 5U);
}

TEST_F(ClosedLoopTest, NextTickFailsOnceRobotdNoLongerListsTheSession) {
  peer_.write_session_status(true, 42);
  auto info = session_->info(kPatience);
  ASSERT_TRUE(info) << info.error().message;
  EXPECT_EQ(info.value().ticks_answered_in_time, 42U);
  EXPECT_TRUE(info.value().closed_loop);

  peer_.write_session_status(false);
  auto state = session_->next_tick(kPatience);
  ASSERT_FALSE(state);
  EXPECT_EQ(state.error().code, ErrorCode::kRefused);
  EXPECT_NE(state.error().message.find(std::string(kPeerSessionId) + " on 'arm' has ended"), std::string::npos)
      << state.error().message;
}

TEST_F(ClosedLoopTest, ASessionRobotdNeverListedEndsAtTheSecondStatusWithoutIt) {
  // The first status may predate the grant: it ends nothing.
  peer_.write_session_status(false);
  peer_.write_tick(1);
  auto state = session_->next_tick(kPatience);
  ASSERT_TRUE(state) << state.error().message;
  EXPECT_EQ(state.value().tick, 1U);

  // A later one without the session does (repeated: two written back to back may arrive as one).
  const auto deadline = std::chrono::steady_clock::now() + kPatience;
  Result<TickState> next = make_error(ErrorCode::kTimeout, "not yet");
  while (!next && next.error().code == ErrorCode::kTimeout && std::chrono::steady_clock::now() < deadline) {
    peer_.write_session_status(false);
    next = session_->next_tick(50ms);
  }
  ASSERT_FALSE(next);
  EXPECT_EQ(next.error().code, ErrorCode::kRefused) << next.error().message;
}

TEST(SendAligned, PublishesNoEarlierThanTheLeadBeforeATickOfTheDevicesPhase) {
  // A streaming session, no tick reader: the phase comes from /device_status (ticks due at
  // 0.3 ms + n × 1 ms).
  TickPeer other_peer;
  auto connected = Client::connect(other_peer.client_options());
  ASSERT_TRUE(connected) << connected.error().message;
  SessionRequest request;
  request.device = std::string(kPeerDevice);
  auto session = connected.value().request_control(request);
  ASSERT_TRUE(session) << session.error().message;
  const detail::TickPhase phase{300'000, kPeerPeriodNs};
  std::jthread statuses([&](const std::stop_token& stop) {
    while (!stop.stop_requested()) {
      other_peer.write_device_status(phase.deadline_steady_ns, phase.period_ns);
      std::this_thread::sleep_for(20ms);
    }
  });
  const std::int64_t lead_ns = 150'000;
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  const std::int64_t earliest = detail::aligned_send_time_ns(phase, now.tv_sec * 1'000'000'000 + now.tv_nsec, lead_ns);
  Command positions;
  positions.positions.assign(6, 0.1F);
  ASSERT_TRUE(session.value().send_aligned(positions, 150us));
  const auto sent = other_peer.next_command(kPatience);
  ASSERT_TRUE(sent);
  EXPECT_EQ(sent->answers_tick, 0U);
  EXPECT_GE(sent->sent_steady_ns, earliest);
}

TEST(TickPhase, AlignedSendTimeIsTheLeadBeforeTheFirstTickDueAfterNowPlusTheLead) {
  const detail::TickPhase phase{1'300'000, 1'000'000};  // ticks at …, 0.3 ms, 1.3 ms, 2.3 ms, …
  EXPECT_EQ(detail::aligned_send_time_ns(phase, 5'000'000, 200'000), 5'100'000);    // tick 5.3 ms
  EXPECT_EQ(detail::aligned_send_time_ns(phase, 5'100'000, 200'000), 5'100'000);    // exactly on it
  EXPECT_EQ(detail::aligned_send_time_ns(phase, 5'100'001, 200'000), 6'100'000);    // just missed: the next
  EXPECT_EQ(detail::aligned_send_time_ns(phase, 200'000, 50'000), 250'000);         // before the deadline known
  EXPECT_EQ(detail::aligned_send_time_ns(phase, 5'000'000, 1'500'000), 5'800'000);  // a lead over a period
}

}  // namespace
}  // namespace robotd::testing
