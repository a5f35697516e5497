#include "robotd/rbtscript/interpreter.hpp"

#include <type_traits>
#include <utility>

namespace robotd::rbtscript {
namespace {

bool stop_requested(const RunOptions& options) {
  return options.stop != nullptr && options.stop->load(std::memory_order_acquire);
}

/// What running one statement asks of the interpreter next.
enum class Next { kContinue, kEnd, kLoop };

struct StepResult {
  Next next = Next::kContinue;
  Result<void> done;
};

StepResult step(const StatementKind& statement, Executor& executor) {
  return std::visit(
      [&executor](const auto& s) -> StepResult {
        using S = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<S, Begin>) {
          return {};  // marks where the program starts; Loop() goes back to the first statement
        } else if constexpr (std::is_same_v<S, End>) {
          return {Next::kEnd, {}};
        } else if constexpr (std::is_same_v<S, Loop>) {
          return {Next::kLoop, {}};
        } else if constexpr (std::is_same_v<S, MoveJoint>) {
          return {Next::kContinue, executor.move_joint(s)};
        } else if constexpr (std::is_same_v<S, MovePose>) {
          return {Next::kContinue, executor.move_pose(s)};
        } else if constexpr (std::is_same_v<S, MoveCart>) {
          return {Next::kContinue, executor.move_cart(s)};
        } else if constexpr (std::is_same_v<S, MoveCartRelTrf>) {
          return {Next::kContinue, executor.move_cart_rel_trf(s)};
        } else if constexpr (std::is_same_v<S, Delay>) {
          return {Next::kContinue, executor.delay(s)};
        } else if constexpr (std::is_same_v<S, Output>) {
          return {Next::kContinue, executor.output(s)};
        } else if constexpr (std::is_same_v<S, GripperCalibrate>) {
          return {Next::kContinue, executor.gripper_calibrate(s)};
        } else {
          static_assert(std::is_same_v<S, Gripper>, "every statement kind is handled");
          return {Next::kContinue, executor.gripper(s)};
        }
      },
      statement);
}

}  // namespace

std::string RunError::to_string() const {
  return "line " + std::to_string(location.line) + ", column " + std::to_string(location.column) + ": " + text + ": " +
         message;
}

RunOutcome run_program(const Program& program, Executor& executor, const RunOptions& options) {
  RunOutcome outcome;
  if (options.loops && *options.loops == 0) {
    outcome.end = RunEnd::kLoopLimit;
    return outcome;
  }
  outcome.passes = 1;
  std::size_t index = 0;
  while (index < program.statements.size()) {
    if (stop_requested(options)) {
      outcome.end = RunEnd::kStopped;
      return outcome;
    }
    const Statement& statement = program.statements[index];
    if (options.on_statement) {
      options.on_statement(Progress{index, statement.location, statement.text, outcome.passes});
    }
    ++outcome.statements_run;
    StepResult result = step(statement.kind, executor);
    if (!result.done) {
      if (stop_requested(options)) {
        outcome.end = RunEnd::kStopped;
      } else {
        outcome.end = RunEnd::kFailed;
        outcome.error = RunError{index, statement.location, statement.text, result.done.error().message};
      }
      return outcome;
    }
    switch (result.next) {
      case Next::kContinue:
        ++index;
        break;
      case Next::kEnd:
        outcome.end = RunEnd::kEnd;
        return outcome;
      case Next::kLoop:
        if (options.loops && outcome.passes >= *options.loops) {
          outcome.end = RunEnd::kLoopLimit;
          return outcome;
        }
        ++outcome.passes;
        index = 0;
        break;
    }
  }
  outcome.end = RunEnd::kEndOfProgram;
  return outcome;
}

}  // namespace robotd::rbtscript
