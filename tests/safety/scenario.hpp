// A safety scenario: one simulated device and a sequence of events that happen to it — ticks,
// sessions, commands, e-stops, faults, link losses, strange feedback, maintenance, shutdown.
// Scenarios are plain text (one event a line, see docs/safety.md "The randomized test"), so a
// failing one can be printed, shrunk, kept as a regression case and replayed exactly.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "control/device_model.hpp"
#include "robotd/messages.hpp"

namespace robotd::safety {

inline constexpr std::int64_t kPeriodNs = 1'000'000;  // the rigs' 1 kHz loop
inline constexpr std::int64_t kMsNs = 1'000'000;

/// The simulated device: every joint shares these limits and default gains.
struct DeviceSpec {
  std::size_t joints = 3;
  bool torque = true;  // TORQUE and MIXED sessions
  bool damping = true;
  bool zero_torque = true;
  Behavior safe = Behavior::kDamping;      // requested; mapped to what the device can do
  Behavior shutdown = Behavior::kDamping;  // requested; mapped likewise
  control::LimitPolicy policy = control::LimitPolicy::kReject;
  int feedback_timeout_ms = 50;
  int shutdown_ms = 20;
  double position_min = -2;
  double position_max = 2;
  double velocity_max = 1;
  double acceleration_max = 10;
  double effort_max = 5;
  double kp_max = 100;
  double kd_max = 10;
  double default_kp = 50;
  double default_kd = 2;

  control::DeviceModel model() const;
};

enum class FeedbackField : std::uint8_t { kPosition, kVelocity, kEffort };

struct Event {
  enum class Kind : std::uint8_t {
    kTick,        // count ticks, each woken latency_us after its deadline
    kStart,       // request_control as session `label`
    kRelease,     // release_control of session `label` with `behavior`
    kCommand,     // a control command of session `label`, its content drawn from `seed`; with
                  // `answers`, it names the tick newest + `answer_offset` (newest: the rig's latest state)
    kKeepalive,   // an empty command of session `label`
    kEstop,       // e-stop service: engage (on) or reset
    kEstopInput,  // the device's own e-stop button: pressed (on) or released
    kFault,       // the driver reports fault `code` until a recover clears it
    kLink,        // the link goes down (on = false) or comes back (on = true)
    kSilence,     // the driver stops (on) or resumes delivering feedback
    kNonFinite,   // `joint` reports a non-finite `field` (on) or finite values again
    kTeleport,    // `joint` is measured at `value` from now on (pushed, zeroed, sagged)
    kNarrow,      // `joint`'s position limits narrowed to ±`value` at run time (an op, a reconnect)
    kRecover,     // device_call recover: maintenance lasting `count` ticks, failing if `fail`
    kResetZero,   // reset_zero: maintenance lasting `count` ticks
    kShutdown,    // SIGTERM
  };
  Kind kind = Kind::kTick;
  int label = 0;
  int count = 1;
  int latency_us = 0;
  std::uint64_t motors = 0;  // kStart: bit j = joint j
  ControlMode mode = ControlMode::kPosition;
  Behavior behavior = Behavior::kKeep;  // kStart: timeout fallback; kRelease: release mode
  int timeout_ms = 100;
  double default_kp = -1;  // kStart: < 0 = not given
  double default_kd = -1;
  double min_rate = 0;  // kStart: min_command_success_rate (0 = none)
  LowRateAction on_low = LowRateAction::kWarn;
  std::uint32_t seed = 0;
  bool answers = false;   // kCommand: answers a tick (a closed-loop client); else answers_tick 0
  int answer_offset = 0;  // kCommand: the tick it answers, relative to the newest the rig has seen
  bool on = true;
  bool fail = false;
  int code = 0;
  std::size_t joint = 0;
  FeedbackField field = FeedbackField::kPosition;
  double value = 0;
};

struct Scenario {
  DeviceSpec device;
  std::vector<Event> events;

  std::size_t tick_count() const;
};

std::string to_text(const Scenario& scenario);
std::string to_text(const Event& event);

/// Parses what to_text wrote. On error, `error` says which line and what was expected.
std::optional<Scenario> parse_scenario(std::string_view text, std::string& error);

}  // namespace robotd::safety
