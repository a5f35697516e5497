// Running a Program: the interpreter walks the statements and handles the control flow (Begin,
// End, Loop, the stop flag); an Executor carries out each other statement on a device, or only
// checks it (a dry run uses the same interpreter with a checking executor).
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "robotd/rbtscript/program.hpp"
#include "robotd/result.hpp"

namespace robotd::rbtscript {

/// One call per statement kind that does something on the arm. Each returns once the statement is
/// done (a move has arrived, a delay has passed) or has failed; the error message says why
/// (the interpreter adds where). A long statement should end early when the run's stop flag
/// is set: Delay goes through here for that reason.
class Executor {
 public:
  virtual ~Executor() = default;
  virtual Result<void> move_joint(const MoveJoint& statement) = 0;
  virtual Result<void> move_pose(const MovePose& statement) = 0;
  virtual Result<void> move_cart(const MoveCart& statement) = 0;
  virtual Result<void> move_cart_rel_trf(const MoveCartRelTrf& statement) = 0;
  virtual Result<void> delay(const Delay& statement) = 0;
  virtual Result<void> output(const Output& statement) = 0;
  virtual Result<void> gripper_calibrate(const GripperCalibrate& statement) = 0;
  virtual Result<void> gripper(const Gripper& statement) = 0;
};

/// Reported before each statement runs.
struct Progress {
  std::size_t index = 0;  // into Program::statements
  SourceLocation location;
  std::string_view text;  // the statement as written
  std::size_t pass = 1;   // 1 on the first way through the program, +1 after each Loop()
};

struct RunOptions {
  /// Loop() starts the program over at most this many times in all (so `loops` passes); unset:
  /// until stopped. 0 runs nothing.
  std::optional<std::size_t> loops;
  /// Checked before each statement; when it is set the run ends there. Executors should watch it
  /// too, to cut a move or a delay short.
  const std::atomic<bool>* stop = nullptr;
  std::function<void(const Progress&)> on_statement;
};

enum class RunEnd {
  kEndOfProgram,  // ran past the last statement
  kEnd,           // reached End()
  kLoopLimit,     // reached Loop() after RunOptions::loops passes
  kStopped,       // the stop flag was set (a statement that fails once it is set ended by the stop too)
  kFailed,        // the executor refused or failed a statement: see RunOutcome::error
};

struct RunError {
  std::size_t index = 0;
  SourceLocation location;
  std::string text;     // the statement as written
  std::string message;  // the executor's reason
  /// "line 4, column 1: MoveJoint(0,-90,180,0,0,180,t=4): <message>"
  std::string to_string() const;
};

struct RunOutcome {
  RunEnd end = RunEnd::kEndOfProgram;
  std::size_t statements_run = 0;  // executor calls and control statements, over all passes
  std::size_t passes = 0;          // passes started
  std::optional<RunError> error;   // set when end == kFailed
};

RunOutcome run_program(const Program& program, Executor& executor, const RunOptions& options = {});

}  // namespace robotd::rbtscript
