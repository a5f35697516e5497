// The simulated robot: N joints behind motors (joint_dynamics.hpp) and an optional still base
// IMU, with fault injection through call() for tests and the no-hardware demo.
//
// Threads, beyond driver.hpp's contract: call() and diagnostics() share with the RT thread only
// atomics and two sequence locks. The RT thread publishes a snapshot of the joints after every
// read(); faults injected through call() reach the RT thread through a sequence lock it reads
// without waiting (a read that races a write keeps the previous copy, one tick late at worst).
//
// The simulated controller damps every joint (kp = 0, kd = default_kd) while the e-stop flag of
// the last command frame is set, while a fault is injected and while the link is lost, as a
// motor controller's fault or command timeout would. After recover() no earlier command is
// resumed: the joints are unpowered until the next write().
//
// The motors can be disabled (op "motors", as a vendor's disable op): they then apply no torque
// at all, the e-stop's damping included. write() decides a disable at the tick it acts on, from
// that tick's commands: never while robotd drives a joint (a session, or the KEEP or DAMPING a
// session left behind) or under the e-stop. A session taking a joint enables them again, as the
// PiPER and xArm drivers do by default.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <optional>
#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "joint_dynamics.hpp"
#include "robotd/driver/abort_flag.hpp"
#include "robotd/driver/driver.hpp"
#include "robotd/driver/json_reader.hpp"
#include "robotd/driver/rt_handoff.hpp"
#include "robotd/driver/seqlock.hpp"
#include "sim_params.hpp"

namespace robotd::sim {

/// FaultInfo codes of the sim's own link states (an injected fault carries the code it was given).
inline constexpr std::int32_t kNotConnectedFaultCode = -1;
inline constexpr std::int32_t kLinkLostFaultCode = -2;

inline constexpr double kNativeRateHz = 1000;
inline constexpr double kStandardGravity_m_s2 = 9.81;

struct SimJointSnapshot {
  double position_rad = 0;           // reported: after the zero offset
  double physical_position_rad = 0;  // before the zero offset
  double velocity_rad_s = 0;
  double torque_nm = 0;  // applied by the motor
  double kp = 0;         // gains applied, after defaults, limits and e-stop
  double kd = 0;
  driver::JointCommandKind command = driver::JointCommandKind::kNone;
};

/// What the RT thread publishes after every physics step.
struct SimSnapshot {
  std::size_t joint_count = 0;
  bool estop = false;
  std::array<SimJointSnapshot, driver::kMaxJoints> joints{};
};

struct InjectedFaults {
  bool feedback_stopped = false;
  bool link_lost = false;
  driver::FaultInfo fault{};  // code 0: none

  bool halts_motors() const noexcept { return link_lost || fault.code != 0; }
};

/// What write() decided about a request to disable the motors.
struct MotorsOffOutcome {
  enum class Verdict : std::uint8_t { kDisabled, kEstop, kOwned, kHeld };
  Verdict verdict = Verdict::kDisabled;
  std::size_t joint = 0;  // kOwned, kHeld: the first joint in the way
};
struct MotorsOffRequest {};

class SimDriver final : public driver::Driver {
 public:
  Result<void> configure(const nlohmann::json& params) override;
  driver::DeviceDescription describe() const override;

  Result<void> connect() override;
  void disconnect() noexcept override;
  Result<void> recover() override;
  /// Each listed joint then reads 0 where it stands; an empty list means every joint. The
  /// configured limits stay in the reported frame, so the hard stops move with the zero.
  Result<void> reset_zero(std::span<const int> joints) override;
  /// recover() and reset_zero() are instant unless slow_maintenance made them wait: then it ends
  /// that wait with an error.
  void abort_maintenance() noexcept override { abort_.request(); }

  /// Advances the simulation by the CLOCK_MONOTONIC time since the previous read().
  driver::IoResult read(driver::Feedback& out, driver::FaultInfo& fault) noexcept override;
  driver::IoResult write(const driver::CommandFrame& command, driver::FaultInfo& fault) noexcept override;

  Result<nlohmann::json> call(const std::string& op, const nlohmann::json& args) override;
  driver::Diagnostics diagnostics() const override;

  /// read() at an explicit CLOCK_MONOTONIC time, so a test can run the simulation on its own clock.
  driver::IoResult read_at(std::int64_t now_ns, driver::Feedback& out, driver::FaultInfo& fault) noexcept;

 private:
  // RT side (sim_driver.cpp).
  /// Applies what connect(), recover() and call() changed since the last tick; false while not connected.
  bool refresh_link_state(driver::FaultInfo& fault) noexcept;
  /// kOk, or the injected link loss or fault that halts the motors.
  driver::IoResult injected_link_status(driver::FaultInfo& fault) const noexcept;
  void advance_physics(std::int64_t now_ns) noexcept;
  /// Disables the motors unless robotd drives a joint or the e-stop is on.
  MotorsOffOutcome decide_motors_off(const driver::CommandFrame& command) noexcept;
  void fill_feedback(driver::Feedback& out) const noexcept;

  // Non-RT side (sim_driver_ops.cpp).
  Result<nlohmann::json> stop_feedback(const nlohmann::json& args);
  Result<nlohmann::json> press_estop_input(const nlohmann::json& args);
  Result<nlohmann::json> inject_disconnect(const nlohmann::json& args);
  Result<nlohmann::json> raise_fault(const nlohmann::json& args);
  Result<nlohmann::json> set_external_torque(const nlohmann::json& args);
  Result<nlohmann::json> stall(const nlohmann::json& args);
  Result<nlohmann::json> slow_maintenance(const nlohmann::json& args);
  /// The wait slow_maintenance asked of this recover() or reset_zero(); false when aborted.
  bool wait_as_asked();
  Result<nlohmann::json> motors(const nlohmann::json& args);
  /// Hands a disable to write() until it is decided otherwise than "a session owns a joint": the
  /// session robotd released before this op may not have ended in the loop yet.
  Result<MotorsOffOutcome> disable_motors();
  Result<nlohmann::json> set_imu(const nlohmann::json& args);
  Result<nlohmann::json> command_latency(const nlohmann::json& args);
  Result<nlohmann::json> state(const nlohmann::json& args) const;
  std::optional<std::size_t> joint_argument(JsonReader& reader, const nlohmann::json& args) const;
  template <class Change>
  void change_injected_faults(Change change);

  // Set by configure(), which never runs while the RT thread does.
  SimParams params_;
  bool configured_ = false;

  // Shared between the RT thread and the others.
  std::atomic<bool> connected_{false};
  // Bumped by connect() and recover(): the RT thread then drops the stored command and restarts its clock.
  std::atomic<std::uint64_t> link_generation_{0};
  std::array<std::atomic<double>, driver::kMaxJoints> external_torque_nm_{};
  std::array<std::atomic<double>, driver::kMaxJoints> zero_offset_rad_{};
  std::atomic<std::int64_t> stall_ns_{0};             // the next read() blocks this long (a hung bus)
  std::atomic<std::int64_t> maintenance_wait_ns_{0};  // the next recover(), reset_zero() or motors op waits this long
  std::atomic<bool> motors_enabled_{true};
  std::atomic<bool> motors_op_waiting_{false};  // a motors op waits as slow_maintenance asked
  driver::RtHandoff<MotorsOffRequest, MotorsOffOutcome> motors_off_;
  driver::AbortFlag abort_;
  std::atomic<bool> estop_input_{false};         // the simulated controller's e-stop button
  std::atomic<std::uint64_t> recover_calls_{0};  // how often robotd (or a person) tried recover()
  // An injected disconnect lasts until this CLOCK_MONOTONIC time: recover() fails before it.
  std::atomic<std::int64_t> link_down_until_ns_{0};
  // Client send → write() latency of every frame that carries a new command (see
  // command_latency): a ring the RT thread fills and call() reads, atomics only.
  static constexpr std::size_t kLatencySamples = std::size_t{1} << 15U;
  std::array<std::atomic<std::int32_t>, kLatencySamples> latency_ns_{};
  std::atomic<std::uint64_t> latency_count_{0};
  std::atomic<std::uint64_t> latency_reset_at_{0};
  driver::SeqLock<InjectedFaults> injected_faults_;
  std::mutex injected_faults_writer_mutex_;  // serialises non-RT writers; never taken by the RT thread
  driver::SeqLock<SimSnapshot> snapshot_;
  driver::SeqLock<driver::ImuSample> imu_;  // what the IMU reports (set_imu); written under imu_writer_mutex_
  std::mutex imu_writer_mutex_;

  // RT thread only.
  std::array<JointState, driver::kMaxJoints> joints_{};
  driver::CommandFrame command_{};
  std::array<double, driver::kMaxJoints> rt_command_zero_offset_rad_{};  // each joint's zero when command_ came
  InjectedFaults rt_injected_faults_{};
  SimSnapshot rt_snapshot_{};
  driver::ImuSample rt_imu_{};
  std::uint64_t rt_link_generation_ = 0;
  bool rt_clock_started_ = false;
  std::int64_t rt_last_step_ns_ = 0;
};

template <class Change>
void SimDriver::change_injected_faults(Change change) {
  const std::lock_guard lock(injected_faults_writer_mutex_);
  InjectedFaults faults = injected_faults_.load_non_rt();
  change(faults);
  injected_faults_.store(faults);
}

}  // namespace robotd::sim
