// move: take the motors, stream a smooth trajectory to a target, wait until the joints arrive,
// release them.
#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>

#include "cli_options.hpp"
#include "device_lookup.hpp"
#include "exit_status.hpp"
#include "joint_position_watch.hpp"
#include "session_motion.hpp"
#include "text_format.hpp"
#include "trajectory.hpp"
#include "verbs/verbs.hpp"

namespace robotctl {
namespace {

struct MoveOptions {
  std::string device;
  std::vector<double> target_rad;
  std::vector<std::int32_t> motor_ids;  // empty = every motor
  double speed_rad_s = 0.5;
  double rate_hz = 100;
  double tolerance_rad = 0.02;
  int settle_ms = 2000;
  robotd::Behavior on_timeout = robotd::Behavior::kDamping;
  robotd::Behavior release_mode = robotd::Behavior::kKeep;
};

// What is wrong with moving `motor_ids` of `device` to `target_rad`, or "" when nothing is.
std::string target_problem(const robotd::DeviceInfo& device, const std::vector<std::int32_t>& motor_ids,
                           const std::vector<double>& target_rad) {
  if (target_rad.size() != motor_ids.size()) {
    return "--to has " + std::to_string(target_rad.size()) + " value(s) for " + std::to_string(motor_ids.size()) +
           " motor(s) of '" + device.name + "'; give one target in rad per motor, in --motors order";
  }
  const std::size_t joints = device.joint_names.size();
  for (std::size_t i = 0; i < motor_ids.size(); ++i) {
    const auto id = static_cast<std::size_t>(motor_ids[i]);
    if (id >= joints) {
      return "motor id " + std::to_string(id) + " does not exist on '" + device.name + "' (valid: 0.." +
             std::to_string(joints - 1) + ")";
    }
    if (id < device.position_min.size() && id < device.position_max.size() &&
        (target_rad[i] < device.position_min[id] || target_rad[i] > device.position_max[id])) {
      return "target " + fixed(target_rad[i], 3) + " rad for motor " + std::to_string(id) + " (" +
             device.joint_names[id] + ") is outside its limits " + fixed(device.position_min[id], 3) + ".." +
             fixed(device.position_max[id], 3) + " rad";
    }
  }
  return "";
}

std::string not_arrived_text(const robotd::DeviceInfo& device, const std::vector<std::int32_t>& motor_ids,
                             const std::vector<double>& actual, const std::vector<double>& target,
                             const MoveOptions& options) {
  std::string joints;
  for (std::size_t i = 0; i < motor_ids.size(); ++i) {
    const double error = std::fabs(actual[i] - target[i]);
    if (error <= options.tolerance_rad) continue;
    joints += std::string(joints.empty() ? "" : "; ") + device.joint_names[static_cast<std::size_t>(motor_ids[i])] +
              " at " + fixed(actual[i], 4) + " rad (target " + fixed(target[i], 4) + ", off by " + fixed(error, 4) +
              ")";
  }
  return "did not arrive within " + std::to_string(options.settle_ms) + " ms after the trajectory ended: " + joints +
         " (tolerance " + fixed(options.tolerance_rad, 4) + " rad; robotctl status shows any rejected commands)";
}

int move(VerbContext& context, const MoveOptions& options) {
  const robotd::ClientOptions& client_options = context.client.options();
  auto device = find_device(context.client, options.device);
  if (!device) return report_failure(device.error(), client_options);
  const std::vector<std::int32_t> motor_ids =
      options.motor_ids.empty() ? every_motor(device.value()) : options.motor_ids;
  if (const std::string problem = target_problem(device.value(), motor_ids, options.target_rad); !problem.empty()) {
    return report_usage_error(problem);
  }

  const auto tick_period =
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / options.rate_hz));
  JointPositionWatch watch(context.client, options.device);
  auto taken = take_position_session(context.client,
                                     {options.device, motor_ids, tick_period, options.on_timeout, options.release_mode},
                                     device.value().joint_names.size());
  if (!taken) return report_failure(taken.error(), client_options);
  robotd::Session& session = taken.value().session;
  const robotd::JointState& start = taken.value().start;

  const MinimumJerkMove plan(positions_of(start.position, motor_ids), options.target_rad, options.speed_rad_s);
  std::cerr << "moving " << motor_ids.size() << " joint(s) of '" << options.device << "' over "
            << fixed(plan.duration_s(), 2) << " s at up to " << fixed(options.speed_rad_s, 2) << " rad/s" << std::endl;

  // Stream the trajectory at the command rate, then keep sending its target until the joints arrive.
  const MotionSettings settings{tick_period, options.tolerance_rad, std::chrono::milliseconds(options.settle_ms)};
  const MotionResult motion =
      stream_move(session, context.stop, watch, start.position, plan, options.target_rad, settings);
  switch (motion.end) {
    case MotionResult::End::kArrived:
      std::cout << "arrived in " << fixed(motion.elapsed_s, 2) << " s, max error "
                << fixed(max_error_rad(motion.actual_rad, options.target_rad), 4) << " rad" << std::endl;
      break;
    case MotionResult::End::kNotArrived:
      report_failure(not_arrived_text(device.value(), motor_ids, motion.actual_rad, options.target_rad, options));
      (void)session.release(options.release_mode);
      return kExitFailure;
    case MotionResult::End::kStopSignal: {
      auto released = session.release(options.release_mode);
      std::cerr << "robotctl: interrupted; " << (released ? released.value().message : released.error().message)
                << std::endl;
      return exit_status_for_signal(context.stop.received_signal());
    }
    case MotionResult::End::kFailed:
      return report_failure(motion.error, client_options);
  }
  auto released = session.release(options.release_mode);
  if (!released) return report_failure(released.error(), client_options);
  return kExitSuccess;
}

}  // namespace

Verb add_move_verb(CLI::App& app) {
  auto options = std::make_shared<MoveOptions>();
  CLI::App* command =
      app.add_subcommand("move", "Move joints smoothly to target positions, wait until they arrive, release them");
  command->add_option("DEVICE", options->device, "Device to move")->required();
  command->add_option("--to", options->target_rad, "Target positions in rad, one per motor, comma-separated")
      ->required()
      ->delimiter(',')
      ->allow_extra_args(false);
  add_motors_option(*command, options->motor_ids);
  command->add_option("--speed", options->speed_rad_s, "Peak joint speed in rad/s")
      ->check(CLI::Range(0.001, 100.0))
      ->capture_default_str();
  command->add_option("--rate", options->rate_hz, "Command rate in Hz (robotd interpolates up to its loop rate)")
      ->check(CLI::Range(1.0, 1000.0))
      ->capture_default_str();
  command->add_option("--tolerance", options->tolerance_rad, "How close, in rad, counts as arrived")
      ->check(CLI::Range(1e-6, 10.0))
      ->capture_default_str();
  command->add_option("--settle-ms", options->settle_ms, "How long after the trajectory the joints may take to arrive")
      ->check(CLI::Range(0, 600'000))
      ->capture_default_str();
  add_behavior_option(*command, "--on-timeout", options->on_timeout,
                      "What robotd does to the motors if robotctl stops sending (it crashed or hung)");
  add_behavior_option(*command, "--release-mode", options->release_mode,
                      "What robotd does to the motors when robotctl releases them");
  command->footer(
      "Takes the motors, streams a minimum-jerk trajectory from where they are to --to (no joint faster than "
      "--speed), keeps sending the target until every joint is within --tolerance, then releases them. Exits 1 if "
      "a joint has not arrived --settle-ms after the trajectory ends, 130 on Ctrl-C; the motors are released either "
      "way.\n\n"
      "Example:\n  robotctl move arm --to 0.5,0,0,0,0,0\n  robotctl move arm --motors 0,1 --to=-0.3,0.4 --speed 1.0");
  return Verb{command, true, [options](VerbContext& context) { return move(context, *options); }};
}

}  // namespace robotctl
