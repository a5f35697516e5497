// The RBTscript parser (clients/rbtscript) on any script text, and the interpreter on what it
// accepts. The parser must answer with a program or with errors, never crash: every error points
// into the text and says what it found and what it expected, at most one per line; every
// statement it accepts is within the language's ranges and reads back the same from its own text.
// The program then runs twice round (loops = 2) against an executor that fails its n-th call.
//
// Input: the script text (n is the text's length modulo 8; 0 never fails).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "fuzz_check.hpp"
#include "robotd/rbtscript/interpreter.hpp"
#include "robotd/rbtscript/parser.hpp"

namespace {

using namespace robotd::rbtscript;

std::vector<std::string_view> split_lines(std::string_view text) {
  std::vector<std::string_view> lines;
  for (std::size_t start = 0; start <= text.size();) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return lines;
}

bool percent_ok(const std::optional<double>& value) { return !value || (*value > 0 && *value <= 100); }
bool duration_ok(const std::optional<double>& value) { return !value || (std::isfinite(*value) && *value > 0); }
bool pose_ok(const Pose& p) {
  return std::isfinite(p.x_mm) && std::isfinite(p.y_mm) && std::isfinite(p.z_mm) && std::isfinite(p.rx_deg) &&
         std::isfinite(p.ry_deg) && std::isfinite(p.rz_deg);
}

void check_ranges(const StatementKind& kind) {
  std::visit(
      [](const auto& s) {
        using S = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<S, MoveJoint>) {
          FUZZ_CHECK(!s.joints_deg.empty() && s.joints_deg.size() <= kMaxJointValues);
          for (const double q : s.joints_deg) FUZZ_CHECK(std::isfinite(q));
          FUZZ_CHECK(percent_ok(s.motion.speed_percent) && percent_ok(s.motion.acceleration_percent));
          FUZZ_CHECK(duration_ok(s.motion.duration_s));
        } else if constexpr (std::is_same_v<S, MovePose>) {
          FUZZ_CHECK(pose_ok(s.pose));
          FUZZ_CHECK(percent_ok(s.motion.speed_percent) && percent_ok(s.motion.acceleration_percent));
          FUZZ_CHECK(duration_ok(s.motion.duration_s));
        } else if constexpr (std::is_same_v<S, MoveCart>) {
          FUZZ_CHECK(pose_ok(s.pose) && duration_ok(s.motion.duration_s));
        } else if constexpr (std::is_same_v<S, MoveCartRelTrf>) {
          FUZZ_CHECK(pose_ok(s.delta) && duration_ok(s.motion.duration_s));
        } else if constexpr (std::is_same_v<S, Delay>) {
          FUZZ_CHECK(std::isfinite(s.seconds) && s.seconds >= 0);
        } else if constexpr (std::is_same_v<S, Output>) {
          FUZZ_CHECK(s.number >= 1);
        } else if constexpr (std::is_same_v<S, Gripper>) {
          FUZZ_CHECK(s.position >= 0 && s.position <= 255 && s.speed >= 0 && s.speed <= 255);
          FUZZ_CHECK(s.current_ma >= 0 && s.current_ma <= 1300);
        }
      },
      kind);
}

/// Succeeds on every call but the n-th (counting from 1; 0: never fails).
class FailingExecutor final : public Executor {
 public:
  explicit FailingExecutor(std::size_t fail_at) : fail_at_(fail_at) {}
  robotd::Result<void> move_joint(const MoveJoint&) override { return call(); }
  robotd::Result<void> move_pose(const MovePose&) override { return call(); }
  robotd::Result<void> move_cart(const MoveCart&) override { return call(); }
  robotd::Result<void> move_cart_rel_trf(const MoveCartRelTrf&) override { return call(); }
  robotd::Result<void> delay(const Delay&) override { return call(); }
  robotd::Result<void> output(const Output&) override { return call(); }
  robotd::Result<void> gripper_calibrate(const GripperCalibrate&) override { return call(); }
  robotd::Result<void> gripper(const Gripper&) override { return call(); }

 private:
  robotd::Result<void> call() {
    if (++calls_ == fail_at_) return robotd::make_error(robotd::ErrorCode::kRefused, "fuzz failure");
    return {};
  }
  std::size_t fail_at_;
  std::size_t calls_ = 0;
};

void check_errors(const std::vector<ParseError>& errors, const std::vector<std::string_view>& lines) {
  std::size_t previous_line = 0;
  for (const auto& error : errors) {
    FUZZ_CHECK(error.location.line > previous_line && error.location.line <= lines.size());
    FUZZ_CHECK(error.location.column >= 1 && error.location.column <= lines[error.location.line - 1].size() + 1);
    FUZZ_CHECK(!error.found.empty() && !error.expected.empty());
    previous_line = error.location.line;
  }
}

void check_program(const Program& program, const std::vector<std::string_view>& lines) {
  for (const auto& statement : program.statements) {
    FUZZ_CHECK(statement.location.line >= 1 && statement.location.line <= lines.size());
    const std::string_view line = lines[statement.location.line - 1];
    FUZZ_CHECK(statement.location.column >= 1 && statement.location.column <= line.size());
    FUZZ_CHECK(line.substr(statement.location.column - 1, statement.text.size()) == statement.text);
    check_ranges(statement.kind);
    const auto again = parse_program(statement.text);
    FUZZ_CHECK(again.program && again.program->statements.size() == 1);
    FUZZ_CHECK(again.program->statements[0].kind == statement.kind);
  }
}

void check_run(const Program& program, std::size_t fail_at) {
  FailingExecutor executor(fail_at);
  RunOptions options;
  options.loops = 2;
  const auto outcome = run_program(program, executor, options);
  FUZZ_CHECK(outcome.statements_run <= 2 * program.statements.size());
  FUZZ_CHECK(outcome.passes <= 2);
  FUZZ_CHECK(outcome.end != RunEnd::kStopped);
  FUZZ_CHECK(outcome.error.has_value() == (outcome.end == RunEnd::kFailed));
  if (outcome.error) {
    FUZZ_CHECK(outcome.error->index < program.statements.size());
    const auto& failed = program.statements[outcome.error->index];
    FUZZ_CHECK(outcome.error->location == failed.location && outcome.error->text == failed.text);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const auto lines = split_lines(text);
  const auto result = parse_program(text);
  FUZZ_CHECK(result.program.has_value() == result.errors.empty());
  check_errors(result.errors, lines);
  if (!result.program) return 0;
  check_program(*result.program, lines);
  check_run(*result.program, size % 8);
  return 0;
}
