// The interpreter's control flow against an executor that records what it is asked to do: the
// statements reach the executor as parsed, End, Loop with and without a limit, the stop flag,
// progress, and an executor's error ending the run at its statement.
#include "robotd/rbtscript/interpreter.hpp"

#include <atomic>
#include <cstddef>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "parse_helpers.hpp"

namespace robotd::rbtscript {
namespace {

using test::parse_ok;

/// Records each statement it gets; can fail its n-th call or set a stop flag during it.
class RecordingExecutor final : public Executor {
 public:
  std::vector<StatementKind> calls;
  std::size_t fail_at = 0;  // 1-based call number; 0: never
  std::size_t stop_at = 0;  // 1-based call number at which `stop` is set; 0: never
  std::atomic<bool> stop{false};

  Result<void> move_joint(const MoveJoint& s) override { return record(s); }
  Result<void> move_pose(const MovePose& s) override { return record(s); }
  Result<void> move_cart(const MoveCart& s) override { return record(s); }
  Result<void> move_cart_rel_trf(const MoveCartRelTrf& s) override { return record(s); }
  Result<void> delay(const Delay& s) override { return record(s); }
  Result<void> output(const Output& s) override { return record(s); }
  Result<void> gripper_calibrate(const GripperCalibrate& s) override { return record(s); }
  Result<void> gripper(const Gripper& s) override { return record(s); }

 private:
  Result<void> record(const StatementKind& statement) {
    calls.push_back(statement);
    if (calls.size() == stop_at) stop = true;
    if (calls.size() == fail_at) return make_error(ErrorCode::kRefused, "the gripper is not calibrated");
    return {};
  }
};

RunOptions with_loops(std::size_t loops) {
  RunOptions options;
  options.loops = loops;
  return options;
}

TEST(RbtscriptInterpreter, EveryStatementReachesItsExecutorCallAsParsed) {
  const Program program = parse_ok(
      "Begin()\n"
      "MoveJoint(1,2,3,4,5,6,v=50,a=40)\n"
      "MovePose(10,20,30,0,90,0,t=2,trap)\n"
      "MoveCart(10,20,40,0,90,0,t=1,speed)\n"
      "MoveCartRelTRF(-80,0,0,0,0,0)\n"
      "Delay(0.5)\n"
      "Output(2,HIGH)\n"
      "Gripper_cal()\n"
      "Gripper(100,60,600)\n");
  RecordingExecutor executor;
  const RunOutcome outcome = run_program(program, executor);
  EXPECT_EQ(outcome.end, RunEnd::kEndOfProgram);
  EXPECT_EQ(outcome.statements_run, 9U);
  EXPECT_EQ(outcome.passes, 1U);
  EXPECT_FALSE(outcome.error.has_value());
  ASSERT_EQ(executor.calls.size(), 8U);  // Begin() is the interpreter's
  for (std::size_t i = 0; i < executor.calls.size(); ++i) EXPECT_EQ(executor.calls[i], program.statements[i + 1].kind);
}

TEST(RbtscriptInterpreter, EndEndsTheRun) {
  const Program program = parse_ok("Delay(1)\nEnd()\nDelay(2)\n");
  RecordingExecutor executor;
  const RunOutcome outcome = run_program(program, executor);
  EXPECT_EQ(outcome.end, RunEnd::kEnd);
  EXPECT_EQ(outcome.statements_run, 2U);
  EXPECT_EQ(executor.calls, std::vector<StatementKind>{Delay{1}});
}

TEST(RbtscriptInterpreter, LoopStartsOverForTheGivenNumberOfPasses) {
  const Program program = parse_ok("Begin()\nOutput(1,HIGH)\nDelay(1)\nOutput(1,LOW)\nLoop()\nDelay(9)\n");
  RecordingExecutor executor;
  const RunOutcome outcome = run_program(program, executor, with_loops(3));
  EXPECT_EQ(outcome.end, RunEnd::kLoopLimit);
  EXPECT_EQ(outcome.passes, 3U);
  EXPECT_EQ(outcome.statements_run, 15U);
  const std::vector<StatementKind> pass = {Output{1, Level::kHigh}, Delay{1}, Output{1, Level::kLow}};
  std::vector<StatementKind> expected;
  for (int i = 0; i < 3; ++i) expected.insert(expected.end(), pass.begin(), pass.end());
  EXPECT_EQ(executor.calls, expected);  // never the Delay(9) after Loop()
}

TEST(RbtscriptInterpreter, LoopGoesBackToTheFirstStatement) {
  const Program program = parse_ok("Delay(1)\nBegin()\nDelay(2)\nLoop()\n");
  RecordingExecutor executor;
  EXPECT_EQ(run_program(program, executor, with_loops(2)).end, RunEnd::kLoopLimit);
  EXPECT_EQ(executor.calls, (std::vector<StatementKind>{Delay{1}, Delay{2}, Delay{1}, Delay{2}}));
}

TEST(RbtscriptInterpreter, ZeroLoopsRunsNothing) {
  const Program program = parse_ok("Delay(1)\nLoop()\n");
  RecordingExecutor executor;
  const RunOutcome outcome = run_program(program, executor, with_loops(0));
  EXPECT_EQ(outcome.end, RunEnd::kLoopLimit);
  EXPECT_EQ(outcome.passes, 0U);
  EXPECT_TRUE(executor.calls.empty());
}

TEST(RbtscriptInterpreter, EndBeforeLoopEndsTheFirstPass) {
  const Program program = parse_ok("Delay(1)\nEnd()\nLoop()\n");
  RecordingExecutor executor;
  const RunOutcome outcome = run_program(program, executor, with_loops(5));
  EXPECT_EQ(outcome.end, RunEnd::kEnd);
  EXPECT_EQ(outcome.passes, 1U);
  EXPECT_EQ(executor.calls.size(), 1U);
}

TEST(RbtscriptInterpreter, WithoutALimitLoopRunsUntilStopped) {
  const Program program = parse_ok("Begin()\nDelay(1)\nDelay(2)\nLoop()\n");
  RecordingExecutor executor;
  executor.stop_at = 7;  // during the first Delay of the fourth pass
  RunOptions options;
  options.stop = &executor.stop;
  const RunOutcome outcome = run_program(program, executor, options);
  EXPECT_EQ(outcome.end, RunEnd::kStopped);
  EXPECT_EQ(outcome.passes, 4U);
  EXPECT_EQ(executor.calls.size(), 7U);  // the flag is checked before the next statement
  EXPECT_FALSE(outcome.error.has_value());
}

TEST(RbtscriptInterpreter, StopSetBeforeTheRunRunsNothing) {
  const Program program = parse_ok("Delay(1)\n");
  RecordingExecutor executor;
  executor.stop = true;
  RunOptions options;
  options.stop = &executor.stop;
  const RunOutcome outcome = run_program(program, executor, options);
  EXPECT_EQ(outcome.end, RunEnd::kStopped);
  EXPECT_EQ(outcome.statements_run, 0U);
  EXPECT_TRUE(executor.calls.empty());
}

TEST(RbtscriptInterpreter, ExecutorErrorEndsTheRunAtItsStatement) {
  const Program program = parse_ok("Begin()\nGripper_cal()\n  Gripper(100,60,600) // close\nDelay(2)\n");
  RecordingExecutor executor;
  executor.fail_at = 2;
  const RunOutcome outcome = run_program(program, executor);
  EXPECT_EQ(outcome.end, RunEnd::kFailed);
  EXPECT_EQ(executor.calls.size(), 2U);
  ASSERT_TRUE(outcome.error.has_value());
  EXPECT_EQ(outcome.error->index, 2U);
  EXPECT_EQ(outcome.error->location, (SourceLocation{3, 3}));
  EXPECT_EQ(outcome.error->text, "Gripper(100,60,600)");
  EXPECT_EQ(outcome.error->message, "the gripper is not calibrated");
  EXPECT_EQ(outcome.error->to_string(), "line 3, column 3: Gripper(100,60,600): the gripper is not calibrated");
}

TEST(RbtscriptInterpreter, AStatementThatFailsOnceStoppedEndsTheRunAsStopped) {
  const Program program = parse_ok("Delay(5)\nDelay(1)\n");
  RecordingExecutor executor;
  executor.stop_at = 1;
  executor.fail_at = 1;  // a delay cut short by the stop
  RunOptions options;
  options.stop = &executor.stop;
  const RunOutcome outcome = run_program(program, executor, options);
  EXPECT_EQ(outcome.end, RunEnd::kStopped);
  EXPECT_FALSE(outcome.error.has_value());
}

TEST(RbtscriptInterpreter, ProgressReportsEachStatementBeforeItRuns) {
  const Program program = parse_ok("Begin()\n  Delay(1) // wait\nLoop()\n");
  RecordingExecutor executor;
  std::vector<std::string> reports;
  RunOptions options = with_loops(2);
  options.on_statement = [&](const Progress& progress) {
    reports.push_back(std::to_string(progress.pass) + ":" + std::to_string(progress.index) + "@" +
                      std::to_string(progress.location.line) + "," + std::to_string(progress.location.column) + " " +
                      std::string(progress.text) + " after " + std::to_string(executor.calls.size()));
  };
  EXPECT_EQ(run_program(program, executor, options).end, RunEnd::kLoopLimit);
  EXPECT_EQ(reports, (std::vector<std::string>{"1:0@1,1 Begin() after 0", "1:1@2,3 Delay(1) after 0",
                                               "1:2@3,1 Loop() after 1", "2:0@1,1 Begin() after 1",
                                               "2:1@2,3 Delay(1) after 1", "2:2@3,1 Loop() after 2"}));
}

TEST(RbtscriptInterpreter, AnEmptyProgramEndsAtOnce) {
  RecordingExecutor executor;
  const RunOutcome outcome = run_program(Program{}, executor);
  EXPECT_EQ(outcome.end, RunEnd::kEndOfProgram);
  EXPECT_EQ(outcome.statements_run, 0U);
}

}  // namespace
}  // namespace robotd::rbtscript
