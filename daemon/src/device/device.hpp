// One configured device: its driver plugin, what robotd knows about it, the channel to its
// RT loop, and the loop's thread. Lifecycle (non-RT): configure → start → [maintenance]* →
// stop.
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <span>
#include <string_view>
#include <thread>
#include <vector>

#include "config/config.hpp"
#include "control/device_model.hpp"
#include "device/control_loop.hpp"
#include "device/device_channel.hpp"
#include "plugin/plugin_loader.hpp"
#include "robotd/result.hpp"
#include "rt/realtime_thread.hpp"

namespace robotd::device {

/// How many ticks apart the device's states are published (and offered to closed-loop sessions):
/// its joint_state_rate_hz as the nearest whole number of ticks, 1 when that is unset.
std::uint64_t state_every_ticks(const config::DeviceConfig& config);

class Device {
 public:
  Device(config::DeviceConfig config, std::unique_ptr<plugin::LoadedDriver> plugin);
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;
  ~Device();

  /// Configures the driver with the device's params and builds the model (limits narrowed by
  /// the config's joint_limits; widening a driver limit is refused).
  Result<void> configure();
  /// How the loop runs: on its own RT thread at rate_hz (robotd), or a tick at a time when the
  /// caller says (deterministic tests of the services around a loop, at simulated times).
  enum class LoopRunner { kThread, kCaller };
  /// Connects the driver and starts the RT loop. Limits the connected driver describes (read
  /// from the device, e.g. the PiPER's 0x473) narrow the model's, never widen them.
  Result<void> start(LoopRunner runner = LoopRunner::kThread);
  /// LoopRunner::kCaller only: one tick due at `deadline_ns`, run at `now_ns`.
  void tick(std::int64_t deadline_ns, std::int64_t now_ns) noexcept { loop_->tick(deadline_ns, now_ns); }
  /// Tells the loop to begin its safe stop (returns at once).
  void request_stop();
  /// Brings the device to its safe stop, ends the loop and disconnects the driver.
  void stop();

  /// Pauses the loop's driver I/O, runs `work` on the calling thread, resumes. If `work`
  /// succeeds and `clears_fault`, a latched fault is cleared. Joints then hold where measured.
  /// After a successful `work` (a reconnect, a recover) the limits the driver describes
  /// narrow the device's (narrow_to_described).
  /// An e-stop or a shutdown pre-empts it: refused if one is pending, aborted (through the
  /// driver's abort_maintenance) if one comes while `work` runs.
  Result<void> run_maintenance(const std::function<Result<void>(driver::Driver&)>& work, bool clears_fault,
                               std::chrono::milliseconds timeout);

  /// The device's limits now: the model's, narrowed by what the connected driver describes at
  /// start, after every maintenance and after every device op. Any non-RT thread.
  std::shared_ptr<const std::vector<driver::JointLimits>> limits() const;
  /// Narrows the limits by `reported` (control::narrow_limits: never widens) and hands them to
  /// the loop, which holds them from its next tick. Each change is logged, naming `source`.
  /// Refused (nothing changes) if a joint would be left with no position range. Non-RT.
  Result<void> narrow_limits(std::span<const driver::JointLimits> reported, std::string_view source);
  /// narrow_limits by the limits the driver describes now; a refusal is logged. Non-RT.
  void narrow_to_described();

  const config::DeviceConfig& config() const { return config_; }
  const control::DeviceModel& model() const { return model_; }
  DeviceChannel& channel() { return *channel_; }
  const DeviceChannel& channel() const { return *channel_; }
  driver::Driver& driver() { return plugin_->driver(); }
  const rt::ThreadStart& thread_start() const { return thread_start_; }
  bool running() const {
    return thread_.joinable() || (runner_ == LoopRunner::kCaller && loop_ != nullptr && !loop_->finished());
  }

  /// Who engaged the e-stop and why, for DeviceStatus.state_text.
  void set_estop_note(std::string note);
  std::string estop_note() const;

 private:
  std::string preempted_by() const;
  void publish_limits_locked();

  config::DeviceConfig config_;
  std::unique_ptr<plugin::LoadedDriver> plugin_;
  control::DeviceModel model_;
  std::unique_ptr<DeviceChannel> channel_;
  std::unique_ptr<ControlLoop> loop_;
  driver::NamedThread thread_;
  LoopRunner runner_ = LoopRunner::kThread;
  rt::ThreadStart thread_start_;
  std::mutex maintenance_mutex_;
  // Serialises the narrowings (the loop's limit buffer has one producer) and guards limits_.
  mutable std::mutex limits_mutex_;
  std::shared_ptr<const std::vector<driver::JointLimits>> limits_;
  mutable std::mutex note_mutex_;
  std::string estop_note_;
  bool connected_ = false;
};

}  // namespace robotd::device
