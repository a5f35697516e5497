// The reference model of one device's loop and the safety invariants it checks on every tick
// (docs/safety.md lists them). The model is told what the service side did (sessions granted
// and released, commands accepted, e-stop, maintenance, shutdown) and what the driver saw (the
// feedback it gave, the frame it was asked to write); from that alone it decides what each
// joint may do on this tick and flags the first frame, state or event that breaks a rule.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "answer_model.hpp"
#include "control/command_validator.hpp"
#include "device/control_loop.hpp"
#include "device/device_channel.hpp"
#include "scenario.hpp"
#include "session/session_table.hpp"

namespace robotd::safety {

struct Violation {
  std::string invariant;  // "I1 no jump", …
  std::string detail;
  std::uint64_t tick = 0;
};

struct TickObservation {
  std::uint64_t tick = 0;
  std::int64_t now_ns = 0;
  driver::IoResult read_result = driver::IoResult::kOk;  // what the driver's read returned
  const driver::Feedback* read = nullptr;                // the feedback it gave, if kOk
  bool wrote = false;
  const driver::CommandFrame* frame = nullptr;  // what the loop wrote, if it wrote
  bool write_failed = false;                    // the driver refused the write (link down)
  const device::LoopState* state = nullptr;     // what the loop published at the end of the tick
  const std::vector<device::LoopEvent>* events = nullptr;
  bool estop_input = false;  // the device's e-stop button as the driver reported it
};

class InvariantChecker {
 public:
  InvariantChecker(const DeviceSpec& spec, const device::LoopSettings& settings);

  // What the service side did between ticks.
  void on_start_posted(const session::SessionRecord& record);
  void on_release_posted(std::uint8_t slot, std::uint32_t generation, Behavior applied);
  void on_command_accepted(std::uint32_t generation, const control::ValidatedCommand& command, std::int64_t received_ns,
                           std::uint64_t answers_tick);
  void on_estop(bool engaged);
  void on_maintenance_requested();
  void on_shutdown_requested();
  /// The device's limits now (narrowed at run time); the loop holds them from the next tick.
  void on_limits_narrowed(std::span<const driver::JointLimits> limits);

  /// Checks everything the loop did on one tick. Returns the first broken rule.
  std::optional<Violation> check(const TickObservation& tick);

 private:
  enum class Activity : std::uint8_t { kIdle, kHold, kFollow, kTorque, kDamping, kZeroTorque };

  struct Session {
    std::uint8_t slot = 0;
    std::uint32_t generation = 0;
    ControlMode mode = ControlMode::kPosition;
    Behavior fallback = Behavior::kKeep;
    std::int64_t timeout_ns = 0;
    std::int64_t last_activity_ns = 0;
    control::MotorSet motors;
    std::array<double, driver::kMaxJoints> fallback_kp{};
    std::array<double, driver::kMaxJoints> fallback_kd{};
    std::array<double, driver::kMaxJoints> default_kp{};  // a command without gains uses these
    std::array<double, driver::kMaxJoints> default_kd{};
    bool started = false;  // the loop has taken its start event
    LowRateAction on_low = LowRateAction::kWarn;
    std::uint64_t answer = 0;  // what its newest accepted command answers, as the mailbox holds it
    AnswerModel answers;
  };
  struct Target {
    bool present = false;
    std::uint32_t generation = 0;
    std::uint64_t sequence = 0;
    std::int64_t received_ns = 0;
    control::JointTargetUpdate update;
  };
  struct Joint {
    std::uint32_t owner = 0;
    Activity activity = Activity::kIdle;
    double kp = 0;  // the gains Activity allows (hold: both; damping: kd)
    double kd = 0;
    bool session_gains_allowed = false;  // after a safe state, damping may keep the session's kd
    double session_kd = 0;
    std::uint64_t applied_sequence = 0;
    bool has_target = false;  // the owner's newest admissible target has been applied
    Target applied;
    bool idle_before_safe_state = true;  // its last frame while RUNNING was "none"
    // The loop's measurement, as robotd must see it: the newest finite reading.
    double measured = 0;
    double measured_velocity = 0;
    std::int64_t non_finite_since_ns = -1;
    bool measured_known = false;  // a finite reading since the link (re)started
    // What was written before.
    bool previous_in_effect = false;
    std::uint64_t previous_tick = 0;
    double previous_position = 0;
    double previous_step = 0;
    bool reseed_allowed = true;
    bool holding = false;    // braking to a stop, then still
    double hold_origin = 0;  // where the hold began
    double hold_reach = 0;   // how far from there braking may take it
    bool narrowed = false;   // its position limits narrowed since the setpoint last was at rest
  };

  std::optional<Violation> check_state(const TickObservation& tick);
  std::optional<Violation> check_events(const TickObservation& tick);
  std::optional<Violation> check_frame(const TickObservation& tick);
  std::optional<Violation> check_joint(const TickObservation& tick, std::size_t j);
  std::optional<Violation> check_setpoint(const TickObservation& tick, std::size_t j,
                                          const driver::JointCommand& command, bool hold);
  void update_measurement(const TickObservation& tick);
  void take_control_events();
  std::optional<Violation> take_shutdown_ends(const TickObservation& tick);
  void end_session(std::uint32_t generation, Behavior behavior);
  void expire_sessions(std::int64_t now_ns);
  void book_answers();
  std::optional<Violation> check_answers(const TickObservation& tick);
  void apply_targets();
  void leave_safe_state();
  Violation violation(const TickObservation& tick, const char* invariant, const std::string& detail) const;

  DeviceSpec spec_;
  control::DeviceModel model_;
  device::LoopSettings settings_;
  double dt_s_;

  std::map<std::uint32_t, Session> sessions_;
  struct ControlEvent {
    bool start = true;
    std::uint32_t generation = 0;
    Behavior behavior = Behavior::kKeep;  // release only
  };
  std::vector<ControlEvent> pending_events_;  // posted to the loop, in order
  std::vector<std::uint32_t> expected_timeouts_;
  std::vector<std::uint32_t> expected_ends_;
  std::vector<std::uint32_t> expected_rate_ends_;  // FALLBACK sessions whose rate fell below their minimum
  std::vector<std::uint32_t> expected_rate_lows_;  // WARN sessions, likewise
  std::vector<std::uint32_t> expected_rate_recoveries_;
  std::uint64_t offered_ = 0;        // the newest tick whose state the loop offered for answering
  std::vector<bool> offered_ticks_;  // by tick: its state was offered
  std::array<Target, driver::kMaxJoints> targets_{};
  std::uint64_t sequence_ = 0;
  std::array<Joint, driver::kMaxJoints> joints_{};

  bool estop_ = false;                     // engaged and not reset (by the service or the button)
  std::int64_t estop_pending_ticks_ = -1;  // ticks since engagement without an e-stop frame
  bool maintenance_requested_ = false;     // since the request, until the loop is back
  bool safe_ = false;                      // the loop's published state was not RUNNING
  std::int64_t safe_ended_ns_ = 0;         // targets received before this are stale
  bool shutting_down_ = false;
  std::int64_t shutdown_pending_ticks_ = -1;  // ticks since the request without the shutdown stop
  std::int64_t last_ok_read_ns_ = -1;
  bool ever_read_ = false;
  std::uint64_t previous_frame_tick_ = 0;
  DeviceState previous_state_ = DeviceState::kConnecting;
};

}  // namespace robotd::safety
