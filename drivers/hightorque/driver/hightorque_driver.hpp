// HighTorque motors on one or more buses — the PI Plus humanoid's 23, or any chain of them
// (docs/drivers/hightorque.md).
//
// RT thread: read() drains every bus (non-blocking) and turns the motors' replies into joint
// feedback through the joint map; a bus that closes or goes silent is a lost link. write() sends
// the tick's commands in MIT block frames (six motors a frame), free-wheels motors nobody
// commands, brakes every motor on robotd's e-stop, passes on the ops' system requests, and
// reports a motor's own fault.
// Other threads: connect(), recover() and reset_zero() own the buses while the loop is paused;
// call() ops hand system requests to the RT thread and read its replies through lock-free rings;
// diagnostics() reads the snapshot the RT thread publishes.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include "driver/hightorque_params.hpp"
#include "driver/motor_bus.hpp"
#include "robotd/driver/abort_flag.hpp"
#include "robotd/driver/driver.hpp"
#include "robotd/driver/rt_handoff.hpp"
#include "robotd/driver/seqlock.hpp"
#include "robotd/driver/spsc_ring.hpp"
#include "robotd/imu/imu_source.hpp"

namespace robotd::hightorque {

inline constexpr std::int32_t kNotConnectedFault = -1;
inline constexpr std::int32_t kLinkLostFault = -2;
inline constexpr std::int32_t kMotorSilentFault = -3;
inline constexpr std::size_t kMaxBuses = 16;

/// One motor as the RT thread last heard it, in the joint frame.
struct MotorStatus {
  double position_rad = 0;
  double velocity_rad_s = 0;
  double torque_nm = 0;
  double temperature_c = 0;
  bool has_temperature = false;
  std::uint8_t mode = 0;
  std::uint8_t fault = 0;
  bool owned = false;
  std::int64_t last_reply_ns = 0;
  std::uint64_t replies = 0;
};

struct BusCounters {
  std::uint64_t frames_sent = 0;
  std::uint64_t frames_received = 0;
  std::uint64_t frames_dropped = 0;
  std::uint64_t bytes_skipped = 0;
  double sent_per_s = 0;  // over the last full second
  double received_per_s = 0;
};

/// What the RT thread publishes for diagnostics() and the ops.
struct DriverSnapshot {
  bool link_up = false;
  std::uint64_t ticks = 0;
  std::array<MotorStatus, driver::kMaxJoints> motors{};
  std::array<BusCounters, kMaxBuses> buses{};
};

class HighTorqueDriver final : public driver::Driver, private ReplySink {
 public:
  HighTorqueDriver();
  ~HighTorqueDriver() override;
  HighTorqueDriver(const HighTorqueDriver&) = delete;
  HighTorqueDriver& operator=(const HighTorqueDriver&) = delete;

  Result<void> configure(const nlohmann::json& params) override;
  driver::DeviceDescription describe() const override;

  Result<void> connect() override;
  void disconnect() noexcept override;
  Result<void> recover() override;
  Result<void> reset_zero(std::span<const int> joints) override;
  void abort_maintenance() noexcept override { abort_.request(); }

  driver::IoResult read(driver::Feedback& out, driver::FaultInfo& fault) noexcept override;
  driver::IoResult write(const driver::CommandFrame& command, driver::FaultInfo& fault) noexcept override;

  Result<nlohmann::json> call(const std::string& op, const nlohmann::json& args) override;
  driver::Diagnostics diagnostics() const override;

 private:
  struct MotorRuntime {
    MotorStatus status;
    std::int64_t fault_since_ns = 0;
  };
  struct BusRuntime {
    std::int64_t last_reply_ns = 0;
    std::uint64_t sent_at_second = 0;
    std::uint64_t received_at_second = 0;
  };

  // ReplySink: runs on whichever thread drains the buses (RT, or connect/zeroing while paused).
  void on_reply(const Reply& reply) noexcept override;

  // Link (non-RT, loop paused).
  Result<void> connect_and_start();
  Result<void> clear_faults();
  void restart_silence_checks() noexcept;
  void open_buses();
  Result<void> open_and_probe();
  Result<void> await_motor_states(std::span<const std::size_t> motors, std::chrono::milliseconds timeout,
                                  const char* what);
  void drain_buses() noexcept;
  void send_to_motors(std::span<const std::size_t> motors, SystemRequest::Kind kind, int value = 0);
  /// Sends `kind` to `motors` until every one acknowledged it (a kResult reply), again every
  /// 20 ms to those that did not, for at most reply_timeout_ms.
  Result<void> acknowledged(std::span<const std::size_t> motors, SystemRequest::Kind kind, const char* what);
  void resend_to_pending(std::span<const std::size_t> motors, const std::vector<bool>& pending,
                         SystemRequest::Kind kind);
  Result<void> check_zeroable(std::span<const int> joints) const;
  Result<void> zero(std::span<const int> joints);

  // reboot_motor, decided by write() at the tick that would send it.
  struct RebootRequest {
    std::size_t motor = 0;
  };
  struct RebootOutcome {
    enum class Verdict : std::uint8_t { kSent, kEstop, kOwned, kHeld, kBusBusy, kLinkClosed };
    Verdict verdict = Verdict::kSent;
    std::size_t blocking_motor = 0;     // kOwned, kHeld: the motor robotd holds
    std::uint64_t replies_at_send = 0;  // kSent: the motor's reply count when the reboot went out
  };
  RebootOutcome decide_reboot(const driver::CommandFrame& command, std::size_t motor) noexcept;

  // RT helpers.
  bool motor_fault(std::int64_t now_ns, driver::FaultInfo& fault) noexcept;
  void publish(std::int64_t now_ns) noexcept;
  void send_tick(const driver::CommandFrame& command) noexcept;
  BlockSlot to_motor_frame(std::size_t motor, const driver::JointCommand& joint) const noexcept;

  // Ops (hightorque_ops.cpp).
  Result<std::size_t> motor_argument(const nlohmann::json& args, const std::string& op, const char* usage) const;
  Result<nlohmann::json> op_state() const;
  Result<nlohmann::json> op_motor_info(const nlohmann::json& args);
  Result<nlohmann::json> op_set_motor_timeout(const nlohmann::json& args);
  Result<nlohmann::json> op_reboot_motor(const nlohmann::json& args);
  /// After a reboot: once `motor` answers again, its own watchdog (which a reboot disarms) is set
  /// to motor_timeout_ms again. False when it did not answer within reply_timeout_ms.
  bool rearm_watchdog_after_reboot(std::size_t motor, std::uint64_t replies_at_send);
  /// The motors a reboot of `motor` restarts: the motor, or its whole port on a board bus.
  std::vector<std::size_t> rebooted_with(std::size_t motor) const;
  /// Queues a system request for the RT thread to send (fails when the loop is not draining).
  Result<void> queue_request(std::size_t motor, const SystemRequest& request);
  std::vector<Reply> collect_replies(std::size_t motor, std::size_t count);

  HighTorqueParams params_;
  std::vector<std::unique_ptr<MotorBus>> buses_;
  std::vector<std::vector<std::size_t>> motors_on_bus_;                           // logical motor indices per bus
  std::array<std::array<std::int16_t, kBroadcastId + 1>, kMaxBuses> motor_at_{};  // [bus][CAN id] → motor, −1
  std::unique_ptr<imu::ImuSource> imu_;

  // RT-owned state.
  std::array<MotorRuntime, driver::kMaxJoints> motors_{};
  std::array<BusRuntime, kMaxBuses> bus_runtime_{};
  std::size_t draining_bus_ = 0;    // which bus on_reply hears from
  std::int64_t reply_time_ns_ = 0;  // when this drain of the buses began: the replies' time
  bool link_up_ = false;
  std::uint64_t ticks_ = 0;
  std::int64_t second_started_ns_ = 0;
  std::array<BusCounters, kMaxBuses> rates_{};

  // Ops ⇄ RT thread.
  struct QueuedRequest {
    std::size_t bus = 0;
    SystemRequest request;
  };
  struct BusReply {
    std::size_t bus = 0;
    Reply reply;
  };
  driver::SpscRing<QueuedRequest, 64> requests_;
  driver::SpscRing<BusReply, 256> replies_;  // every reply that is not a motor's state
  driver::RtHandoff<RebootRequest, RebootOutcome> reboot_;
  /// Whether a reply heard on its bus came from logical motor `motor`.
  bool from_motor(const BusReply& reply, std::size_t motor) const;
  mutable std::mutex ops_mutex_;  // one op at a time; never taken by the RT thread
  driver::AbortFlag abort_;       // abort_maintenance(): connect, recover and reset_zero stop waiting
  driver::SeqLock<DriverSnapshot> snapshot_;
  std::atomic<bool> connected_{false};
  std::atomic<int> motor_timeout_ms_{0};  // set by configure and the set_motor_timeout op
};

}  // namespace robotd::hightorque
