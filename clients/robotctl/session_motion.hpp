// Streaming position targets through a session at a steady rate: a minimum-jerk trajectory,
// then its target held until the joints arrive. move and replay both use it.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "joint_position_watch.hpp"
#include "robotd/client/client.hpp"
#include "robotd/result.hpp"
#include "stop_signals.hpp"
#include "trajectory.hpp"

namespace robotctl {

using Clock = std::chrono::steady_clock;

/// Motor ids 0..joints-1.
std::vector<std::int32_t> every_motor(const robotd::DeviceInfo& device);
/// The values of `motor_ids` from a value per joint.
std::vector<double> positions_of(const std::vector<double>& all_rad, const std::vector<std::int32_t>& motor_ids);
std::vector<float> as_floats(const std::vector<double>& values);
/// Long enough that a late tick never ends the session, short enough that a dead robotctl is
/// caught quickly.
std::chrono::milliseconds session_timeout(Clock::duration tick_period);

/// A POSITION session on some motors of a device, and the device's joint state when it began.
struct PositionSession {
  robotd::Session session;
  robotd::JointState start;  // a position per joint of the device
};

struct PositionSessionRequest {
  std::string device;
  std::vector<std::int32_t> motor_ids;
  Clock::duration tick_period{};  // how often commands will come: sets the session timeout
  robotd::Behavior on_timeout = robotd::Behavior::kDamping;
  robotd::Behavior on_release = robotd::Behavior::kKeep;
};

/// Takes the motors and reads where the device's `joint_count` joints are. Fails with robotd's
/// refusal, a timeout, or a joint state of another size (the session is then released).
robotd::Result<PositionSession> take_position_session(robotd::Client& client, const PositionSessionRequest& wanted,
                                                      std::size_t joint_count);

struct MotionSettings {
  Clock::duration tick_period = std::chrono::milliseconds(10);
  double tolerance_rad = 0.02;             // how close counts as arrived
  std::chrono::milliseconds settle{2000};  // how long after the trajectory the joints may take
};

struct MotionResult {
  enum class End { kArrived, kNotArrived, kStopSignal, kFailed };
  End end = End::kFailed;
  double elapsed_s = 0;            // from the first command
  std::vector<double> actual_rad;  // last measured positions of the motors, in motor order
  robotd::Error error;             // kFailed: why
};

/// Streams `plan` through `session` (whose motors are `motor_ids`) every tick, then keeps
/// sending `target_rad` until every motor is within the tolerance (by `watch`, or
/// `measured_rad`, a value per joint, until it has a sample) or the settle time is over.
/// Returns early on a stop signal or when robotd cannot be reached. Does not release.
MotionResult stream_move(robotd::Session& session, StopSignals& stop, const JointPositionWatch& watch,
                         const std::vector<double>& measured_rad, const MinimumJerkMove& plan,
                         const std::vector<double>& target_rad, const MotionSettings& settings);

/// The largest |actual - target|.
double max_error_rad(const std::vector<double>& actual_rad, const std::vector<double>& target_rad);

}  // namespace robotctl
