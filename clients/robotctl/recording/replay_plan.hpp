// What robotctl replay streams, and whether a device's current limits allow it: the recorded
// position commands of one device, checked joint by joint before anything moves.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "recording/recording_format.hpp"
#include "recording/recording_reader.hpp"
#include "robotd/messages.hpp"
#include "robotd/result.hpp"

namespace robotctl::recording {

struct ReplayStep {
  std::int64_t time_ns = 0;             // recorded receive time, ns since the recording began
  std::int64_t stamp_ns = 0;            // the sender's stamp (CLOCK_REALTIME), 0 = none
  std::vector<std::int32_t> motor_ids;  // the replayed motors this command addressed
  std::vector<float> positions;         // rad, parallel to motor_ids
  std::int64_t pace_ns = 0;             // when to send it, ns after the first step (on plan.pace_clock)
};

/// The clock replay keeps the recorded pace by. The senders' stamps show when each command was
/// sent, free of the delays of delivery to the recorder (a busy recorder takes several at once);
/// receive times are the fallback for commands without stamps, or with stamps that go back
/// (senders whose clocks disagree).
enum class PaceClock { kSenderStamps, kReceiveTimes };

struct ReplayPlan {
  RecordedDevice device;                // as the recording describes it
  std::vector<std::int32_t> motor_ids;  // ascending: every motor the replay commands
  std::vector<double> start_rad;        // each motor's first recorded position, parallel to motor_ids
  std::vector<ReplayStep> steps;        // in recorded order
  PaceClock pace_clock = PaceClock::kReceiveTimes;
  std::size_t keepalives = 0;  // recorded keepalives; replay sends its own instead
  std::string ending;          // how the file ended, when not closed properly ("" if it was)

  /// From the first step to the last, on the pace clock.
  double recorded_duration_s() const;
};

/// Reads the position commands for `device` to the end of `reader`, keeping only `motor_ids`
/// (empty: every motor they address). Fails, saying why and what is expected, when the
/// recording has no such device or no position commands for it, or when a command carries
/// torques (torque and mixed commands are not replayed), has no motor ids, or is malformed.
robotd::Result<ReplayPlan> read_replay_plan(RecordingReader& reader, const std::string& device,
                                            const std::vector<std::int32_t>& motor_ids);

/// What a replay would do on one motor.
struct MotorReplay {
  std::int32_t motor = 0;
  std::string joint;  // the current device's name for it, or "?"
  double min_rad = 0;
  double max_rad = 0;
  double peak_velocity_rad_s = 0;   // at the chosen speed
  double velocity_limit_rad_s = 0;  // 0 when the device gives none
};

struct ReplayCheck {
  std::vector<std::string> violations;  // each: joint, recorded time, value and limit
  std::vector<MotorReplay> motors;
  double duration_s = 0;  // at the chosen speed
};

/// Velocities are measured over at least this much time on the pace clock, so that the jitter
/// of single commands does not count as speed.
inline constexpr std::int64_t kVelocityWindowNs = 20'000'000;

/// Checks `plan` at `speed` (its pace divided by it) against `current`: the joint count
/// and names, that each motor exists, each position within position_min..position_max, each
/// velocity within velocity_max. Runs of consecutive offending commands are one violation.
ReplayCheck check_replay(const ReplayPlan& plan, const robotd::DeviceInfo& current, double speed);

}  // namespace robotctl::recording
