// A driver with a simulated mechanism behind it, for the safety scenarios: joints with inertia,
// gravity and the command each tick asked for, plus every misbehaviour a scenario injects
// (faults, a lost link, silence, non-finite readings, a pressed e-stop button, joints moved
// by hand). It records what the loop wrote and what it read, for the invariant checker.
#pragma once

#include <array>
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <span>

#include "robotd/driver/driver.hpp"
#include "scenario.hpp"

namespace robotd::safety {

class PlantDriver final : public driver::Driver {
 public:
  explicit PlantDriver(const DeviceSpec& spec);

  Result<void> configure(const nlohmann::json& /*params*/) override { return {}; }
  driver::DeviceDescription describe() const override;
  Result<void> connect() override { return {}; }
  void disconnect() noexcept override {}
  /// Recovering and zeroing take the ticks set by next_maintenance() (0: at once), counted by
  /// advance(), unless abort_maintenance() ends them first; meanwhile they block the calling
  /// (maintenance) thread.
  Result<void> recover() override;
  Result<void> reset_zero(std::span<const int> joints) override;
  void abort_maintenance() noexcept override { abort_requested.store(true); }

  /// How long the next recover() or reset_zero() takes, and whether it fails.
  void next_maintenance(int ticks, bool fail) noexcept;
  /// Whether a recover() or reset_zero() is waiting out its ticks now.
  bool in_maintenance_work() const noexcept { return in_work_.load(); }
  /// Whether that wait is over (its ticks have passed, or it was aborted): it returns now.
  bool maintenance_released();

  driver::IoResult read(driver::Feedback& out, driver::FaultInfo& fault) noexcept override;
  driver::IoResult write(const driver::CommandFrame& command, driver::FaultInfo& fault) noexcept override;

  Result<nlohmann::json> call(const std::string& op, const nlohmann::json& /*args*/) override {
    return make_error(ErrorCode::kRefused, "no op " + op);
  }
  driver::Diagnostics diagnostics() const override { return {}; }

  /// Moves the mechanism one period under the command written this tick (or none).
  void advance(double dt_s) noexcept;

  // What the scenario injects.
  int fault_code = 0;  // nonzero: read reports this fault
  bool link_up = true;
  bool silent = false;
  bool estop_input = false;
  std::array<std::array<bool, 3>, driver::kMaxJoints> non_finite{};  // [joint][FeedbackField]
  void teleport(std::size_t joint, double position) noexcept;
  /// describe() reports `joint`'s position limits as ±`range` (within the spec's) from now on.
  void narrow(std::size_t joint, double range);

  // What the loop did this tick.
  bool wrote = false;
  driver::CommandFrame frame{};
  bool read_called = false;
  driver::IoResult read_result = driver::IoResult::kNoNewData;
  bool read_ok = false;
  driver::Feedback read_feedback{};
  std::atomic<bool> abort_requested{false};

  /// Clears the per-tick records before a tick.
  void begin_tick() noexcept;

 private:
  driver::IoResult read_unrecorded(driver::Feedback& out, driver::FaultInfo& fault) noexcept;
  /// Waits out the maintenance ticks; false if aborted.
  bool wait_for_maintenance();

  struct Joint {
    double position = 0;
    double velocity = 0;
    double effort = 0;
  };
  DeviceSpec spec_;
  std::size_t joint_count_;
  mutable std::mutex mutex_;  // the ticks counted, the joints and the described limits, shared with a
                              // maintenance thread
  std::condition_variable ticked_;
  std::uint64_t ticks_ = 0;
  std::uint64_t until_ = 0;  // the tick a waiting maintenance ends at
  int maintenance_ticks_ = 0;
  bool maintenance_fails_ = false;
  std::atomic<bool> in_work_{false};
  std::array<Joint, driver::kMaxJoints> joints_{};
  std::array<double, driver::kMaxJoints> described_range_{};  // 0: the spec's limits
  driver::CommandFrame last_written_{};
  bool have_written_ = false;
};

}  // namespace robotd::safety
