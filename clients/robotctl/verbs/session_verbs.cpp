// acquire and release: hold a control session from the shell, and end a session by its uuid.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <iostream>
#include <memory>
#include <string>

#include "cli_options.hpp"
#include "exit_status.hpp"
#include "message_text.hpp"
#include "text_format.hpp"
#include "verbs/verbs.hpp"

namespace robotctl {
namespace {

// Notices when robotd stops listing a session (by its public id: /session_status never shows a
// uuid): it was released with its uuid elsewhere, or it timed out.
class SessionPresence {
 public:
  SessionPresence(robotd::Client& client, std::string session_id, StopSignals& stop)
      : session_id_(std::move(session_id)) {
    subscription_ = client.on_session_status([this, &stop](const robotd::SessionStatus& status) {
      bool listed = false;
      for (const auto& session : status.sessions) listed = listed || session.uuid == session_id_;
      // A sample published before the grant does not list it yet; only a disappearance counts.
      if (listed) {
        seen_ = true;
      } else if (seen_ && !ended_.exchange(true)) {
        stop.wake();
      }
    });
  }
  SessionPresence(const SessionPresence&) = delete;
  SessionPresence& operator=(const SessionPresence&) = delete;
  ~SessionPresence() = default;

  bool ended() const { return ended_; }

 private:
  std::string session_id_;
  std::atomic<bool> seen_{false};
  std::atomic<bool> ended_{false};
  robotd::Subscription subscription_;  // last: its callbacks stop before the members they use go
};

struct AcquireOptions {
  robotd::SessionRequest request;
  int timeout_ms = 1000;
};

std::string grant_text(const robotd::Session& session, const robotd::SessionRequest& request) {
  return "uuid " + session.uuid() + "  session " + session.session_id() + "  device " + session.device() + "  motors " +
         id_ranges(session.motor_ids()) + "  mode " + std::string(robotd::to_string(session.mode())) + "  on timeout " +
         behavior_text(request.on_timeout, session.applied_timeout_behavior()) + " after " +
         std::to_string(request.timeout.count()) + " ms";
}

int hold_session(VerbContext& context, const robotd::SessionRequest& request) {
  const robotd::ClientOptions& options = context.client.options();
  auto granted = context.client.request_control(request);
  if (!granted) return report_failure(granted.error(), options);
  robotd::Session& session = granted.value();
  SessionPresence presence(context.client, session.session_id(), context.stop);
  std::cout << grant_text(session, request) << std::endl;

  const auto keepalive_period = std::max(request.timeout / 4, std::chrono::milliseconds(1));
  std::cerr << "holding the session (keepalive every " << keepalive_period.count() << " ms); Ctrl-C releases it with "
            << robotd::to_string(request.on_release) << std::endl;
  auto next_keepalive = std::chrono::steady_clock::now() + keepalive_period;
  while (true) {
    const StopSignals::Wake wake = context.stop.wait_until(next_keepalive);
    if (wake == StopSignals::Wake::kStopSignal) break;
    if (presence.ended()) {
      return report_failure("session " + session.session_id() +
                            " has ended: robotd no longer lists it (released with its uuid elsewhere, or timed out)");
    }
    if (wake == StopSignals::Wake::kDeadline) {
      if (auto sent = session.keepalive(); !sent) return report_failure(sent.error(), options);
      next_keepalive += keepalive_period;
    }
  }
  auto released = session.release(request.on_release);
  if (!released) return report_failure(released.error(), options);
  std::cout << released.value().message << std::endl;
  return kExitSuccess;
}

}  // namespace

Verb add_acquire_verb(CLI::App& app) {
  auto options = std::make_shared<AcquireOptions>();
  CLI::App* command =
      app.add_subcommand("acquire", "Take control of motors and hold it until Ctrl-C, then release them");
  command->add_option("DEVICE", options->request.device, "Device to control (see robotctl devices)")->required();
  add_motors_option(*command, options->request.motor_ids);
  add_control_mode_option(*command, options->request.mode);
  add_behavior_option(*command, "--on-timeout", options->request.on_timeout,
                      "What robotd does to the motors if robotctl stops sending keepalives");
  command->add_option("--timeout-ms", options->timeout_ms, "Session timeout in ms (keepalives go every quarter of it)")
      ->check(CLI::Range(10, 600'000))
      ->capture_default_str();
  add_behavior_option(*command, "--on-release", options->request.on_release,
                      "What robotd does to the motors when robotctl releases them on Ctrl-C");
  command->add_option("--policy", options->request.policy_name, "The policy that commands, shown in robotctl sessions");
  command->add_option("--policy-file", options->request.policy_file_name, "The file that policy was loaded from");
  command->footer(
      "Prints 'uuid <uuid>  session <id>' and what was granted on one line, then sends keepalives every quarter of "
      "the timeout. Nothing moves: use it to keep other clients off the motors. The uuid is the session's "
      "capability (it commands and releases the session) and is shown only here; robotctl sessions and robotd's "
      "log show the public id. Exits 1 if robotd ends the session (released with its uuid elsewhere, or timed "
      "out).\n\n"
      "Example:\n  robotctl acquire arm --motors 0,1,2 --on-timeout damping --timeout-ms 500\n"
      "  robotctl release UUID     # from another shell: ends it");
  return Verb{command, true, [options](VerbContext& context) {
                options->request.timeout = std::chrono::milliseconds(options->timeout_ms);
                return hold_session(context, options->request);
              }};
}

Verb add_release_verb(CLI::App& app) {
  struct ReleaseOptions {
    std::string uuid;
    robotd::Behavior mode = robotd::Behavior::kKeep;
  };
  auto options = std::make_shared<ReleaseOptions>();
  CLI::App* command = app.add_subcommand("release", "End a control session by its uuid");
  command->add_option("UUID", options->uuid, "The session's uuid, as request_control (or robotctl acquire) gave it")
      ->required();
  add_behavior_option(*command, "--mode", options->mode, "What robotd does to the motors as they are freed");
  command->footer(
      "The uuid is the session's capability: only whoever was granted the session knows it. robotctl sessions "
      "shows public ids, which release nothing. A session you do not hold cannot be released: it ends when its "
      "holder releases it or stops commanding it (its timeout), and robotctl estop stops its motors at once. "
      "The motors are freed with --mode.\n\n"
      "Example:\n  robotctl release 3f1c9a2e-7b40-4d6e-9c15-a8f2e0b7d341 --mode damping");
  return Verb{command, false, [options](VerbContext& context) {
                auto released = context.client.release_control(options->uuid, options->mode);
                if (!released) return report_failure(released.error(), context.client.options());
                std::cout << released.value().message << std::endl;
                return kExitSuccess;
              }};
}

}  // namespace robotctl
