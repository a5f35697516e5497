// replay: stream a recording's position commands for one device back through a session, at
// the recorded pace scaled by --speed, after checking them against the device's current limits.
#include <algorithm>
#include <chrono>
#include <iostream>
#include <map>
#include <memory>

#include "cli_options.hpp"
#include "device_lookup.hpp"
#include "exit_status.hpp"
#include "joint_position_watch.hpp"
#include "recording/recording_reader.hpp"
#include "recording/replay_plan.hpp"
#include "replay_report.hpp"
#include "session_motion.hpp"
#include "text_format.hpp"
#include "trajectory.hpp"
#include "verbs/verbs.hpp"

namespace robotctl {
namespace {

// The approach and the final hold stream at this rate; the recording keeps its own pace.
constexpr auto kTickPeriod = std::chrono::milliseconds(10);
constexpr auto kSettle = std::chrono::milliseconds(2000);

struct ReplayOptions {
  std::string path;
  std::string device;
  std::vector<std::int32_t> motor_ids;  // empty = every motor the recording commands
  double speed = 1.0;
  bool dry_run = false;
  double approach_speed_rad_s = 0.5;
  double tolerance_rad = 0.02;
  robotd::Behavior on_timeout = robotd::Behavior::kDamping;
  robotd::Behavior release_mode = robotd::Behavior::kKeep;
};

// Where the replay is: the target of every motor (in the session's order) and the commands sent.
class ReplayProgress {
 public:
  ReplayProgress(const std::vector<std::int32_t>& motor_ids, const recording::ReplayPlan& plan)
      : motor_ids_(motor_ids) {
    for (std::size_t i = 0; i < plan.motor_ids.size(); ++i) targets_[plan.motor_ids[i]] = plan.start_rad[i];
  }
  void sent(const recording::ReplayStep& step) {
    for (std::size_t i = 0; i < step.motor_ids.size(); ++i) targets_[step.motor_ids[i]] = step.positions[i];
    ++commands_;
  }
  std::vector<double> targets_rad() const {
    std::vector<double> targets;
    targets.reserve(motor_ids_.size());
    for (const std::int32_t id : motor_ids_) targets.push_back(targets_.at(id));
    return targets;
  }
  std::size_t commands() const { return commands_; }

 private:
  std::vector<std::int32_t> motor_ids_;
  std::map<std::int32_t, double> targets_;
  std::size_t commands_ = 0;
};

Clock::duration scaled(std::int64_t recorded_ns, double speed) {
  return std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double, std::nano>(static_cast<double>(recorded_ns) / speed));
}

int interrupted(robotd::Session& session, const ReplayOptions& options, StopSignals& stop, const std::string& when) {
  auto released = session.release(options.release_mode);
  std::cerr << "robotctl: interrupted " << when << "; "
            << (released ? released.value().message : released.error().message) << std::endl;
  return exit_status_for_signal(stop.received_signal());
}

enum class StreamEnd { kDone, kStopSignal };

// Sends each step when its time on the pace clock (scaled) comes, and keepalives through the gaps.
robotd::Result<StreamEnd> stream_steps(robotd::Session& session, StopSignals& stop, const recording::ReplayPlan& plan,
                                       double speed, ReplayProgress& progress) {
  const auto keepalive_period = session_timeout(kTickPeriod) / 4;
  const auto start = Clock::now();
  auto last_sent = start;
  for (const auto& step : plan.steps) {
    const auto due = start + scaled(step.pace_ns, speed);
    while (Clock::now() < due) {
      const auto keepalive_at = last_sent + keepalive_period;
      if (stop.wait_until(std::min(due, keepalive_at)) == StopSignals::Wake::kStopSignal) {
        return StreamEnd::kStopSignal;
      }
      if (Clock::now() >= keepalive_at && Clock::now() < due) {
        if (auto sent = session.keepalive(); !sent) return sent.error();
        last_sent = Clock::now();
      }
    }
    if (auto sent = session.command(robotd::Command{step.motor_ids, step.positions, {}, {}, {}, {}}); !sent) {
      return sent.error();
    }
    last_sent = Clock::now();
    progress.sent(step);
  }
  return StreamEnd::kDone;
}

int play(VerbContext& context, const ReplayOptions& options, const recording::ReplayPlan& plan,
         const robotd::DeviceInfo& device) {
  const robotd::ClientOptions& client_options = context.client.options();
  JointPositionWatch watch(context.client, options.device);
  auto taken = take_position_session(
      context.client, {options.device, plan.motor_ids, kTickPeriod, options.on_timeout, options.release_mode},
      device.joint_names.size());
  if (!taken) return report_failure(taken.error(), client_options);
  robotd::Session& session = taken.value().session;
  const robotd::JointState& start = taken.value().start;

  ReplayProgress progress(session.motor_ids(), plan);
  const MotionSettings settings{kTickPeriod, options.tolerance_rad, kSettle};
  const std::vector<double> first_rad = progress.targets_rad();
  const MinimumJerkMove approach(positions_of(start.position, session.motor_ids()), first_rad,
                                 options.approach_speed_rad_s);
  std::cerr << "moving to the recording's first positions over " << fixed(approach.duration_s(), 2) << " s"
            << std::endl;
  const MotionResult approached =
      stream_move(session, context.stop, watch, start.position, approach, first_rad, settings);
  if (approached.end == MotionResult::End::kStopSignal) {
    return interrupted(session, options, context.stop, "before the replay");
  }
  if (approached.end != MotionResult::End::kArrived) {
    (void)session.release(options.release_mode);
    return approached.end == MotionResult::End::kFailed
               ? report_failure(approached.error, client_options)
               : report_failure("did not reach the recording's first positions within " +
                                std::to_string(kSettle.count()) + " ms (max error " +
                                fixed(max_error_rad(approached.actual_rad, first_rad), 4) + " rad, tolerance " +
                                fixed(options.tolerance_rad, 4) + " rad); nothing was replayed");
  }

  std::cerr << "replaying " << plan.steps.size() << " commands at speed " << fixed(options.speed, 2) << std::endl;
  const auto replay_start = Clock::now();
  const auto streamed = stream_steps(session, context.stop, plan, options.speed, progress);
  if (!streamed) return report_failure(streamed.error(), client_options);
  if (streamed.value() == StreamEnd::kStopSignal) {
    return interrupted(
        session, options, context.stop,
        "after " + std::to_string(progress.commands()) + " of " + std::to_string(plan.steps.size()) + " commands");
  }
  const double replay_s = std::chrono::duration<double>(Clock::now() - replay_start).count();

  // Hold the last positions until the joints are there: what the recording ended with.
  const std::vector<double> last_rad = progress.targets_rad();
  const MotionResult held = stream_move(session, context.stop, watch, start.position,
                                        MinimumJerkMove(last_rad, last_rad, 1.0), last_rad, settings);
  if (held.end == MotionResult::End::kStopSignal) return interrupted(session, options, context.stop, "at the end");
  if (held.end == MotionResult::End::kFailed) return report_failure(held.error, client_options);
  auto released = session.release(options.release_mode);
  if (!released) return report_failure(released.error(), client_options);
  const double error_rad = max_error_rad(held.actual_rad, last_rad);
  if (held.end == MotionResult::End::kNotArrived) {
    return report_failure("replayed " + std::to_string(progress.commands()) + " commands, but the joints were " +
                          fixed(error_rad, 4) + " rad from the last positions " + std::to_string(kSettle.count()) +
                          " ms later (tolerance " + fixed(options.tolerance_rad, 4) +
                          " rad; robotctl status shows any rejected commands)");
  }
  std::cout << "replayed " << progress.commands() << " commands in " << fixed(replay_s, 2)
            << " s, max error at the end " << fixed(error_rad, 4) << " rad" << std::endl;
  return kExitSuccess;
}

int replay(VerbContext& context, const ReplayOptions& options) {
  auto reader = recording::RecordingReader::open(options.path);
  if (!reader) return report_failure(reader.error().message);
  auto plan = recording::read_replay_plan(reader.value(), options.device, options.motor_ids);
  if (!plan) return report_failure(plan.error().message);
  if (!plan.value().ending.empty()) std::cerr << "robotctl: note: " << plan.value().ending << std::endl;
  auto device = find_device(context.client, options.device);
  if (!device) return report_failure(device.error(), context.client.options());

  const recording::ReplayCheck check = recording::check_replay(plan.value(), device.value(), options.speed);
  std::cout << replay_report(options.path, reader.value().description(), plan.value(), check, options.device,
                             options.speed)
            << std::flush;
  if (!check.violations.empty()) {
    return report_failure("replay refused: " + std::to_string(check.violations.size()) +
                          " violation(s) of the current limits of '" + options.device +
                          "' (listed above); nothing moved. Expected every command within position_min..position_max "
                          "and velocity_max at --speed " +
                          fixed(options.speed, 2));
  }
  if (options.dry_run) return kExitSuccess;
  return play(context, options, plan.value(), device.value());
}

}  // namespace

Verb add_replay_verb(CLI::App& app) {
  auto options = std::make_shared<ReplayOptions>();
  CLI::App* command = app.add_subcommand(
      "replay", "Replay a recording's position commands for a device, at the recorded pace, after checking limits");
  command->add_option("FILE", options->path, "A recording made by robotctl record")->required();
  command->add_option("--device", options->device, "The device whose recorded commands to replay")->required();
  add_motors_option(*command, options->motor_ids)
      ->description("Replay only these motors (default: every motor the recording commands)");
  command->add_option("--speed", options->speed, "Pace: 2 replays twice as fast, 0.5 at half speed")
      ->check(CLI::Range(0.01, 10.0))
      ->capture_default_str();
  command->add_flag("--dry-run", options->dry_run, "Check the recording against the limits, print the report, stop");
  command
      ->add_option("--approach-speed", options->approach_speed_rad_s,
                   "Peak joint speed in rad/s of the move to the recording's first positions")
      ->check(CLI::Range(0.001, 100.0))
      ->capture_default_str();
  command->add_option("--tolerance", options->tolerance_rad, "How close, in rad, counts as arrived (start and end)")
      ->check(CLI::Range(1e-6, 10.0))
      ->capture_default_str();
  add_behavior_option(*command, "--on-timeout", options->on_timeout,
                      "What robotd does to the motors if robotctl stops sending (it crashed or hung)");
  add_behavior_option(*command, "--release-mode", options->release_mode,
                      "What robotd does to the motors when robotctl releases them (at the end, or on Ctrl-C)");
  command->footer(
      "Checks first, against the device's current limits from robotd: its joint count and names, that each motor "
      "exists, every recorded position within position_min..position_max and every velocity (at --speed) within "
      "velocity_max. Any violation refuses the replay, listing each with joint, recorded time, value and limit. "
      "Then takes the motors, moves smoothly to the recording's first positions, streams the recorded commands at "
      "their recorded times divided by --speed (keepalives through gaps), holds the last positions until the "
      "joints arrive and releases them. Replays position commands only: a recording with torque or mixed "
      "commands for the device is refused. Ctrl-C releases the motors with --release-mode and exits 130.\n\n"
      "Example:\n  robotctl replay run.rdrec --device arm --dry-run\n"
      "  robotctl replay run.rdrec --device arm --speed 0.5");
  return Verb{command, true, [options](VerbContext& context) { return replay(context, *options); }};
}

}  // namespace robotctl
