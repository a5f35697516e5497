// Planned moves on a session: the C face of robotd/motion/session_moves.hpp.
#include <cmath>
#include <string>
#include <string_view>

#include "arguments.hpp"
#include "conversions.hpp"
#include "errors.hpp"
#include "handles.hpp"
#include "robotd/motion/session_moves.hpp"
#include "stop_flag.hpp"

using robotd::c::array_argument;
using robotd::c::client_handle;
using robotd::c::copy_text;
using robotd::c::fail;
using robotd::c::guarded;
using robotd::c::require;
using robotd::c::require_joint_count;
using robotd::c::session_handle;
using robotd::c::StopFlagWatch;
using robotd::c::take;

namespace {

// 0 = not given; else within (0, most].
std::optional<double> optional_amount(double value, std::string_view name, std::string_view unit, double most) {
  if (value == 0) return std::nullopt;
  if (!std::isfinite(value) || value < 0 || value > most) {
    fail(ROBOTD_INVALID_ARGUMENT, std::string(name) + " is " + std::to_string(value) + ": expected 0 (not given) or " +
                                      (std::isfinite(most) ? "up to " + std::to_string(most) + " " : "more than 0 ") +
                                      std::string(unit));
  }
  return value;
}

robotd::motion::MoveTiming timing_argument(const robotd_move_options& options) {
  robotd::motion::MoveTiming timing;
  timing.duration_s = optional_amount(options.duration_s, "options->duration_s", "s", INFINITY);
  timing.speed_percent = optional_amount(options.speed_percent, "options->speed_percent", "%", 100);
  timing.acceleration_percent =
      optional_amount(options.acceleration_percent, "options->acceleration_percent", "%", 100);
  switch (options.shape) {
    case ROBOTD_SHAPE_DEFAULT:
      break;
    case ROBOTD_SHAPE_POLYNOMIAL:
      timing.shape = robotd::motion::Shape::kPolynomial;
      break;
    case ROBOTD_SHAPE_TRAPEZOID:
      timing.shape = robotd::motion::Shape::kTrapezoid;
      break;
    default:
      fail(ROBOTD_INVALID_ARGUMENT,
           "options->shape is " + std::to_string(static_cast<int>(options.shape)) +
               ": expected ROBOTD_SHAPE_DEFAULT, ROBOTD_SHAPE_POLYNOMIAL or ROBOTD_SHAPE_TRAPEZOID");
  }
  return timing;
}

robotd::motion::CartesianPath path_argument(robotd_cartesian_path path) {
  switch (path) {
    case ROBOTD_PATH_JOINT:
      return robotd::motion::CartesianPath::kJoint;
    case ROBOTD_PATH_LINE:
      return robotd::motion::CartesianPath::kLine;
    default:
      fail(ROBOTD_INVALID_ARGUMENT,
           "path is " + std::to_string(static_cast<int>(path)) + ": expected ROBOTD_PATH_JOINT or ROBOTD_PATH_LINE");
  }
}

const robotd_move_options& options_or_defaults(const robotd_move_options* options, robotd_move_options& defaults) {
  if (options != nullptr) return *options;
  (void)robotd_move_options_init(&defaults);
  return defaults;
}

void to_c(const robotd::motion::StreamReport& report, robotd_move_report& out) {
  out = robotd_move_report{};
  out.stopped = report.end == robotd::motion::StreamEnd::kStopped;
  out.commands_sent = report.commands_sent;
  out.fraction_done = report.fraction_done;
  out.joint_count = std::min<std::size_t>(report.last_measured_rad.size(), ROBOTD_MAX_JOINTS);
  std::copy_n(report.last_measured_rad.begin(), out.joint_count, out.last_measured);
  copy_text(report.summary, out.summary);
}

}  // namespace

extern "C" {

robotd_status robotd_move_options_init(robotd_move_options* options) {
  return guarded("robotd_move_options_init",
                 [&] { require(options, "options", "a robotd_move_options to fill") = robotd_move_options{}; });
}

robotd_status robotd_session_move_joints(robotd_client* client, robotd_session* session, const double* target_rad,
                                         size_t count, const robotd_move_options* options, robotd_move_report* report) {
  return guarded("robotd_session_move_joints", [&] {
    auto& client_ref = client_handle(client);
    auto& handle = session_handle(session);
    require_joint_count(count, "count");
    require(target_rad, "target_rad", "count joint positions in rad, one per joint of the device");
    robotd_move_options defaults;
    const robotd_move_options& given = options_or_defaults(options, defaults);
    const robotd::motion::MoveTiming timing = timing_argument(given);
    const StopFlagWatch stop(given.stop);
    const auto moved = take(robotd::motion::move_joints(*client_ref.client, handle.session,
                                                        array_argument(target_rad, count), timing, stop.flag()));
    if (report != nullptr) to_c(moved, *report);
  });
}

robotd_status robotd_session_move_cartesian(robotd_client* client, robotd_session* session, const robotd_pose* goal,
                                            robotd_cartesian_path path, const robotd_move_options* options,
                                            robotd_move_report* report) {
  return guarded("robotd_session_move_cartesian", [&] {
    auto& client_ref = client_handle(client);
    auto& handle = session_handle(session);
    const auto& pose = require(goal, "goal", "a robotd_pose: the tool's position (m) and angles (rad)");
    const robotd::motion::CartesianPath converted_path = path_argument(path);
    robotd_move_options defaults;
    const robotd_move_options& given = options_or_defaults(options, defaults);
    const robotd::motion::MoveTiming timing = timing_argument(given);
    robotd::kinematics::EulerPose euler;
    for (std::size_t i = 0; i < 3; ++i) {
      if (!std::isfinite(pose.position_m[i]) || !std::isfinite(pose.angles_rad[i])) {
        fail(ROBOTD_INVALID_ARGUMENT, "goal has a value that is not a finite number: expected m and rad");
      }
      euler.position_m[i] = pose.position_m[i];
      euler.angles_rad[i] = pose.angles_rad[i];
    }
    const StopFlagWatch stop(given.stop);
    const auto moved = take(
        robotd::motion::move_cartesian(*client_ref.client, handle.session, euler, timing, converted_path, stop.flag()));
    if (report != nullptr) to_c(moved, *report);
  });
}

}  // extern "C"
