#include "robotd/motion/trajectory_streamer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "device_watch.hpp"

namespace robotd::motion {

using namespace std::chrono_literals;

namespace {

std::string fixed(double value, int decimals) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

std::vector<float> as_floats(const std::vector<double>& values) {
  std::vector<float> out(values.size());
  std::transform(values.begin(), values.end(), out.begin(), [](double v) { return static_cast<float>(v); });
  return out;
}

// "42 % (0.84 of 2.00 s)"
std::string progress_text(double fraction, double duration_s) {
  return fixed(100.0 * fraction, 0) + " % (" + fixed(fraction * duration_s, 2) + " of " + fixed(duration_s, 2) + " s)";
}

// "ESTOP (e-stop engaged by 'teleop')": the state, and robotd's text when it says more.
std::string state_description(DeviceState state, const std::string& text) {
  std::string name(to_string(state));
  if (text.empty() || text == name) return name;
  if (text.rfind(name, 0) == 0) return text;  // robotd's text often starts with the state
  return name + " (" + text + ")";
}

// The joint farthest from `target`: its index and distance.
std::pair<std::size_t, double> farthest(const std::vector<double>& actual, const std::vector<double>& target) {
  std::pair<std::size_t, double> worst{0, 0};
  for (std::size_t j = 0; j < target.size(); ++j) {
    const double distance = std::fabs(actual[j] - target[j]);
    if (distance > worst.second) worst = {j, distance};
  }
  return worst;
}

}  // namespace

Result<TrajectoryStreamer> TrajectoryStreamer::create(Client& client, Session& session) {
  if (!session.active()) return make_error(ErrorCode::kInvalidArgument, "the session has been released");
  if (session.mode() != ControlMode::kPosition) {
    return make_error(ErrorCode::kInvalidArgument, "session " + session.session_id() + " on '" + session.device() +
                                                       "' is in " + std::string(to_string(session.mode())) +
                                                       " mode: a trajectory streams through a POSITION session");
  }
  auto devices = client.list_devices();
  if (!devices) return devices.error();
  const auto device = std::find_if(devices.value().begin(), devices.value().end(),
                                   [&](const DeviceInfo& info) { return info.name == session.device(); });
  if (device == devices.value().end() || !(device->rate_hz > 0)) {
    return make_error(ErrorCode::kRefused, "robotd does not list device '" + session.device() + "' with a loop rate");
  }
  return TrajectoryStreamer(client, session, 1.0 / device->rate_hz,
                            std::make_unique<detail::DeviceWatch>(client, session.device()));
}

TrajectoryStreamer::TrajectoryStreamer(Client& client, Session& session, double period_s,
                                       std::unique_ptr<detail::DeviceWatch> watch)
    : client_(&client), session_(&session), period_s_(period_s), watch_(std::move(watch)) {}
TrajectoryStreamer::TrajectoryStreamer(TrajectoryStreamer&&) noexcept = default;
TrajectoryStreamer& TrajectoryStreamer::operator=(TrajectoryStreamer&&) noexcept = default;
TrajectoryStreamer::~TrajectoryStreamer() = default;

std::vector<double> TrajectoryStreamer::measured() const {
  const std::vector<double> all = watch_->positions();
  std::vector<double> motors;
  motors.reserve(session_->motor_ids().size());
  for (const std::int32_t id : session_->motor_ids()) {
    const auto index = static_cast<std::size_t>(id);
    motors.push_back(index < all.size() ? all[index] : std::nan(""));
  }
  return motors;
}

Result<void> TrajectoryStreamer::hold() { return session_->send_positions(as_floats(measured())); }

Result<void> TrajectoryStreamer::still_running(const std::string& where) {
  const detail::DeviceCondition condition = watch_->condition();
  const std::string device = "'" + session_->device() + "'";
  if (condition.state != DeviceState::kRunning) {
    (void)hold();  // robotd refuses it in an e-stop or fault; it keeps the arm still anywhere else
    return make_error(ErrorCode::kRefused, "device " + device + " left RUNNING: it is " +
                                               state_description(condition.state, condition.text) +
                                               "; the trajectory stopped at " + where);
  }
  auto info = session_->info(0ms);
  if (!info && info.error().code == ErrorCode::kRefused) {
    // Why it ended shows in the device's next status (an e-stop ends every session of the device).
    std::string device_now;
    if (auto status = client_->next_device_status(session_->device(), 500ms); status) {
      device_now = "; device " + device + " is " + state_description(status.value().state, status.value().state_text);
    }
    return make_error(ErrorCode::kRefused, info.error().message + device_now + "; the trajectory stopped at " + where);
  }
  return {};
}

Result<StreamReport> TrajectoryStreamer::stream(const SampledTrajectory& trajectory, const std::atomic<bool>& stop,
                                                const StreamOptions& options) {
  const std::size_t motors = session_->motor_ids().size();
  if (auto checked = check_trajectory(trajectory, motors); !checked) return checked.error();
  if (auto first = watch_->wait_for_first(client_->options().service_timeout); !first) return first.error();

  StreamReport report;
  report.last_measured_rad = measured();
  const auto [start_joint, start_offset] = farthest(report.last_measured_rad, trajectory.positions.front());
  if (!(start_offset <= options.max_start_offset_rad)) {
    return make_error(ErrorCode::kInvalidArgument,
                      "the trajectory starts " + fixed(start_offset, 3) + " rad from where motor " +
                          std::to_string(session_->motor_ids()[start_joint]) + " of '" + session_->device() + "' is (" +
                          fixed(report.last_measured_rad[start_joint], 3) + " rad): expected at most " +
                          fixed(options.max_start_offset_rad, 3) + " rad; plan it from the measured position");
  }

  const SampledTrajectory samples = resample(trajectory, period_s_);
  const double duration = trajectory.duration_s();
  const std::size_t count = samples.positions.size();
  const auto fraction_at = [&](std::size_t k) {
    return count == 1 ? 1.0 : static_cast<double>(k) / static_cast<double>(count - 1);
  };
  // One command per tick (the velocities feed forward): false after the stop flag, an error for
  // any other reason to stop or a failed send.
  const auto command = [&](const std::vector<double>& positions, const std::vector<double>& velocities,
                           double fraction) -> Result<bool> {
    const std::string where = progress_text(fraction, duration);
    if (stop.load()) {
      if (auto held = hold(); !held) return held.error();
      report.end = StreamEnd::kStopped;
      report.summary = "stopped at " + where + "; holding at the measured position";
      return false;
    }
    if (auto running = still_running(where); !running) return running.error();
    if (auto sent = session_->send_aligned(
            Command{.positions = as_floats(positions), .velocities = as_floats(velocities)}, options.send_lead);
        !sent) {
      return sent.error();
    }
    ++report.commands_sent;
    return true;
  };

  for (std::size_t k = 0; k < count; ++k) {
    std::vector<double> positions = samples.positions[k];
    if (options.tracking == Tracking::kSpeedOnly) {
      const std::vector<double> now = measured();
      for (std::size_t j = 0; j < motors; ++j) positions[j] = now[j] + samples.velocities[k][j] * period_s_;
    }
    auto sent = command(positions, samples.velocities[k], report.fraction_done);
    if (!sent) return sent.error();
    report.last_measured_rad = measured();
    if (!sent.value()) return report;
    report.fraction_done = fraction_at(k);
    if (options.on_progress) options.on_progress(report.fraction_done);
  }
  report.summary = "sent " + std::to_string(count) + " commands over " + fixed(duration, 2) + " s";
  if (!options.arrival) return report;

  const std::vector<double>& target = samples.positions.back();
  const std::vector<double> still(motors, 0.0);
  const auto deadline = std::chrono::steady_clock::now() + options.arrival->timeout;
  while (true) {
    report.last_measured_rad = measured();
    const auto [joint, off] = farthest(report.last_measured_rad, target);
    if (off <= options.arrival->tolerance_rad) {
      report.summary += "; arrived within " + fixed(options.arrival->tolerance_rad, 3) + " rad";
      return report;
    }
    if (std::chrono::steady_clock::now() >= deadline) {
      return make_error(ErrorCode::kTimeout,
                        "'" + session_->device() + "' did not arrive within " +
                            std::to_string(options.arrival->timeout.count()) + " ms of the trajectory's end: motor " +
                            std::to_string(session_->motor_ids()[joint]) + " is " + fixed(off, 4) +
                            " rad from its target (tolerance " + fixed(options.arrival->tolerance_rad, 4) + " rad)");
    }
    auto sent = command(target, still, 1.0);
    if (!sent) return sent.error();
    if (!sent.value()) return report;
  }
}

}  // namespace robotd::motion
