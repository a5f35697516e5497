// Closed loop: tick states, answers, the control loop with a C law, aligned sends, SessionInfo.
#include <atomic>
#include <string>

#include "arguments.hpp"
#include "conversions.hpp"
#include "errors.hpp"
#include "handles.hpp"

using robotd::c::check;
using robotd::c::fail;
using robotd::c::guarded;
using robotd::c::require;
using robotd::c::session_handle;
using robotd::c::take;
using robotd::c::tick_of;
using robotd::c::timeout_argument;
using robotd::c::to_c;
using robotd::c::to_command;

namespace {

static_assert(ROBOTD_DEFAULT_SEND_LEAD_US == robotd::kDefaultSendLead.count(), "the C default is the C++ one");

robotd::ControlLoopOptions loop_options(const robotd_control_loop_options& options) {
  robotd::ControlLoopOptions converted;
  converted.duration = timeout_argument(options.duration_ms, "options->duration_ms", true);
  converted.state_timeout = timeout_argument(options.state_timeout_ms, "options->state_timeout_ms", false);
  return converted;
}

void to_c(const robotd::ControlLoopReport& report, robotd_control_loop_report& out) {
  out = robotd_control_loop_report{};
  out.ticks_seen = report.ticks_seen;
  out.ticks_answered = report.ticks_answered;
  out.ticks_skipped = report.ticks_skipped;
  out.first_tick = report.first_tick;
  out.last_tick = report.last_tick;
  out.finished = report.finished;
}

}  // namespace

extern "C" {

robotd_status robotd_session_next_tick(robotd_session* session, int32_t timeout_ms, robotd_tick_state* state) {
  return guarded("robotd_session_next_tick", [&] {
    auto& handle = session_handle(session);
    const auto timeout = timeout_argument(timeout_ms, "timeout_ms", true);
    auto& out = require(state, "state", "a robotd_tick_state to fill");
    to_c(take(handle.session.next_tick(timeout)), out);
  });
}

robotd_status robotd_session_answer(robotd_session* session, const robotd_tick_state* state,
                                    const robotd_command* command) {
  return guarded("robotd_session_answer", [&] {
    auto& handle = session_handle(session);
    const auto& tick = require(state, "state", "the robotd_tick_state to answer, from robotd_session_next_tick");
    const auto& values = require(command, "command", "a robotd_command");
    check(handle.session.answer(tick_of(tick), to_command(values, handle.session.motor_ids().size())));
  });
}

robotd_status robotd_control_loop_options_init(robotd_control_loop_options* options) {
  return guarded("robotd_control_loop_options_init", [&] {
    auto& out = require(options, "options", "a robotd_control_loop_options to fill");
    const robotd::ControlLoopOptions defaults;
    out = robotd_control_loop_options{};
    out.duration_ms = static_cast<int32_t>(defaults.duration.count());
    out.state_timeout_ms = static_cast<int32_t>(defaults.state_timeout.count());
  });
}

robotd_status robotd_session_run_control_loop(robotd_session* session, robotd_control_law law, void* user_data,
                                              const robotd_control_loop_options* options,
                                              robotd_control_loop_report* report) {
  return guarded("robotd_session_run_control_loop", [&] {
    auto& handle = session_handle(session);
    if (law == nullptr) fail(ROBOTD_INVALID_ARGUMENT, "law is NULL: expected a robotd_control_law");
    robotd_control_loop_options defaults{};
    if (options == nullptr) (void)robotd_control_loop_options_init(&defaults);
    const robotd_control_loop_options& given = options != nullptr ? *options : defaults;
    robotd::ControlLoopOptions converted = loop_options(given);
    // The C flag is read on this thread, after each answer (the C++ loop checks its own before each tick).
    std::atomic<bool> stop{given.stop != nullptr && *given.stop != 0};
    converted.stop = &stop;
    const std::size_t motors = handle.session.motor_ids().size();
    const auto c_law = [&](const robotd::TickState& state) {
      robotd_tick_state c_state;
      to_c(state, c_state);
      robotd_command c_command{};
      const int verdict = law(&c_state, &c_command, user_data);
      if (verdict != 0 && verdict != 1) {
        fail(ROBOTD_INVALID_ARGUMENT, "the law returned " + std::to_string(verdict) + " for tick " +
                                          std::to_string(state.tick) + ": expected 0 (go on) or 1 (finished)");
      }
      robotd::Command command = to_command(c_command, motors);
      command.finished = verdict == 1;
      if (given.stop != nullptr && *given.stop != 0) stop.store(true);
      return command;
    };
    const auto result = take(handle.session.run_control_loop(c_law, converted));
    if (report != nullptr) to_c(result, *report);
  });
}

robotd_status robotd_session_send_aligned(robotd_session* session, const robotd_command* command, int32_t lead_us) {
  return guarded("robotd_session_send_aligned", [&] {
    auto& handle = session_handle(session);
    const auto& values = require(command, "command", "a robotd_command");
    const auto lead = std::chrono::microseconds(lead_us < 0 ? ROBOTD_DEFAULT_SEND_LEAD_US : lead_us);
    check(handle.session.send_aligned(to_command(values, handle.session.motor_ids().size()), lead));
  });
}

robotd_status robotd_session_get_info(robotd_session* session, int32_t timeout_ms, robotd_session_info* info) {
  return guarded("robotd_session_get_info", [&] {
    auto& handle = session_handle(session);
    const auto timeout = timeout_argument(timeout_ms, "timeout_ms", true);
    auto& out = require(info, "info", "a robotd_session_info to fill");
    to_c(take(handle.session.info(timeout)), out);
  });
}

}  // extern "C"
