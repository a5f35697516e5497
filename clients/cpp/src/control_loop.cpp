// Session::run_control_loop: the tick → law → answer loop on the calling thread.
#include <string>

#include "robotd/client/session.hpp"

namespace robotd {
namespace {

bool stop_requested(const ControlLoopOptions& options) {
  return options.stop != nullptr && options.stop->load(std::memory_order_relaxed);
}

std::string seen_text(const ControlLoopReport& report) {
  return " (after " + std::to_string(report.ticks_seen) + " tick(s) seen, the last " +
         std::to_string(report.last_tick) + "; " + std::to_string(report.ticks_answered) + " answered)";
}

}  // namespace

Result<ControlLoopReport> Session::run_control_loop(const ControlLaw& law, const ControlLoopOptions& options) {
  if (!law) return make_error(ErrorCode::kInvalidArgument, "the control law is empty: expected a callable");
  if (options.state_timeout.count() <= 0 || options.duration.count() < 0) {
    return make_error(ErrorCode::kInvalidArgument, "state_timeout is " + std::to_string(options.state_timeout.count()) +
                                                       " ms and duration " + std::to_string(options.duration.count()) +
                                                       " ms: expected state_timeout > 0, duration >= 0");
  }
  ControlLoopReport report;
  const auto start = std::chrono::steady_clock::now();
  const auto out_of_time = [&] {
    return options.duration.count() > 0 && std::chrono::steady_clock::now() - start >= options.duration;
  };
  while (!stop_requested(options) && !out_of_time()) {
    auto state = next_tick(options.state_timeout);
    if (!state) return make_error(state.error().code, state.error().message + seen_text(report));
    const std::uint64_t tick = state.value().tick;
    if (report.ticks_seen == 0) {
      report.first_tick = tick;
    } else {
      report.ticks_skipped += tick - report.last_tick - 1;  // next_tick returns newer ticks only
    }
    report.last_tick = tick;
    ++report.ticks_seen;

    const Command command = law(state.value());
    if (auto sent = answer(state.value(), command); !sent) {
      return make_error(sent.error().code, sent.error().message + seen_text(report));
    }
    ++report.ticks_answered;
    if (command.finished) {
      report.finished = true;
      break;
    }
  }
  return report;
}

}  // namespace robotd
