// A closed-loop session's answers as the loop books them: each offered tick decided once, in time
// or not; late answers; the rate over the window and the session's minimum.
#include "device/answer_book.hpp"

#include <gtest/gtest.h>

namespace robotd::device {
namespace {

class AnswerBookTest : public ::testing::Test {
 protected:
  AnswerBookTest() { book_.start(7, 0); }

  // One loop tick `now`: the session's newest command answers `answered` (0 = none); the
  // newest offered state before this tick is `offered_`; afterwards this tick's state is offered
  // when it is due (every `every_` ticks).
  void tick(std::uint64_t now, std::uint64_t answered) {
    book_.take_answer(answered, offered_, true);
    book_.close_overdue(offered_, now, every_);
    book_.end_tick();
    if (now % every_ == 0) offered_ = now;
  }

  AnswerBook book_;
  std::uint64_t offered_ = 0;
  std::uint64_t every_ = 1;
};

TEST_F(AnswerBookTest, ASessionThatNamesNoTickIsNotClosedLoopAndCountsNothing) {
  for (std::uint64_t t = 1; t <= 50; ++t) tick(t, 0);
  EXPECT_FALSE(book_.counts().closed_loop);
  EXPECT_EQ(book_.counts().to_answer, 0U);
  EXPECT_EQ(book_.counts().generation, 7U);
}

TEST_F(AnswerBookTest, AnAnswerTakenOnTheNextTickIsInTime) {
  tick(1, 0);
  for (std::uint64_t t = 2; t <= 11; ++t) tick(t, t - 1);  // each tick takes the answer to the one before
  const AnswerCounts& counts = book_.counts();
  EXPECT_TRUE(counts.closed_loop);
  EXPECT_EQ(counts.to_answer, 10U);
  EXPECT_EQ(counts.in_time, 10U);
  EXPECT_EQ(counts.unanswered, 0U);
  EXPECT_EQ(counts.late, 0U);
  EXPECT_FLOAT_EQ(counts.success_rate, 1.0F);
}

TEST_F(AnswerBookTest, AMissedTickIsUnansweredAndItsLaterAnswerCountsLate) {
  tick(1, 0);
  tick(2, 1);  // in time
  tick(3, 1);  // tick 2's answer has not come: decided unanswered here
  EXPECT_EQ(book_.counts().unanswered, 1U);
  tick(4, 2);  // tick 2's answer, a tick late; tick 3 unanswered
  const AnswerCounts& counts = book_.counts();
  EXPECT_EQ(counts.to_answer, 3U);  // ticks 1, 2, 3
  EXPECT_EQ(counts.in_time, 1U);
  EXPECT_EQ(counts.late, 1U);
  EXPECT_EQ(counts.unanswered, 1U);
  EXPECT_FLOAT_EQ(counts.success_rate, 1.0F / 3.0F);
}

TEST_F(AnswerBookTest, AnAnswerSupersededBeforeATickTookItWasNeverApplied) {
  tick(1, 0);
  tick(2, 1);
  tick(3, 0);  // nothing new: tick 2 unanswered
  tick(4, 3);  // the answers to 2 and 3 both came; the mailbox holds only the newer: tick 3 in time
  const AnswerCounts& counts = book_.counts();
  EXPECT_EQ(counts.in_time, 2U);
  EXPECT_EQ(counts.unanswered, 1U);
  EXPECT_EQ(counts.late, 0U);
}

TEST_F(AnswerBookTest, RepeatsAndTicksNeverOfferedCountForNothing) {
  tick(1, 0);
  tick(2, 1);
  tick(3, 2);
  tick(4, 3);
  EXPECT_FALSE(book_.take_answer(3, offered_, true));  // the same answer, still in the mailbox
  EXPECT_FALSE(book_.take_answer(9, offered_, true));  // a tick the loop has not run yet
  EXPECT_EQ(book_.counts().to_answer, 3U);
  EXPECT_EQ(book_.counts().in_time, 3U);
}

TEST_F(AnswerBookTest, AnAnswerToATickWhoseStateWasNotOfferedDecidesNothing) {
  // Ticks 1 and 2 ran e-stopped (their states published, not offered); tick 3 was offered.
  offered_ = 3;
  EXPECT_TRUE(book_.take_answer(1, offered_, false));
  book_.close_overdue(offered_, 4, 1);  // tick 3 is decided: not answered
  EXPECT_EQ(book_.counts().to_answer, 1U);
  EXPECT_EQ(book_.counts().unanswered, 1U);
  EXPECT_EQ(book_.counts().late, 0U);
  offered_ = 4;
  EXPECT_TRUE(book_.take_answer(4, offered_, true));
  EXPECT_EQ(book_.counts().to_answer, 2U);
  EXPECT_EQ(book_.counts().in_time, 1U);
}

TEST_F(AnswerBookTest, AStateEveryOtherTickGivesItsAnswerUntilTheNextState) {
  every_ = 2;
  tick(1, 0);
  tick(2, 0);  // offers tick 2
  tick(3, 0);
  tick(4, 2);  // answered on the tick the next state is offered: in time
  tick(5, 0);
  tick(6, 0);  // tick 4 unanswered by the next state
  tick(7, 4);  // late
  const AnswerCounts& counts = book_.counts();
  EXPECT_EQ(counts.to_answer, 2U);
  EXPECT_EQ(counts.in_time, 1U);
  EXPECT_EQ(counts.late, 1U);
  EXPECT_EQ(counts.unanswered, 0U);
}

TEST_F(AnswerBookTest, TheRateCoversTheLastWindowAndTheMinimumIsJudgedOnAFullWindow) {
  book_.start(8, 0.95F);
  tick(1, 0);
  std::uint64_t t = 2;
  // One tick in ten unanswered: 90 %, but nothing is judged before the window is full.
  for (; t <= kSuccessRateWindowTicks; ++t) {
    tick(t, t % 10 == 0 ? 0 : t - 1);
    ASSERT_FALSE(book_.counts().rate_low) << "tick " << t;
  }
  bool fell = false;
  for (; t <= kSuccessRateWindowTicks + 5; ++t) {
    book_.take_answer(t % 10 == 0 ? 0 : t - 1, offered_, true);
    book_.close_overdue(offered_, t, 1);
    fell = fell || book_.fell_below_minimum();
    book_.end_tick();
    offered_ = t;
  }
  EXPECT_TRUE(fell);
  EXPECT_TRUE(book_.counts().rate_low);
  EXPECT_NEAR(book_.counts().success_rate, 0.9, 0.011);
  // Every tick answered from here: the missed ones leave the window and the rate recovers.
  bool recovered = false;
  for (const std::uint64_t end = t + kSuccessRateWindowTicks; t < end; ++t) {
    book_.take_answer(t - 1, offered_, true);
    book_.close_overdue(offered_, t, 1);
    recovered = recovered || book_.recovered();
    ASSERT_FALSE(book_.fell_below_minimum());
    book_.end_tick();
    offered_ = t;
  }
  EXPECT_TRUE(recovered);
  EXPECT_FALSE(book_.counts().rate_low);
  EXPECT_FLOAT_EQ(book_.counts().success_rate, 1.0F);
}

TEST_F(AnswerBookTest, ANewSessionStartsWithAnEmptyRecord) {
  tick(1, 0);
  tick(2, 1);
  book_.start(9, 0);
  EXPECT_EQ(book_.counts().generation, 9U);
  EXPECT_FALSE(book_.counts().closed_loop);
  EXPECT_EQ(book_.counts().to_answer, 0U);
}

}  // namespace
}  // namespace robotd::device
