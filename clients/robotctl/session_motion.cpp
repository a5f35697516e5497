#include "session_motion.hpp"

#include <algorithm>
#include <cmath>

namespace robotctl {

std::vector<std::int32_t> every_motor(const robotd::DeviceInfo& device) {
  std::vector<std::int32_t> ids(device.joint_names.size());
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<std::int32_t>(i);
  return ids;
}

std::vector<double> positions_of(const std::vector<double>& all_rad, const std::vector<std::int32_t>& motor_ids) {
  std::vector<double> positions(motor_ids.size());
  for (std::size_t i = 0; i < motor_ids.size(); ++i) positions[i] = all_rad.at(static_cast<std::size_t>(motor_ids[i]));
  return positions;
}

std::vector<float> as_floats(const std::vector<double>& values) {
  std::vector<float> floats(values.size());
  std::transform(values.begin(), values.end(), floats.begin(), [](double v) { return static_cast<float>(v); });
  return floats;
}

std::chrono::milliseconds session_timeout(Clock::duration tick_period) {
  return std::max(std::chrono::milliseconds(500), std::chrono::ceil<std::chrono::milliseconds>(5 * tick_period));
}

robotd::Result<PositionSession> take_position_session(robotd::Client& client, const PositionSessionRequest& wanted,
                                                      std::size_t joint_count) {
  robotd::SessionRequest request;
  request.device = wanted.device;
  request.motor_ids = wanted.motor_ids;
  request.mode = robotd::ControlMode::kPosition;
  request.on_timeout = wanted.on_timeout;
  request.timeout = session_timeout(wanted.tick_period);
  request.on_release = wanted.on_release;
  auto granted = client.request_control(request);
  if (!granted) return granted.error();
  auto start = client.next_joint_state(wanted.device, client.options().service_timeout);
  if (!start) return start.error();
  if (start.value().position.size() != joint_count) {
    return robotd::make_error(robotd::ErrorCode::kRefused, "robotd's /joint_states for '" + wanted.device + "' has " +
                                                               std::to_string(start.value().position.size()) +
                                                               " positions for " + std::to_string(joint_count) +
                                                               " joints");
  }
  return PositionSession{std::move(granted.value()), std::move(start.value())};
}

double max_error_rad(const std::vector<double>& actual_rad, const std::vector<double>& target_rad) {
  double largest = 0;
  for (std::size_t i = 0; i < target_rad.size(); ++i)
    largest = std::max(largest, std::fabs(actual_rad[i] - target_rad[i]));
  return largest;
}

MotionResult stream_move(robotd::Session& session, StopSignals& stop, const JointPositionWatch& watch,
                         const std::vector<double>& measured_rad, const MinimumJerkMove& plan,
                         const std::vector<double>& target_rad, const MotionSettings& settings) {
  MotionResult result;
  const auto start_time = Clock::now();
  const auto trajectory_end =
      start_time + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(plan.duration_s()));
  const auto settle_deadline = trajectory_end + settings.settle;
  auto next_tick = start_time;
  while (true) {
    const auto now = Clock::now();
    result.elapsed_s = std::chrono::duration<double>(now - start_time).count();
    if (auto sent = session.send_positions(as_floats(plan.positions_at(result.elapsed_s))); !sent) {
      result.error = sent.error();
      return result;
    }
    if (now >= trajectory_end) {
      result.actual_rad = positions_of(watch.latest().value_or(measured_rad), session.motor_ids());
      if (max_error_rad(result.actual_rad, target_rad) <= settings.tolerance_rad) {
        result.end = MotionResult::End::kArrived;
        return result;
      }
      if (now >= settle_deadline) {
        result.end = MotionResult::End::kNotArrived;
        return result;
      }
    }
    next_tick += settings.tick_period;
    StopSignals::Wake wake = StopSignals::Wake::kWoken;
    while (wake == StopSignals::Wake::kWoken) wake = stop.wait_until(next_tick);
    if (wake == StopSignals::Wake::kStopSignal) {
      result.end = MotionResult::End::kStopSignal;
      return result;
    }
  }
}

}  // namespace robotctl
