// End to end through a real robotd: closed-loop control over DDS. A client reads each tick's
// state on /arm/tick_state and answers it (ControlCommand.answers_tick); robotd books every
// answer for the session and applies the session's minimum success rate. No timing is asserted:
// how many ticks a loaded host answers in time is the closed_loop bench's business.
#include <chrono>
#include <thread>

#include <gtest/gtest.h>

#include "robotd_fixture.hpp"
#include "sample_queue.hpp"
#include "wire/participant.hpp"
#include "wire/qos.hpp"
#include "wire/topic_io.hpp"
#include "wire/topics.hpp"

namespace robotd::testing {
namespace {

using namespace std::chrono_literals;

class ClosedLoopTest : public RobotdTest {
 protected:
  /// A raw DDS client of the arm's tick states (plain wire types, as any DDS program would).
  void open_tick_reader() {
    wire::DdsSettings settings;
    settings.domain_id = domain_.id();
    auto participant = wire::Participant::create(settings);
    ASSERT_TRUE(participant) << participant.error().message;
    participant_.emplace(std::move(participant.value()));
    const auto qos = wire::reliable_qos(1);
    auto reader = wire::TopicReader<TickState>::create(*participant_, wire::tick_state_topic("arm"), qos.get());
    ASSERT_TRUE(reader) << reader.error().message;
    reader_.emplace(std::move(reader.value()));
  }

  /// The next tick state newer than `after`, or none within `timeout`.
  std::optional<TickState> next_tick(std::uint64_t after, std::chrono::milliseconds timeout = 5s) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    std::optional<TickState> newest;
    while (std::chrono::steady_clock::now() < deadline) {
      reader_->take_each([&](TickState&& state, const dds_sample_info_t& /*info*/) {
        if (state.tick > after && (!newest || state.tick > newest->tick)) newest = std::move(state);
      });
      if (newest) return newest;
      std::this_thread::sleep_for(100us);
    }
    return std::nullopt;
  }

  /// A session on every motor of the arm that asks for a success rate of at least 0.9.
  Result<Session> minimum_rate_session(LowRateAction below) {
    SessionRequest request;
    request.device = "arm";
    request.on_timeout = Behavior::kKeep;
    request.min_command_success_rate = 0.9F;
    request.on_low_success_rate = below;
    return client().request_control(request);
  }

  /// Holds every joint where it is, answering `state`.
  Result<void> answer(const Session& session, const TickState& state, const std::vector<float>& hold) {
    ControlCommand command;
    command.uuid = session.uuid();
    command.motor_ids = session.motor_ids();
    command.positions = hold;
    command.answers_tick = state.tick;
    return client().publish(command);
  }

  /// This session's entry in /session_status once `predicate` holds, or the last one seen.
  std::optional<SessionInfo> session_info(const Session& session,
                                          const std::function<bool(const SessionInfo&)>& predicate) {
    std::optional<SessionInfo> last;
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    while (std::chrono::steady_clock::now() < deadline) {
      auto status = client().session_status(2s);
      if (status) {
        for (const SessionInfo& info : status.value().sessions) {
          if (info.uuid != session.session_id()) continue;
          last = info;
          if (predicate(info)) return last;
        }
      }
      std::this_thread::sleep_for(50ms);
    }
    return last;
  }

  std::optional<wire::Participant> participant_;
  std::optional<wire::TopicReader<TickState>> reader_;
};

std::vector<float> positions_of(const TickState& state) { return {state.position.begin(), state.position.end()}; }

TEST_F(ClosedLoopTest, EachTicksStateComesWithItsNumberAndDeadlineAndTheSessionsAnswersAreBooked) {
  start_robotd();
  open_tick_reader();
  Session session = acquire_device("arm");
  auto first = next_tick(0);
  ASSERT_TRUE(first) << "no /arm/tick_state sample";
  const std::vector<float> hold = positions_of(*first);

  TickState previous = *first;
  int answered = 0;
  for (; answered < 300; ++answered) {
    auto state = next_tick(previous.tick);
    ASSERT_TRUE(state) << "tick states stopped after tick " << previous.tick;
    EXPECT_EQ(state->header.frame_id, "arm");
    EXPECT_EQ(state->state, DeviceState::kRunning);
    EXPECT_EQ(state->position.size(), 6U);
    EXPECT_EQ(state->period_ns, 1'000'000);  // the test arm runs at 1 kHz
    // Deadlines lie on the loop's grid: a whole number of periods apart, at least one per tick
    // (more when the loop skipped a deadline it overran).
    const std::int64_t apart = state->deadline_steady_ns - previous.deadline_steady_ns;
    const auto ticks_apart = static_cast<std::int64_t>(state->tick - previous.tick);
    EXPECT_EQ(apart % state->period_ns, 0) << "tick " << state->tick;
    EXPECT_GE(apart, ticks_apart * state->period_ns) << "tick " << state->tick;
    EXPECT_GE(state->state_ready_steady_ns, state->deadline_steady_ns);
    EXPECT_GE(state->published_steady_ns, state->state_ready_steady_ns);
    ASSERT_TRUE(answer(session, *state, hold));
    previous = *state;
  }

  const auto info = session_info(session, [&](const SessionInfo& i) { return i.ticks_to_answer >= 250; });
  ASSERT_TRUE(info) << "the session is not in /session_status";
  EXPECT_TRUE(info->closed_loop);
  EXPECT_GE(info->ticks_to_answer, 250U);
  EXPECT_GT(info->ticks_answered_in_time, 0U);
  EXPECT_EQ(info->ticks_answered_in_time + info->ticks_answered_late + info->ticks_unanswered, info->ticks_to_answer);
  EXPECT_GT(info->command_success_rate, 0.0F);
  EXPECT_FALSE(info->success_rate_low);  // no minimum asked for
  std::printf("[ measured ] %d ticks answered: %llu to answer, %llu in time, %llu late, %llu never; rate %.3f\n",
              answered, static_cast<unsigned long long>(info->ticks_to_answer),
              static_cast<unsigned long long>(info->ticks_answered_in_time),
              static_cast<unsigned long long>(info->ticks_answered_late),
              static_cast<unsigned long long>(info->ticks_unanswered), info->command_success_rate);
}

TEST_F(ClosedLoopTest, JointStatesAreStampedWithTheDeadlineOfTheTickThatMeasuredThem) {
  start_robotd();
  open_tick_reader();
  SampleQueue<JointState> joint_states;
  const Subscription subscription =
      client().on_joint_states([&](const JointState& state) { joint_states.offer(state); });
  // A tick state and a joint state of the same tick carry the same stamp and the same positions.
  bool matched = false;
  for (int attempt = 0; attempt < 200 && !matched; ++attempt) {
    auto tick = next_tick(0);
    ASSERT_TRUE(tick);
    const auto same = joint_states.wait_for(
        [&](const JointState& state) { return state.header.stamp.to_ns() >= tick->header.stamp.to_ns(); }, 2s);
    ASSERT_TRUE(same);
    if (same->header.stamp.to_ns() != tick->header.stamp.to_ns()) continue;  // the next tick's came first
    matched = true;
    EXPECT_EQ(same->header.frame_id, "arm");
    for (std::size_t j = 0; j < same->position.size(); ++j) EXPECT_DOUBLE_EQ(same->position[j], tick->position[j]);
  }
  EXPECT_TRUE(matched) << "no /joint_states sample was stamped like a tick state";
}

TEST_F(ClosedLoopTest, ASessionBelowItsMinimumSuccessRateFallsBackWhenItAskedTo) {
  start_robotd();
  open_tick_reader();
  auto granted = minimum_rate_session(LowRateAction::kFallback);
  ASSERT_TRUE(granted) << granted.error().message;
  Session& session = granted.value();
  auto first = next_tick(0);
  ASSERT_TRUE(first);
  const std::vector<float> hold = positions_of(*first);

  // Answers every third tick (and so stays well inside the session's timeout): a third at most.
  std::uint64_t last = first->tick;
  bool ended = false;
  for (int i = 0; i < 3000 && !ended; ++i) {
    auto state = next_tick(last + 2, 1s);
    if (!state) break;
    last = state->tick;
    ASSERT_TRUE(answer(session, *state, hold));
    auto status = client().session_status(1s);
    ended = status && status.value().sessions.empty();
  }
  EXPECT_TRUE(ended) << "the session kept its motors at a success rate of a third";
  // Its motors are free: another client may take them.
  SessionRequest next_request;
  next_request.device = "arm";
  auto next = make_client("next").request_control(next_request);
  EXPECT_TRUE(next) << next.error().message;
}

TEST_F(ClosedLoopTest, ASessionBelowItsMinimumThatOnlyWarnsKeepsItsMotorsAndIsFlagged) {
  start_robotd();
  open_tick_reader();
  auto granted = minimum_rate_session(LowRateAction::kWarn);
  ASSERT_TRUE(granted) << granted.error().message;
  Session& session = granted.value();
  auto first = next_tick(0);
  ASSERT_TRUE(first);
  const std::vector<float> hold = positions_of(*first);

  std::uint64_t last = first->tick;
  std::optional<SessionInfo> info;
  for (int i = 0; i < 3000; ++i) {
    auto state = next_tick(last + 2, 1s);
    ASSERT_TRUE(state);
    last = state->tick;
    ASSERT_TRUE(answer(session, *state, hold));
    if (i % 20 != 19) continue;
    auto status = client().session_status(1s);
    ASSERT_TRUE(status);
    ASSERT_EQ(status.value().sessions.size(), 1U) << "a session that only warns was ended";
    info = status.value().sessions[0];
    if (info->success_rate_low) break;
  }
  ASSERT_TRUE(info);
  EXPECT_TRUE(info->success_rate_low);
  EXPECT_FLOAT_EQ(info->min_command_success_rate, 0.9F);
  EXPECT_EQ(info->on_low_success_rate, LowRateAction::kWarn);
  EXPECT_LT(info->command_success_rate, 0.9F);
}

TEST_F(ClosedLoopTest, AnAnswerToATickTheDeviceHasNotRunIsRejectedAndMovesNothing) {
  start_robotd();
  Session session = acquire_device("arm");
  const DeviceStatus before = device_status();
  ControlCommand command;
  command.uuid = session.uuid();
  command.motor_ids = {0};
  command.positions = {1.0F};
  command.answers_tick = before.loop.ticks + 1'000'000'000ULL;
  ASSERT_TRUE(client().publish(command));
  DeviceStatus after = before;
  for (int i = 0; i < 100 && after.commands.rejected_malformed == before.commands.rejected_malformed; ++i) {
    std::this_thread::sleep_for(20ms);
    after = device_status();
  }
  EXPECT_EQ(after.commands.rejected_malformed, before.commands.rejected_malformed + 1);
  EXPECT_EQ(after.commands.accepted, before.commands.accepted);
  EXPECT_NEAR(joint_state().position[0], 0.0, 0.01);
}

}  // namespace
}  // namespace robotd::testing
