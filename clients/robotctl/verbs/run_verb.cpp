// run: an RBTscript program (docs/rbtscript.md) on a device: parsed, checked as a whole (a dry
// run), then run statement by statement in a session, with the statement being run shown on
// stderr. Ctrl-C, an e-stop or a fault stops it with the arm held.
#include <atomic>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <thread>

#include "exit_status.hpp"
#include "robotd/rbtscript/device_runner.hpp"
#include "robotd/rbtscript/parser.hpp"
#include "text_format.hpp"
#include "verbs/verbs.hpp"

namespace robotctl {
namespace {

struct RunVerbOptions {
  std::string program_path;
  std::string device;
  bool dry_run = false;
  std::size_t loops = 0;  // 0: until stopped
};

// The program, or the exit status of what was wrong with it (printed).
std::optional<robotd::rbtscript::Program> load_program(const std::string& path, int& status) {
  std::ifstream file(path);
  if (!file) {
    status = report_usage_error("cannot read the program '" + path + "'");
    return std::nullopt;
  }
  std::stringstream text;
  text << file.rdbuf();
  robotd::rbtscript::ParseResult parsed = robotd::rbtscript::parse_program(text.str());
  if (parsed.program) return std::move(parsed.program);
  for (const robotd::rbtscript::ParseError& error : parsed.errors) std::cerr << path << ": " << error.message() << "\n";
  status = report_usage_error(std::to_string(parsed.errors.size()) + " syntax error(s) in '" + path +
                              "'; nothing was sent to robotd");
  return std::nullopt;
}

void print_outcome(const robotd::rbtscript::RunOutcome& outcome) {
  using robotd::rbtscript::RunEnd;
  switch (outcome.end) {
    case RunEnd::kEndOfProgram:
    case RunEnd::kEnd:
      std::cout << "program ended after " << outcome.statements_run << " statement(s)" << std::endl;
      break;
    case RunEnd::kLoopLimit:
      std::cout << "program ended after " << outcome.passes << " pass(es), " << outcome.statements_run
                << " statement(s)" << std::endl;
      break;
    case RunEnd::kStopped:
      std::cerr << "robotctl: program stopped; the arm holds where it was" << std::endl;
      break;
    case RunEnd::kFailed:
      std::cerr << "robotctl: program failed at " << outcome.error->to_string() << std::endl;
      break;
  }
}

int run(VerbContext& context, const RunVerbOptions& options) {
  int status = kExitSuccess;
  const auto program = load_program(options.program_path, status);
  if (!program) return status;

  std::atomic<bool> stop{false};
  robotd::rbtscript::DeviceRunOptions run_options;
  run_options.device = options.device;
  run_options.dry_run = options.dry_run;
  if (options.loops > 0) run_options.loops = options.loops;
  run_options.stop = &stop;
  run_options.on_statement = [](const robotd::rbtscript::Progress& at) {
    std::cerr << "[pass " << at.pass << ", line " << at.location.line << "] " << at.text << std::endl;
  };

  // The program runs on a thread of its own; this one waits for it or for Ctrl-C.
  std::optional<robotd::Result<robotd::rbtscript::DeviceRunReport>> result;
  std::thread runner([&] {
    result.emplace(robotd::rbtscript::run_on_device(context.client, *program, run_options));
    context.stop.wake();
  });
  if (context.stop.wait_for_wake() == StopSignals::Wake::kStopSignal) stop = true;
  runner.join();

  if (!result->ok()) return report_failure(result->error(), context.client.options());
  const robotd::rbtscript::DeviceRunReport& report = result->value();
  for (const robotd::rbtscript::RunError& problem : report.problems) {
    std::cerr << options.program_path << ": " << problem.to_string() << "\n";
  }
  if (!report.problems.empty()) {
    return report_failure(std::to_string(report.problems.size()) + " problem(s) for device '" + report.device +
                          "'; nothing was sent to it");
  }
  if (!report.outcome) {
    std::cout << options.program_path << ": " << report.moves_planned << " move(s) planned on '" << report.device
              << "', " << fixed(report.pass_seconds, 2) << " s per pass; no problems" << std::endl;
    return kExitSuccess;
  }
  print_outcome(*report.outcome);
  switch (report.outcome->end) {
    case robotd::rbtscript::RunEnd::kStopped:
      return context.stop.received_signal() != 0 ? exit_status_for_signal(context.stop.received_signal())
                                                 : kExitFailure;
    case robotd::rbtscript::RunEnd::kFailed:
      return kExitFailure;
    default:
      return kExitSuccess;
  }
}

}  // namespace

Verb add_run_verb(CLI::App& app) {
  auto options = std::make_shared<RunVerbOptions>();
  CLI::App* command =
      app.add_subcommand("run", "Run an RBTscript program (MoveJoint, MoveCart, Delay, ...) on a device");
  command->add_option("PROGRAM", options->program_path, "The program file (.rbt)")->required();
  command->add_option("--device", options->device, "The device to run it on (default: robotd's only device)");
  command->add_flag("--dry-run", options->dry_run,
                    "Check every statement against the device (limits, reachability, its I/O) and move nothing");
  command->add_option("--loops", options->loops, "Passes through Loop() at most (default: until stopped)")
      ->check(CLI::Range(std::size_t{1}, std::size_t{1'000'000}));
  command->footer(
      "Parses the whole program (syntax errors name line and column), plans every move from where the one before "
      "it ends on the device's limits and arm model, and lists every problem with its line; only a program without "
      "problems runs. Each statement is shown on stderr as it starts. Ctrl-C, an e-stop or a fault stops the "
      "program with the arm held. Exits 0 when the program ended, 1 on a problem or failure, 2 on a syntax error, "
      "130 on Ctrl-C.\n\n"
      "Example:\n  robotctl run pick.rbt --device arm --dry-run\n  robotctl run pick.rbt --device arm --loops 3");
  return Verb{command, true, [options](VerbContext& context) { return run(context, *options); }};
}

}  // namespace robotctl
