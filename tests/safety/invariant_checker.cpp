#include "invariant_checker.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>

#include "control/behavior_map.hpp"

namespace robotd::safety {
namespace {

using driver::JointCommandKind;

constexpr double kTolerance = 1e-9;

bool finite(const driver::JointCommand& c) {
  return std::isfinite(c.position_rad) && std::isfinite(c.velocity_rad_s) && std::isfinite(c.kp) &&
         std::isfinite(c.kd) && std::isfinite(c.torque_nm);
}

bool setpoint_in_effect(const driver::JointCommand& c) {
  return c.kind == JointCommandKind::kPosition || (c.kind == JointCommandKind::kImpedance && c.kp > 0);
}

bool same(double a, double b) { return std::fabs(a - b) <= kTolerance * std::max(1.0, std::fabs(b)); }

std::string describe(const driver::JointCommand& c) {
  std::ostringstream out;
  out.precision(9);
  const char* kind = c.kind == JointCommandKind::kNone       ? "none"
                     : c.kind == JointCommandKind::kPosition ? "position"
                                                             : "impedance";
  out << kind << " p=" << c.position_rad << " v=" << c.velocity_rad_s << " kp=" << c.kp << " kd=" << c.kd
      << " tau=" << c.torque_nm << (c.owned ? " owned" : " unowned");
  return out.str();
}

const char* event_name(device::LoopEvent::Type type) {
  switch (type) {
    case device::LoopEvent::Type::kSessionTimedOut:
      return "SessionTimedOut";
    case device::LoopEvent::Type::kSessionReleased:
      return "SessionReleased";
    case device::LoopEvent::Type::kSessionEndedByShutdown:
      return "SessionEndedByShutdown";
    case device::LoopEvent::Type::kSessionRateTooLow:
      return "SessionRateTooLow";
    case device::LoopEvent::Type::kSuccessRateLow:
      return "SuccessRateLow";
    case device::LoopEvent::Type::kSuccessRateRecovered:
      return "SuccessRateRecovered";
    default:
      return "other";
  }
}

}  // namespace

InvariantChecker::InvariantChecker(const DeviceSpec& spec, const device::LoopSettings& settings)
    : spec_(spec), model_(spec.model()), settings_(settings), dt_s_(1.0 / settings.rate_hz) {}

// --- what the service side did --------------------------------------------------------------

void InvariantChecker::on_start_posted(const session::SessionRecord& record) {
  Session session;
  session.slot = record.slot;
  session.generation = record.generation;
  session.mode = record.mode;
  session.fallback = record.applied_behavior;
  session.timeout_ns = static_cast<std::int64_t>(record.timeout_ms) * 1'000'000;
  session.last_activity_ns = record.granted_ns;
  session.motors = record.motors;
  for (std::size_t j = 0; j < model_.joint_count(); ++j) {
    session.default_kp[j] = model_.default_kp[j];
    session.default_kd[j] = model_.default_kd[j];
  }
  for (std::size_t i = 0; i < record.motor_ids.size(); ++i) {
    const auto j = static_cast<std::size_t>(record.motor_ids[i]);
    if (!record.default_kp.empty()) session.default_kp[j] = static_cast<double>(record.default_kp[i]);
    if (!record.default_kd.empty()) session.default_kd[j] = static_cast<double>(record.default_kd[i]);
  }
  session.fallback_kp = session.default_kp;
  session.fallback_kd = session.default_kd;
  session.on_low = record.on_low_success_rate;
  session.answers = AnswerModel(record.min_command_success_rate);
  sessions_[record.generation] = session;
  pending_events_.push_back(ControlEvent{true, record.generation, Behavior::kKeep});
}

void InvariantChecker::on_release_posted(std::uint8_t /*slot*/, std::uint32_t generation, Behavior applied) {
  pending_events_.push_back(ControlEvent{false, generation, applied});
}

void InvariantChecker::on_command_accepted(std::uint32_t generation, const control::ValidatedCommand& command,
                                           std::int64_t received_ns, std::uint64_t answers_tick) {
  ++sequence_;
  for (std::size_t i = 0; i < command.count; ++i) {
    const control::JointTargetUpdate& update = command.joints[i];
    targets_[update.joint] = Target{true, generation, sequence_, received_ns, update};
  }
  if (auto it = sessions_.find(generation); it != sessions_.end()) {
    it->second.last_activity_ns = std::max(it->second.last_activity_ns, received_ns);
    it->second.answer = answers_tick;
  }
}

void InvariantChecker::on_estop(bool engaged) {
  if (engaged && !estop_) estop_pending_ticks_ = 0;
  if (!engaged) estop_pending_ticks_ = -1;  // reset before it could reach the device: nothing owed
  estop_ = engaged;
}

void InvariantChecker::on_maintenance_requested() { maintenance_requested_ = true; }

void InvariantChecker::on_shutdown_requested() {
  if (!shutting_down_) shutdown_pending_ticks_ = 0;
  shutting_down_ = true;
}

// --- the model ------------------------------------------------------------------------------

void InvariantChecker::end_session(std::uint32_t generation, Behavior behavior) {
  auto it = sessions_.find(generation);
  if (it == sessions_.end()) return;
  const Session& session = it->second;
  for (std::size_t j = 0; j < model_.joint_count(); ++j) {
    Joint& joint = joints_[j];
    if (joint.owner != generation) continue;
    joint.owner = 0;
    joint.has_target = false;
    joint.kp = session.fallback_kp[j];
    joint.kd = session.fallback_kd[j];
    switch (behavior) {
      case Behavior::kKeep:
        // Hold at the braking point with the session's fallback gains and no torque.
        joint.activity = Activity::kHold;
        break;
      case Behavior::kDamping:
        joint.activity = Activity::kDamping;
        joint.session_kd = session.fallback_kd[j];
        joint.session_gains_allowed = true;
        break;
      case Behavior::kZeroTorque:
        joint.activity = Activity::kZeroTorque;
        break;
    }
  }
  sessions_.erase(it);
}

void InvariantChecker::take_control_events() {
  for (const ControlEvent& event : pending_events_) {
    auto it = sessions_.find(event.generation);
    if (it == sessions_.end()) continue;
    if (!event.start) {
      if (it->second.started) {
        expected_ends_.push_back(event.generation);
        end_session(event.generation, event.behavior);
      }
      continue;
    }
    for (auto& [other_generation, other] : sessions_) {
      if (other_generation != event.generation && other.started && other.slot == it->second.slot) {
        expected_ends_.push_back(other_generation);
        end_session(other_generation, other.fallback);
        break;
      }
    }
    it = sessions_.find(event.generation);
    it->second.started = true;
    for (std::size_t j = 0; j < model_.joint_count(); ++j) {
      if (!it->second.motors.test(j)) continue;
      joints_[j].owner = event.generation;
      joints_[j].has_target = false;
    }
  }
  pending_events_.clear();
}

std::optional<Violation> InvariantChecker::take_shutdown_ends(const TickObservation& tick) {
  for (const device::LoopEvent& event : *tick.events) {
    if (event.type != device::LoopEvent::Type::kSessionEndedByShutdown) continue;
    if (!shutting_down_) {
      return violation(tick, "I7 sessions end on time",
                       "session " + std::to_string(event.generation) + " ended by a shutdown nobody requested");
    }
    end_session(event.generation, settings_.shutdown_behavior);
  }
  return std::nullopt;
}

void InvariantChecker::expire_sessions(std::int64_t now_ns) {
  std::vector<std::uint32_t> expired;
  for (const auto& [generation, session] : sessions_) {
    if (session.started && now_ns - session.last_activity_ns > session.timeout_ns) expired.push_back(generation);
  }
  for (const std::uint32_t generation : expired) {
    expected_timeouts_.push_back(generation);
    end_session(generation, sessions_[generation].fallback);
  }
}

// After the timeouts, as the loop books answers: each closed-loop session's newest answer, and
// its rate against its minimum. A FALLBACK session below it ends with its timeout behaviour.
void InvariantChecker::book_answers() {
  std::vector<std::uint32_t> too_low;
  for (auto& [generation, session] : sessions_) {
    if (!session.started) continue;
    const bool answer_offered = session.answer < offered_ticks_.size() && offered_ticks_[session.answer];
    session.answers.tick(session.answer, answer_offered, offered_);
    if (session.answers.recovered()) expected_rate_recoveries_.push_back(generation);
    if (!session.answers.fell()) continue;
    if (session.on_low == LowRateAction::kFallback) {
      too_low.push_back(generation);
    } else {
      expected_rate_lows_.push_back(generation);
    }
  }
  for (const std::uint32_t generation : too_low) {
    expected_rate_ends_.push_back(generation);
    end_session(generation, sessions_[generation].fallback);
  }
}

void InvariantChecker::apply_targets() {
  for (std::size_t j = 0; j < model_.joint_count(); ++j) {
    Joint& joint = joints_[j];
    const Target& target = targets_[j];
    if (joint.owner == 0 || !target.present || target.generation != joint.owner) continue;
    if (target.sequence == joint.applied_sequence) continue;
    joint.applied_sequence = target.sequence;
    if (target.received_ns <= safe_ended_ns_) continue;  // written before a safe state ended: stale
    const Session& session = sessions_[joint.owner];
    joint.activity = session.mode == ControlMode::kTorque ? Activity::kTorque : Activity::kFollow;
    joint.applied = target;
    joint.has_target = true;
  }
}

void InvariantChecker::leave_safe_state() {
  for (std::size_t j = 0; j < model_.joint_count(); ++j) {
    Joint& joint = joints_[j];
    joint.has_target = false;
    switch (joint.activity) {
      case Activity::kHold:
      case Activity::kFollow:
      case Activity::kTorque:
        // Whatever moved a joint before holds it where it is measured now, with default gains.
        joint.activity = Activity::kHold;
        joint.kp = model_.default_kp[j];
        joint.kd = model_.default_kd[j];
        joint.reseed_allowed = true;
        break;
      case Activity::kDamping:
        joint.session_gains_allowed = true;
        break;
      case Activity::kIdle:
      case Activity::kZeroTorque:
        break;
    }
  }
}

void InvariantChecker::update_measurement(const TickObservation& tick) {
  if (tick.read_result != driver::IoResult::kOk || tick.read == nullptr) return;
  ever_read_ = true;
  last_ok_read_ns_ = tick.now_ns;
  for (std::size_t j = 0; j < model_.joint_count(); ++j) {
    Joint& joint = joints_[j];
    const driver::JointFeedback& reading = tick.read->joints[j];
    const bool position_ok = std::isfinite(reading.position_rad);
    const bool velocity_ok = std::isfinite(reading.velocity_rad_s);
    if (position_ok) joint.measured = reading.position_rad;
    if (velocity_ok) joint.measured_velocity = reading.velocity_rad_s;
    if (position_ok && velocity_ok) {
      joint.non_finite_since_ns = -1;
      joint.measured_known = true;
    } else if (joint.non_finite_since_ns < 0) {
      joint.non_finite_since_ns = tick.now_ns;
    }
  }
  if (tick.read->estop_input && !estop_) on_estop(true);
}

Violation InvariantChecker::violation(const TickObservation& tick, const char* invariant,
                                      const std::string& detail) const {
  return Violation{invariant, detail, tick.tick};
}

// --- the checks -----------------------------------------------------------------------------

void InvariantChecker::on_limits_narrowed(std::span<const driver::JointLimits> limits) {
  for (std::size_t j = 0; j < model_.joint_count(); ++j) {
    if (limits[j].position_min_rad == model_.limits[j].position_min_rad &&
        limits[j].position_max_rad == model_.limits[j].position_max_rad)
      continue;
    model_.limits[j] = limits[j];
    joints_[j].narrowed = true;
  }
}

std::optional<Violation> InvariantChecker::check(const TickObservation& tick) {
  // In the loop's order: measure, take the session events, the shutdown, lift a safe state
  // that has cleared, then time out silent sessions.
  update_measurement(tick);
  take_control_events();
  if (auto broken = take_shutdown_ends(tick)) return broken;
  const bool safe_now = tick.state->state != DeviceState::kRunning;
  if (safe_ && !safe_now) {
    safe_ended_ns_ = tick.now_ns;
    leave_safe_state();
  }
  safe_ = safe_now;
  expire_sessions(tick.now_ns);
  book_answers();
  if (auto broken = check_events(tick)) return broken;
  if (auto broken = check_answers(tick)) return broken;
  if (auto broken = check_state(tick)) return broken;
  if (!safe_now && !shutting_down_) apply_targets();

  auto broken = check_frame(tick);
  previous_state_ = tick.state->state;
  if (tick.state->state == DeviceState::kMaintenance && tick.read_result != driver::IoResult::kOk) {
    // The driver is (or was just) out of the loop's hands: what it measured before is old.
    for (std::size_t j = 0; j < model_.joint_count(); ++j) {
      joints_[j].non_finite_since_ns = -1;
      joints_[j].measured_known = false;
    }
  }
  if (tick.state->state != DeviceState::kMaintenance) maintenance_requested_ = false;
  // Closed-loop sessions answer the states of a RUNNING device (docs/design.md "Closed loop").
  if (tick.state->state == DeviceState::kRunning && tick.tick % settings_.state_every_ticks == 0) {
    offered_ = tick.tick;
    offered_ticks_.resize(tick.tick + 1);
    offered_ticks_[tick.tick] = true;
  }
  return broken;
}

std::optional<Violation> InvariantChecker::check_events(const TickObservation& tick) {
  using Type = device::LoopEvent::Type;
  const auto list = [](const std::vector<std::uint32_t>& ids) {
    std::string out;
    for (const auto id : ids) out += (out.empty() ? "" : ",") + std::to_string(id);
    return out.empty() ? std::string("none") : out;
  };
  // The sessions the loop named in events of `type` this tick, against the model's.
  const auto compare = [&](Type type, std::vector<std::uint32_t>& expected, const char* invariant,
                           const char* what) -> std::optional<Violation> {
    std::vector<std::uint32_t> seen;
    for (const device::LoopEvent& event : *tick.events) {
      if (event.type == type) seen.push_back(event.generation);
    }
    std::sort(seen.begin(), seen.end());
    std::sort(expected.begin(), expected.end());
    std::optional<Violation> broken;
    if (seen != expected) {
      broken = violation(
          tick, invariant,
          std::string(what) + ": " + list(seen) + "; expected: " + list(expected) + " (" + event_name(type) + ")");
    }
    expected.clear();
    return broken;
  };
  std::optional<Violation> broken =
      compare(Type::kSessionTimedOut, expected_timeouts_, "I7 sessions end on time", "sessions timed out");
  for (auto [type, expected, what] : {
           std::tuple{Type::kSessionReleased, &expected_ends_, "sessions released"},
           std::tuple{Type::kSessionRateTooLow, &expected_rate_ends_, "sessions ended for their success rate"},
           std::tuple{Type::kSuccessRateLow, &expected_rate_lows_, "sessions warned of a low success rate"},
           std::tuple{Type::kSuccessRateRecovered, &expected_rate_recoveries_, "sessions whose rate recovered"},
       }) {
    const char* invariant = type == Type::kSessionReleased ? "I7 sessions end on time" : "I10 closed loop";
    auto found = compare(type, *expected, invariant, what);
    if (!broken) broken = std::move(found);
  }
  return broken;
}

// What the loop publishes of each live session's answers is what the model booked.
std::optional<Violation> InvariantChecker::check_answers(const TickObservation& tick) {
  for (const auto& [generation, session] : sessions_) {
    if (!session.started) continue;
    const device::AnswerCounts& counts = tick.state->answers[session.slot];
    const AnswerModel& model = session.answers;
    const bool same_rate =
        !model.closed_loop() || counts.success_rate == static_cast<float>(model.in_time_in_window()) /
                                                           static_cast<float>(std::min<std::uint64_t>(
                                                               model.decided(), kSuccessRateWindowTicks));
    if (counts.generation != generation || counts.closed_loop != model.closed_loop() ||
        counts.to_answer != model.decided() || counts.in_time != model.in_time() || !same_rate ||
        counts.rate_low != model.low()) {
      std::ostringstream out;
      out << "session " << generation << " (slot " << int{session.slot} << ") published generation "
          << counts.generation << (counts.closed_loop ? " closed-loop" : " open-loop") << " " << counts.in_time
          << " of " << counts.to_answer << " in time, rate " << counts.success_rate << (counts.rate_low ? " low" : "")
          << "; expected " << (model.closed_loop() ? "closed-loop " : "open-loop ") << model.in_time() << " of "
          << model.decided() << " in time, " << model.in_time_in_window() << " in time in the window"
          << (model.low() ? ", low" : "") << " (newest offered tick " << offered_ << ", its newest answer "
          << session.answer << ")";
      return violation(tick, "I10 closed loop", out.str());
    }
  }
  return std::nullopt;
}

std::optional<Violation> InvariantChecker::check_state(const TickObservation& tick) {
  const DeviceState state = tick.state->state;
  if (state == DeviceState::kStopped) return std::nullopt;
  if (estop_ && state == DeviceState::kRunning) {
    return violation(tick, "I3 e-stop first", "the e-stop is engaged but the device reports RUNNING");
  }
  const bool link_problem =
      tick.read_result == driver::IoResult::kFault || tick.read_result == driver::IoResult::kDisconnected;
  if ((link_problem || tick.write_failed) && state != DeviceState::kFault) {
    return violation(tick, "I8 faults latch",
                     std::string("the driver reported a fault or a lost link but the device reports ") +
                         std::string(to_string(state)));
  }
  if (state != DeviceState::kRunning) return std::nullopt;
  if (!ever_read_ ||
      tick.now_ns - last_ok_read_ns_ > static_cast<std::int64_t>(spec_.feedback_timeout_ms) * 1'000'000) {
    return violation(tick, "I8 faults latch", "RUNNING without fresh feedback for longer than feedback_timeout_ms");
  }
  for (std::size_t j = 0; j < model_.joint_count(); ++j) {
    const Joint& joint = joints_[j];
    if (!joint.measured_known) {
      return violation(tick, "I5 finite", "RUNNING before joint " + std::to_string(j) + " has a finite reading");
    }
    if (joint.non_finite_since_ns >= 0 &&
        tick.now_ns - joint.non_finite_since_ns > static_cast<std::int64_t>(spec_.feedback_timeout_ms) * 1'000'000) {
      return violation(tick, "I5 finite",
                       "joint " + std::to_string(j) + " has read non-finite for " +
                           std::to_string((tick.now_ns - joint.non_finite_since_ns) / 1'000'000) +
                           " ms and the device still reports RUNNING");
    }
  }
  return std::nullopt;
}

std::optional<Violation> InvariantChecker::check_frame(const TickObservation& tick) {
  if (tick.state->state == DeviceState::kMaintenance) maintenance_requested_ = true;
  const bool finished = tick.state->state == DeviceState::kStopped;
  if (estop_pending_ticks_ >= 0) {
    if (tick.wrote && tick.frame->estop) {
      estop_pending_ticks_ = -1;
    } else if (!finished) {
      ++estop_pending_ticks_;
      const std::int64_t allowed = maintenance_requested_ ? 3 : 0;
      if (estop_pending_ticks_ > allowed) {
        return violation(tick, "I3 e-stop first",
                         "the e-stop was engaged " + std::to_string(estop_pending_ticks_) +
                             " tick(s) ago and no e-stop frame has reached the driver" +
                             (maintenance_requested_ ? " (maintenance was running)" : ""));
      }
    }
  }
  if (shutdown_pending_ticks_ >= 0 && !finished) {
    ++shutdown_pending_ticks_;
    const std::int64_t allowed = spec_.shutdown_ms + 2 + (maintenance_requested_ ? 3 : 0);
    if (shutdown_pending_ticks_ > allowed) {
      return violation(tick, "I9 shutdown stops",
                       "the loop has not finished its shutdown stop " + std::to_string(shutdown_pending_ticks_) +
                           " ticks after the shutdown request");
    }
  }
  if (!tick.wrote) return std::nullopt;
  if (shutting_down_) {
    for (const auto& [generation, session] : sessions_) {
      if (session.started) {
        return violation(tick, "I9 shutdown stops",
                         "session " + std::to_string(generation) + " outlived the start of the shutdown stop");
      }
    }
  }
  if (tick.frame->estop != estop_) {
    return violation(tick, "I3 e-stop first",
                     std::string("frame.estop is ") + (tick.frame->estop ? "set" : "clear") + " while the e-stop is " +
                         (estop_ ? "engaged" : "reset"));
  }
  for (std::size_t j = 0; j < model_.joint_count(); ++j) {
    if (auto broken = check_joint(tick, j)) return broken;
  }
  previous_frame_tick_ = tick.tick;
  return std::nullopt;
}

std::optional<Violation> InvariantChecker::check_joint(const TickObservation& tick, std::size_t j) {
  const driver::JointCommand& c = tick.frame->joints[j];
  Joint& joint = joints_[j];
  const driver::JointLimits& limits = model_.limits[j];
  const std::string name = "joint " + std::to_string(j) + ": ";
  const auto fail = [&](const char* invariant, const std::string& why) {
    return violation(tick, invariant,
                     name + why + " [" + describe(c) + ", measured " + std::to_string(joint.measured) + "]");
  };

  if (!finite(c)) return fail("I5 finite", "a non-finite value reached write()");
  if (std::fabs(c.velocity_rad_s) > limits.velocity_max_rad_s + kTolerance)
    return fail("I6 limits", "velocity beyond velocity_max");
  if (std::fabs(c.torque_nm) > limits.effort_max_nm + kTolerance) return fail("I6 limits", "torque beyond effort_max");
  if (c.kp < 0 || c.kp > limits.kp_max + kTolerance || c.kd < 0 || c.kd > limits.kd_max + kTolerance)
    return fail("I6 limits", "gain outside 0..kp_max / 0..kd_max");

  const bool live_owner = joint.owner != 0 && sessions_.count(joint.owner) != 0 && sessions_[joint.owner].started;
  if (c.owned != live_owner) {
    return fail("I4 ownership", std::string("frame says ") + (c.owned ? "owned" : "unowned") + ", the owner is " +
                                    (live_owner ? "session " + std::to_string(joint.owner) : "nobody"));
  }
  if (!live_owner && c.torque_nm != 0) return fail("I4 ownership", "an unowned joint carries a torque");

  const DeviceState state = tick.state->state;
  const bool safe = state != DeviceState::kRunning;
  bool hold = false;
  if (!safe) joint.idle_before_safe_state = c.kind == JointCommandKind::kNone;
  if (c.kind == JointCommandKind::kNone) {
    // Undriven: a joint nobody drives; a joint that was undriven when the safe state began; or,
    // without fresh feedback, a joint that would need a measured position to hold.
    const bool all_measured =
        std::all_of(joints_.begin(), joints_.begin() + static_cast<std::ptrdiff_t>(model_.joint_count()),
                    [](const Joint& other) { return other.measured_known; });
    const bool allowed = joint.activity == Activity::kIdle || !all_measured || (safe && joint.idle_before_safe_state);
    if (!allowed) return fail("I2 nothing stale", "a driven joint was left without a command");
    joint.previous_in_effect = false;
    joint.previous_tick = tick.tick;
    return std::nullopt;
  }
  if (joint.activity == Activity::kIdle) return fail("I4 ownership", "a joint nobody drives was commanded");

  if (safe || shutting_down_) {
    // The safe (or shutdown) behaviour with the joint's own default gains and no torque.
    Behavior behavior = settings_.safe_behavior;
    if (shutting_down_ && !estop_ && state == DeviceState::kRunning) behavior = settings_.shutdown_behavior;
    const auto matches = [&](Behavior b) {
      switch (b) {
        case Behavior::kDamping:
          return c.kind == JointCommandKind::kImpedance && c.kp == 0 && same(c.kd, model_.default_kd[j]) &&
                 c.torque_nm == 0;
        case Behavior::kZeroTorque:
          return c.kind == JointCommandKind::kImpedance && c.kp == 0 && c.kd == 0 && c.torque_nm == 0;
        case Behavior::kKeep:
          return setpoint_in_effect(c) && c.torque_nm == 0;
      }
      return false;
    };
    const bool ok = matches(behavior) ||
                    (shutting_down_ &&
                     (matches(settings_.safe_behavior) || matches(settings_.shutdown_behavior) ||
                      (joint.activity == Activity::kDamping && c.kind == JointCommandKind::kImpedance && c.kp == 0)));
    if (!ok) {
      return fail(estop_ ? "I3 e-stop first" : "I2 nothing stale",
                  std::string("not the ") + std::string(to_string(behavior)) + " safe behaviour in state " +
                      std::string(to_string(state)));
    }
    hold = setpoint_in_effect(c);
    if (hold && !shutting_down_ && (!same(c.kp, model_.default_kp[j]) || !same(c.kd, model_.default_kd[j]))) {
      return fail("I4 ownership", "a safe hold carries gains other than the joint's defaults");
    }
    return check_setpoint(tick, j, c, hold);
  }

  const Target* target = joint.has_target ? &joint.applied : nullptr;
  const Session* session = live_owner ? &sessions_[joint.owner] : nullptr;
  switch (joint.activity) {
    case Activity::kIdle:
      break;
    case Activity::kHold:
      if (!setpoint_in_effect(c) && !(c.kind == JointCommandKind::kImpedance && joint.kp == 0)) {
        return fail("I2 nothing stale", "expected a hold");
      }
      if (c.torque_nm != 0) return fail("I2 nothing stale", "a hold carries a torque (stale or a client's)");
      if (!same(c.kp, joint.kp) || !same(c.kd, joint.kd)) {
        return fail("I4 ownership", "a hold carries gains other than its fallback gains (" + std::to_string(joint.kp) +
                                        ", " + std::to_string(joint.kd) + ")");
      }
      hold = true;
      break;
    case Activity::kFollow: {
      if (target == nullptr || session == nullptr) return fail("I2 nothing stale", "following without a target");
      const auto& u = target->update;
      const bool mixed = session->mode == ControlMode::kMixed;
      const double kp = (u.fields & control::kHasKp) != 0 ? u.kp : session->default_kp[j];
      const double kd = (u.fields & control::kHasKd) != 0 ? u.kd : session->default_kd[j];
      const double torque = mixed ? u.torque : 0.0;
      const auto kind = mixed ? JointCommandKind::kImpedance : JointCommandKind::kPosition;
      if (c.kind != kind || !same(c.kp, kp) || !same(c.kd, kd) || c.torque_nm != torque) {
        std::ostringstream want;
        want << "expected the newest target's kp=" << kp << " kd=" << kd << " tau=" << torque;
        return fail("I2 nothing stale", want.str());
      }
      break;
    }
    case Activity::kTorque: {
      if (target == nullptr) return fail("I2 nothing stale", "torque without a target");
      const auto& u = target->update;
      const double torque = (u.fields & control::kHasTorque) != 0 ? u.torque : 0.0;
      if (c.kind != JointCommandKind::kImpedance || c.kp != 0 || c.kd != 0 || c.torque_nm != torque) {
        return fail("I2 nothing stale", "expected the newest target's torque " + std::to_string(torque));
      }
      break;
    }
    case Activity::kDamping: {
      const bool kd_ok = same(c.kd, joint.kd) || (joint.session_gains_allowed && same(c.kd, joint.session_kd)) ||
                         same(c.kd, model_.default_kd[j]);
      if (c.kind != JointCommandKind::kImpedance || c.kp != 0 || !kd_ok || c.torque_nm != 0 || c.velocity_rad_s != 0)
        return fail("I2 nothing stale", "expected damping");
      break;
    }
    case Activity::kZeroTorque:
      if (c.kind != JointCommandKind::kImpedance || c.kp != 0 || c.kd != 0 || c.torque_nm != 0)
        return fail("I2 nothing stale", "expected zero torque");
      break;
  }
  return check_setpoint(tick, j, c, hold);
}

std::optional<Violation> InvariantChecker::check_setpoint(const TickObservation& tick, std::size_t j,
                                                          const driver::JointCommand& c, bool hold) {
  Joint& joint = joints_[j];
  const driver::JointLimits& limits = model_.limits[j];
  const bool in_effect = setpoint_in_effect(c);
  if (!in_effect) joint.holding = false;
  const bool continuous = joint.previous_in_effect && joint.previous_tick + 1 == tick.tick;
  const bool reseed_allowed = joint.reseed_allowed;
  joint.reseed_allowed = false;
  joint.previous_tick = tick.tick;
  if (!in_effect) {
    joint.previous_in_effect = false;
    return std::nullopt;
  }
  const double p = c.position_rad;
  const double step_limit = limits.velocity_max_rad_s * dt_s_ * (1 + 1e-9) + 1e-12;
  const double acceleration_limit = limits.acceleration_max_rad_s2 * dt_s_ * dt_s_ * (1 + 1e-6) + 1e-12;
  const double step = p - joint.previous_position;
  const bool from_measured = std::fabs(p - joint.measured) <= step_limit;
  const bool smooth =
      continuous && std::fabs(step) <= step_limit && std::fabs(step - joint.previous_step) <= acceleration_limit;
  const auto fail = [&](const char* invariant, const std::string& why) {
    std::ostringstream out;
    out.precision(9);
    out << "joint " << j << ": " << why << " [setpoint " << joint.previous_position << " -> " << p << " (step " << step
        << ", previous step " << joint.previous_step << "), measured " << joint.measured << ", limits "
        << limits.position_min_rad << ".." << limits.position_max_rad << ", v " << limits.velocity_max_rad_s << ", a "
        << limits.acceleration_max_rad_s2 << ", " << describe(c) << "]";
    return violation(tick, invariant, out.str());
  };

  const bool started_here = !continuous || (reseed_allowed && (!smooth || from_measured));
  // A narrowing can put a limit behind a setpoint moving outward, or within its braking
  // distance: the setpoint then stops on the limit (or where it is, outside it) sooner than the
  // acceleration limit would let it: a position limit comes first (docs/safety.md, I6).
  const bool stops_on_narrowed_limit = joint.narrowed && continuous && step * joint.previous_step >= 0 &&
                                       std::fabs(step) <= std::fabs(joint.previous_step) &&
                                       (step == 0 || p == limits.position_min_rad || p == limits.position_max_rad);
  if (started_here || step == 0) joint.narrowed = false;
  if (started_here ? !from_measured : !smooth && !stops_on_narrowed_limit) {
    return fail("I1 no jump", started_here ? "the setpoint does not start from the measured position"
                                           : "the setpoint moved faster than the velocity and acceleration limits");
  }
  const auto outside = [&](double x) {
    return std::max({0.0, limits.position_min_rad - x, x - limits.position_max_rad});
  };
  if (outside(p) > 0 && !started_here && outside(p) > outside(joint.previous_position) + 1e-12) {
    return fail("I6 limits", "the setpoint moved further outside the position limits");
  }
  if (hold) {
    // A hold brakes as hard as the limits allow and stays where it comes to rest: it never
    // speeds up, never goes further than its braking distance, and turns back by at most the
    // last step of a discrete brake (a·dt²). A setpoint outside the limits may come inside.
    const double quantum = limits.acceleration_max_rad_s2 * dt_s_ * dt_s_ * (1 + 1e-6) + 1e-12;
    const auto begin_hold = [&](double origin, double speed) {
      const double a = limits.acceleration_max_rad_s2;
      joint.holding = true;
      joint.hold_origin = origin;
      const double braking = std::max(0.0, speed - a * dt_s_);  // braking begins with the hold's first step
      joint.hold_reach = (braking * braking + braking * a * dt_s_) / (2 * a) + 2 * quantum;
    };
    if (!joint.holding || started_here) {
      begin_hold(started_here ? p : joint.previous_position,
                 started_here ? 0.0 : std::fabs(joint.previous_step) / dt_s_);
    }
    const bool coming_inside = outside(joint.previous_position) > 0 && outside(p) < outside(joint.previous_position);
    const bool speeding_up = !started_here && std::fabs(step) > std::fabs(joint.previous_step) + 1e-12;
    const bool turning_back = !started_here && step * joint.previous_step < 0 && std::fabs(step) > quantum;
    const bool too_far = std::fabs(p - joint.hold_origin) > joint.hold_reach;
    if (!coming_inside && (speeding_up || turning_back || too_far)) {
      return fail("I2 nothing stale", too_far ? "a held joint went further than its braking distance"
                                              : "a held joint is not braking to a stop (it speeds up or turns back)");
    }
    if (coming_inside) begin_hold(p, std::fabs(step) / dt_s_);
  } else {
    joint.holding = false;
  }
  joint.previous_step = started_here ? c.velocity_rad_s * dt_s_ : step;
  joint.previous_position = p;
  joint.previous_in_effect = true;
  return std::nullopt;
}

}  // namespace robotd::safety
