// An exclusive control session on some motors of one device. While it lives, only its
// commands move those motors. Destroying it releases them (with `release_behavior`).
// If it sends nothing for its timeout, robotd applies its fallback and ends it.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "robotd/client/control_loop.hpp"
#include "robotd/messages.hpp"
#include "robotd/result.hpp"

namespace robotd {

namespace detail {
class ClientCore;
class TickLink;
}  // namespace detail

// Every member has an initializer, so that a designated initializer may name any of them
// (request_control({.device = "arm"})) without -Wmissing-field-initializers.
struct SessionRequest {
  std::string device{};                   // "" = the daemon's only device
  std::vector<std::int32_t> motor_ids{};  // empty = every motor of the device
  ControlMode mode = ControlMode::kPosition;
  Behavior on_timeout = Behavior::kDamping;
  std::chrono::milliseconds timeout{1000};
  std::vector<float> default_kp{};  // empty, or one per motor
  std::vector<float> default_kd{};
  Behavior on_release = Behavior::kKeep;  // what the destructor's release asks for
  // Who will command, shown to everyone in /session_status (e.g. "walk", "walk_v3.onnx").
  std::string policy_name{};
  std::string policy_file_name{};
  // Closed loop. closed_loop: the session answers ticks (next_tick, run_control_loop), so its
  // reader of /<device>/tick_state is created with it and request_control returns once that reader
  // has matched robotd's writer (at most the service timeout more): the first tick after the grant
  // reaches it. Without it the reader is created on the first next_tick / run_control_loop /
  // send_aligned (whose first wait then includes DDS discovery): robotd publishes a device's
  // TickState only while a reader is matched, and a streaming session should not make it publish
  // one per tick for nobody.
  bool closed_loop = false;
  // The least fraction of ticks answered in time (0..1, 0 = none) over the last
  // kSuccessRateWindowTicks, and what robotd does below it (warn, or fall back as on timeout).
  float min_command_success_rate = 0;
  LowRateAction on_low_success_rate = LowRateAction::kWarn;
};

/// One command. Arrays are parallel to motor_ids (empty motor_ids = the session's motors in
/// order). Which arrays are required depends on the session's mode (see docs/design.md, "Sessions").
struct Command {
  std::vector<std::int32_t> motor_ids{};
  std::vector<float> positions{};   // rad
  std::vector<float> velocities{};  // rad/s
  std::vector<float> kp{};
  std::vector<float> kd{};
  std::vector<float> torques{};  // N·m
  /// run_control_loop: this is the loop's last answer (sent, then the loop ends). Not sent to robotd.
  bool finished = false;

  bool operator==(const Command&) const = default;
};

class Session {
 public:
  Session(Session&& other) noexcept;
  Session& operator=(Session&& other) noexcept;
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  ~Session();

  /// The session's capability: it commands and releases the session. Keep it to this client;
  /// robotd shows others only session_id().
  const std::string& uuid() const { return uuid_; }
  /// The session's public id, as /session_status (SessionInfo.uuid, active_uuids), refusals and
  /// robotd's log name it.
  const std::string& session_id() const { return session_id_; }
  /// The device robotd granted (also when the request named none).
  const std::string& device() const { return device_; }
  const std::vector<std::int32_t>& motor_ids() const { return motor_ids_; }
  ControlMode mode() const { return mode_; }
  /// What robotd will really do on timeout (a position-only arm cannot damp).
  Behavior applied_timeout_behavior() const { return applied_behavior_; }
  bool active() const { return core_ != nullptr; }

  /// Publishes a command for this session. Fails only on malformed input or a DDS error;
  /// robotd's verdict on the command shows in /device_status (robotctl status).
  Result<void> command(const Command& command);
  /// Positions for every motor of the session, in motor_ids() order.
  Result<void> send_positions(const std::vector<float>& positions_rad);
  /// Renews the session without moving anything.
  Result<void> keepalive();
  /// Closed loop: the newest TickState of the session's device newer than the last one this
  /// returned, waited for on the calling thread up to `timeout` (kTimeout). Fails with kRefused
  /// once robotd no longer lists the session in /session_status (it timed out, fell back or was
  /// released). Ticks it did not return in between are skipped: a controller wants the newest.
  Result<TickState> next_tick(std::chrono::milliseconds timeout);
  /// Publishes `command` as the answer to `state` (ControlCommand.answers_tick = state.tick).
  /// robotd counts it in time when it arrives before the device's next state is measured.
  Result<void> answer(const TickState& state, const Command& command);
  /// Calls `law` with each new tick's state and answers it, until the law returns a finished
  /// command, options.duration passes or options.stop is set. Fails (kTimeout) when no new tick
  /// comes within options.state_timeout, and as next_tick / answer do; the error names the last
  /// tick seen. Runs on the calling thread.
  Result<ControlLoopReport> run_control_loop(const ControlLaw& law, const ControlLoopOptions& options = {});
  /// "Send aligned" open-loop streaming: sleeps until `lead` before the device's next tick is due,
  /// then publishes `command`, so that it waits in robotd for about `lead` instead of up to a
  /// period. The tick phase comes from the newest TickState if this session reads them (closed
  /// loop), else from /device_status (LoopStatistics.tick_deadline_steady_ns and period_ns; the
  /// first call waits for one, at most the service timeout).
  Result<void> send_aligned(const Command& command, std::chrono::microseconds lead = kDefaultSendLead);
  /// This session's entry in /session_status as robotd last published it (e.g. its command success
  /// rate), waiting up to `timeout` for the first one. kRefused once robotd no longer lists it.
  Result<SessionInfo> info(std::chrono::milliseconds timeout);

  /// Time until robotd's timeout fires, counted from the last command this object sent.
  std::chrono::milliseconds time_left() const;
  /// Releases the motors now; the session is inactive afterwards.
  Result<ReleaseControlResponse> release(Behavior release_mode);

 private:
  friend class Client;
  Session(std::shared_ptr<detail::ClientCore> core, RequestControlResponse granted, const SessionRequest& request);
  // The one home of a ControlCommand's making: the session's uuid and device, the stamps.
  Result<void> publish(const Command& command, std::uint64_t answers_tick);
  // The session's readers, created on first use.
  Result<detail::TickLink*> tick_link();

  std::shared_ptr<detail::ClientCore> core_;
  std::unique_ptr<detail::TickLink> ticks_;  // after core_: its readers go before the participant
  std::string uuid_;
  std::string session_id_;
  std::string device_;
  std::vector<std::int32_t> motor_ids_;
  ControlMode mode_ = ControlMode::kPosition;
  Behavior applied_behavior_ = Behavior::kKeep;
  Behavior release_behavior_ = Behavior::kKeep;
  std::chrono::milliseconds timeout_{0};
  std::chrono::steady_clock::time_point last_sent_;
};

}  // namespace robotd
