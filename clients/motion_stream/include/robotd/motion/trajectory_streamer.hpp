// Streams a planned trajectory through a POSITION session at the device's rate: one command per
// tick of the device's loop, published just before the tick (Session::send_aligned). It stops,
// holding the arm where it is, when asked to (a stop flag, e.g. set by Ctrl-C), when the device
// leaves RUNNING (e-stop, fault) or when robotd ends the session, and says which.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "robotd/client.hpp"
#include "robotd/motion/sampled_trajectory.hpp"

namespace robotd::motion {

namespace detail {
class DeviceWatch;
}  // namespace detail

// Each command carries the sample's velocities too (robotd's POSITION mode takes them as the
// velocity target of its PD law, a feed-forward).
enum class Tracking {
  kPosition,   // command the trajectory's positions
  kSpeedOnly,  // command the measured position + velocity·period: the speed curve, no position correction
};

struct Arrival {
  double tolerance_rad = 0.01;              // every joint at most this far from the last sample
  std::chrono::milliseconds timeout{2000};  // after the last sample; longer is an error
};

struct StreamOptions {
  Tracking tracking = Tracking::kPosition;
  /// Called on the streaming thread after each command with the fraction of the trajectory sent
  /// (0..1): keep it short, it runs once per tick.
  std::function<void(double fraction)> on_progress{};
  /// Set: after the last sample, keep commanding it until every joint is within the tolerance.
  std::optional<Arrival> arrival{};
  /// The first sample must be this close to where each joint is (a plan made from elsewhere
  /// would make robotd rate-limit a jump).
  double max_start_offset_rad = 0.05;
  std::chrono::microseconds send_lead = kDefaultSendLead;
};

enum class StreamEnd {
  kCompleted,  // every sample sent (and, with StreamOptions::arrival, arrived)
  kStopped,    // the stop flag was set: the arm holds where it was measured then
};

struct StreamReport {
  StreamEnd end = StreamEnd::kCompleted;
  std::size_t commands_sent = 0;
  double fraction_done = 0;               // of the trajectory's samples, 0..1
  std::vector<double> last_measured_rad;  // the session's motors, in motor_ids() order
  std::string summary;                    // e.g. "stopped at 42 % (0.84 of 2.00 s); holding at the measured position"
};

class TrajectoryStreamer {
 public:
  /// A streamer for `session` (POSITION mode), which must outlive it, as must `client`. Reads the
  /// device's loop rate from /list_devices and watches its /joint_states and /device_status.
  static Result<TrajectoryStreamer> create(Client& client, Session& session);
  TrajectoryStreamer(TrajectoryStreamer&&) noexcept;
  TrajectoryStreamer& operator=(TrajectoryStreamer&&) noexcept;
  ~TrajectoryStreamer();

  /// The device's loop period: the step the trajectory is resampled to.
  double period_s() const { return period_s_; }

  /// Streams `trajectory` (one value per motor of the session, in motor_ids() order), resampled
  /// to period_s() by linear interpolation: sample k goes to the device's loop k ticks after the
  /// first (a tick this thread was too slow for delays the rest; it never skips ahead). Checks
  /// `stop`, the device's state and the session before each command.
  /// Errors: kInvalidArgument (a malformed trajectory, or one that starts away from the joints;
  /// nothing sent); kRefused when the device leaves RUNNING (the message names its state and why,
  /// and how far the trajectory got; the measured position is sent once) or robotd ends the
  /// session; kTimeout when the joints do not arrive (StreamOptions::arrival) in time; and the
  /// client's own errors.
  Result<StreamReport> stream(const SampledTrajectory& trajectory, const std::atomic<bool>& stop,
                              const StreamOptions& options = {});

 private:
  TrajectoryStreamer(Client& client, Session& session, double period_s, std::unique_ptr<detail::DeviceWatch> watch);

  // Ok while the device is RUNNING and robotd lists the session; else why not, with `where`.
  Result<void> still_running(const std::string& where);
  // The session's motors' newest measured positions.
  std::vector<double> measured() const;
  // Sends the measured position once: the arm stays where it is.
  Result<void> hold();

  Client* client_;
  Session* session_;
  double period_s_;
  std::unique_ptr<detail::DeviceWatch> watch_;
};

}  // namespace robotd::motion
