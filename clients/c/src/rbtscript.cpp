// RBTscript programs on a device: the C face of robotd/rbtscript/device_runner.hpp, with the
// parser's syntax errors and the dry run's problems in one report.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "arguments.hpp"
#include "conversions.hpp"
#include "errors.hpp"
#include "handles.hpp"
#include "robotd/rbtscript/device_runner.hpp"
#include "robotd/rbtscript/parser.hpp"
#include "stop_flag.hpp"

using robotd::c::client_handle;
using robotd::c::copy_text;
using robotd::c::fail;
using robotd::c::guarded;
using robotd::c::require;
using robotd::c::StopFlagWatch;
using robotd::c::take;
using robotd::c::text_argument;
using robotd::c::timeout_argument;

namespace robotd::c {

// A problem with the strings that robotd_rbtscript_problem points into. Not in the anonymous
// namespace: robotd_rbtscript_report, which has external linkage, holds them.
struct RbtscriptProblem {
  robotd::rbtscript::SourceLocation location;
  std::string statement;
  std::string message;
  std::string description;
};

}  // namespace robotd::c

namespace {

using Problem = robotd::c::RbtscriptProblem;

Problem problem_of(const robotd::rbtscript::ParseError& error) {
  return {error.location, "", "found " + error.found + ", expected " + error.expected, error.message()};
}

Problem problem_of(const robotd::rbtscript::RunError& error) {
  return {error.location, error.text, error.message, error.to_string()};
}

robotd_rbtscript_problem to_c(const Problem& problem) {
  return {problem.location.line, problem.location.column, problem.statement.c_str(), problem.message.c_str(),
          problem.description.c_str()};
}

robotd_rbtscript_end to_c(robotd::rbtscript::RunEnd end) {
  using robotd::rbtscript::RunEnd;
  switch (end) {
    case RunEnd::kEndOfProgram:
      return ROBOTD_RBTSCRIPT_END_OF_PROGRAM;
    case RunEnd::kEnd:
      return ROBOTD_RBTSCRIPT_END;
    case RunEnd::kLoopLimit:
      return ROBOTD_RBTSCRIPT_LOOP_LIMIT;
    case RunEnd::kStopped:
      return ROBOTD_RBTSCRIPT_STOPPED;
    case RunEnd::kFailed:
      return ROBOTD_RBTSCRIPT_FAILED;
  }
  return ROBOTD_RBTSCRIPT_FAILED;
}

const robotd_rbtscript_options& options_or_defaults(const robotd_rbtscript_options* options,
                                                    robotd_rbtscript_options& defaults) {
  if (options != nullptr) return *options;
  (void)robotd_rbtscript_options_init(&defaults);
  return defaults;
}

}  // namespace

struct robotd_rbtscript_report {
  std::string device;
  bool syntax_errors = false;
  std::vector<robotd::c::RbtscriptProblem> problems;
  std::size_t moves_planned = 0;
  double pass_seconds = 0;
  robotd_rbtscript_end end = ROBOTD_RBTSCRIPT_NOT_RUN;
  std::uint64_t statements_run = 0;
  std::uint64_t passes = 0;
  std::optional<robotd::c::RbtscriptProblem> failure;
};

extern "C" {

robotd_status robotd_rbtscript_options_init(robotd_rbtscript_options* options) {
  return guarded("robotd_rbtscript_options_init", [&] {
    auto& out = require(options, "options", "a robotd_rbtscript_options to fill");
    out = robotd_rbtscript_options{};
    out.session_timeout_ms = static_cast<int32_t>(robotd::rbtscript::DeviceRunOptions{}.session_timeout.count());
  });
}

robotd_status robotd_run_rbtscript(robotd_client* client, const char* program_text,
                                   const robotd_rbtscript_options* options, robotd_rbtscript_report** report) {
  return guarded("robotd_run_rbtscript", [&] {
    auto& handle = client_handle(client);
    const std::string text(&require(program_text, "program_text", "the program, RBTscript text"));
    auto& out = require(report, "report", "a robotd_rbtscript_report* to store the report in");
    robotd_rbtscript_options defaults;
    const robotd_rbtscript_options& given = options_or_defaults(options, defaults);
    robotd::rbtscript::DeviceRunOptions run_options;
    run_options.device = text_argument(given.device, "options->device", ROBOTD_NAME_CAPACITY);
    run_options.dry_run = given.dry_run;
    if (given.loops > 0) run_options.loops = given.loops;
    run_options.session_timeout = timeout_argument(given.session_timeout_ms, "options->session_timeout_ms", false);
    if (given.on_statement != nullptr) {
      run_options.on_statement = [&given](const robotd::rbtscript::Progress& at) {
        given.on_statement(at.location.line, std::string(at.text).c_str(), at.pass, given.user_data);
      };
    }

    auto made = std::make_unique<robotd_rbtscript_report>();
    robotd::rbtscript::ParseResult parsed = robotd::rbtscript::parse_program(text);
    if (!parsed.program) {
      made->syntax_errors = true;
      for (const auto& error : parsed.errors) made->problems.push_back(problem_of(error));
    } else {
      const StopFlagWatch stop(given.stop);
      run_options.stop = stop.flag();
      const robotd::rbtscript::DeviceRunReport ran =
          take(robotd::rbtscript::run_on_device(*handle.client, *parsed.program, run_options));
      made->device = ran.device;
      for (const auto& problem : ran.problems) made->problems.push_back(problem_of(problem));
      made->moves_planned = ran.moves_planned;
      made->pass_seconds = ran.pass_seconds;
      if (ran.outcome) {
        made->end = to_c(ran.outcome->end);
        made->statements_run = ran.outcome->statements_run;
        made->passes = ran.outcome->passes;
        if (ran.outcome->error) made->failure = problem_of(*ran.outcome->error);
      }
    }
    out = made.release();
  });
}

robotd_status robotd_rbtscript_report_outcome(const robotd_rbtscript_report* report,
                                              robotd_rbtscript_outcome* outcome) {
  return guarded("robotd_rbtscript_report_outcome", [&] {
    const auto& stored = require(report, "report", "a report from robotd_run_rbtscript");
    auto& out = require(outcome, "outcome", "a robotd_rbtscript_outcome to fill");
    out = robotd_rbtscript_outcome{};
    copy_text(stored.device, out.device);
    out.syntax_errors = stored.syntax_errors;
    out.problem_count = stored.problems.size();
    out.moves_planned = stored.moves_planned;
    out.pass_seconds = stored.pass_seconds;
    out.end = stored.end;
    out.statements_run = stored.statements_run;
    out.passes = stored.passes;
    if (stored.failure) out.failure = to_c(*stored.failure);
  });
}

robotd_status robotd_rbtscript_report_problem(const robotd_rbtscript_report* report, size_t index,
                                              robotd_rbtscript_problem* problem) {
  return guarded("robotd_rbtscript_report_problem", [&] {
    const auto& stored = require(report, "report", "a report from robotd_run_rbtscript");
    auto& out = require(problem, "problem", "a robotd_rbtscript_problem to fill");
    if (index >= stored.problems.size()) {
      fail(ROBOTD_INVALID_ARGUMENT, "index is " + std::to_string(index) + ": the report has " +
                                        std::to_string(stored.problems.size()) + " problem(s)");
    }
    out = to_c(stored.problems[index]);
  });
}

void robotd_rbtscript_report_free(robotd_rbtscript_report* report) { delete report; }

}  // extern "C"
