#include "device/control_loop.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "rt/allocation_probe.hpp"
#include "rt/monotonic_clock.hpp"

namespace robotd::device {
namespace {

using control::JointMode;

bool is_link_problem(driver::IoResult result) {
  return result == driver::IoResult::kFault || result == driver::IoResult::kDisconnected;
}

JointMode mode_after(Behavior behavior) {
  switch (behavior) {
    case Behavior::kKeep:
      return JointMode::kTrack;
    case Behavior::kDamping:
      return JointMode::kDamping;
    case Behavior::kZeroTorque:
      return JointMode::kZeroTorque;
  }
  return JointMode::kTrack;
}

}  // namespace

ControlLoop::ControlLoop(driver::Driver& driver, const control::DeviceModel& model, DeviceChannel& channel,
                         const LoopSettings& settings)
    : driver_(driver),
      model_(model),
      channel_(channel),
      settings_(settings),
      joint_count_(model.joint_count()),
      period_ns_(static_cast<std::int64_t>(std::llround(1e9 / settings.rate_hz))),
      dt_s_(1.0 / settings.rate_hz) {
  for (std::size_t j = 0; j < joint_count_; ++j) motion_limits_[j] = motion_limits(model.limits[j]);
  frame_.joint_count = joint_count_;
}

void ControlLoop::run() noexcept {
  std::int64_t deadline = rt::monotonic_now_ns() + period_ns_;
  std::int64_t previous_wake = 0;
  while (!finished_.load(std::memory_order_relaxed)) {
    rt::sleep_until_ns(deadline);
    const std::int64_t wake = rt::monotonic_now_ns();
    tick(deadline, wake);
    const std::int64_t end = rt::monotonic_now_ns();
    last_execution_ns_ = end - wake;
    channel_.timings.push(TickTiming{wake - deadline, last_execution_ns_,
                                     previous_wake == 0 ? period_ns_ : wake - previous_wake, answer_round_trip_ns_});
    previous_wake = wake;
    deadline += period_ns_;
    if (end > deadline) {
      // Missed at least one deadline: count them and resume on the next one in the future,
      // rather than firing a burst of late ticks.
      const std::int64_t missed = (end - deadline) / period_ns_ + 1;
      overruns_ += static_cast<std::uint64_t>(missed);
      deadline += missed * period_ns_;
    }
  }
  channel_.stopped.store(true, std::memory_order_release);
}

void ControlLoop::tick(std::int64_t deadline_ns, std::int64_t now_ns) noexcept {
  ++tick_count_;
  newest_sent_ns_ = 0;
  answer_round_trip_ns_ = -1;
  recent_ticks_[tick_count_ % recent_ticks_.size()] = RecentTick{deadline_ns, false};
  take_limits();
  handle_maintenance(now_ns);
  if (!in_maintenance_) read_feedback(now_ns);
  // Session starts and ends after the read, so a fallback begins from this tick's measurement.
  drain_control_events(now_ns);
  update_estop(now_ns);
  update_shutdown(now_ns);
  leave_safe_state_if_clear(now_ns);
  // The mailbox is sampled as late as it can be: a command that arrives while the tick reads
  // the driver still makes this tick. Session expiry needs the newest keepalives, so it
  // follows; sessions time out on time even while maintenance holds the driver.
  take_commands();
  expire_sessions(now_ns);
  book_answers(now_ns);
  if (!in_maintenance_) {
    if (!safe_state_ && !shutting_down_) apply_targets();
    write_command(deadline_ns, now_ns);
  }

  if (tick_count_ == settings_.warmup_ticks) allocation_baseline_ = rt::thread_allocation_count();
  if (allocation_baseline_ >= 0) rt_allocations_ = rt::thread_allocation_count() - allocation_baseline_;

  const std::int64_t wake_latency = now_ns - deadline_ns;
  publish(deadline_ns, now_ns);
  record_black_box(now_ns, wake_latency);
  channel_.ticks.store(tick_count_, std::memory_order_release);
  channel_.state_ready.notify();
}

// Limits narrowed at run time (Device::narrow_limits) hold from this tick on. A setpoint now
// outside them comes back inside under the velocity and acceleration limits (joint_limiter).
void ControlLoop::take_limits() noexcept {
  const LimitSet* fresh = channel_.limits.take();
  if (fresh == nullptr) return;
  std::copy_n(fresh->joints.begin(), joint_count_, motion_limits_.begin());
}

// --- sessions -------------------------------------------------------------------------------

void ControlLoop::drain_control_events(std::int64_t now_ns) noexcept {
  while (auto event = channel_.control_events.pop()) {
    SlotRuntime& slot = slots_[event->slot];
    if (event->type == ControlEvent::Type::kSessionStart) {
      if (slot.active) end_session(event->slot, slot.timeout_behavior, LoopEvent::Type::kSessionReleased, now_ns, 0);
      slot = SlotRuntime{true,
                         event->generation,
                         event->mode,
                         event->behavior,
                         event->timeout_ns,
                         event->granted_ns,
                         event->motors,
                         event->default_kp,
                         event->default_kd,
                         event->on_low_success_rate};
      answers_[event->slot].start(event->generation, event->min_success_rate);
      newest_started_generation_ = std::max(newest_started_generation_, event->generation);
      for (std::size_t j = 0; j < joint_count_; ++j) {
        if (!event->motors.test(j)) continue;
        owners_[j].slot = static_cast<std::int8_t>(event->slot);
        owners_[j].generation = event->generation;
        owners_[j].previous_target_time_ns = 0;
      }
    } else if (slot.active && slot.generation == event->generation) {
      end_session(event->slot, event->behavior, LoopEvent::Type::kSessionReleased, now_ns, 0);
    }
  }
}

void ControlLoop::end_session(std::size_t slot_index, Behavior behavior, LoopEvent::Type why, std::int64_t now_ns,
                              std::int64_t silence_ns) noexcept {
  SlotRuntime& slot = slots_[slot_index];
  for (std::size_t j = 0; j < joint_count_; ++j) {
    if (!slot.motors.test(j) || owners_[j].slot != static_cast<std::int8_t>(slot_index)) continue;
    owners_[j].slot = -1;
    set_behavior(j, behavior, gains_for(j, &slot));
  }
  LoopEvent event;
  event.type = why;
  event.slot = static_cast<std::uint8_t>(slot_index);
  event.generation = slot.generation;
  event.behavior = behavior;
  event.time_ns = now_ns;
  event.silence_ns = silence_ns;
  event.success_rate = answers_[slot_index].counts().success_rate;
  post(event);
  slot.active = false;
}

void ControlLoop::set_behavior(std::size_t joint, Behavior behavior, control::Gains gains) noexcept {
  if (safe_state_) {
    // The safe behaviour stays in force; remember what to resume when it lifts.
    saved_modes_[joint] = mode_after(behavior);
    if (behavior == Behavior::kDamping) saved_kd_[joint] = gains.kd;
    return;
  }
  control::apply_behavior(joints_[joint], behavior, feedback_.joints[joint], gains, motion_limits_[joint], dt_s_);
}

void ControlLoop::expire_sessions(std::int64_t now_ns) noexcept {
  for (std::size_t s = 0; s < slots_.size(); ++s) {
    SlotRuntime& slot = slots_[s];
    if (!slot.active) continue;
    std::int64_t last_activity = slot.granted_ns;
    if (commands_ != nullptr && commands_->slots[s].generation == slot.generation) {
      last_activity = std::max(last_activity, commands_->slots[s].last_command_ns);
    }
    const std::int64_t silence = now_ns - last_activity;
    if (silence > slot.timeout_ns) {
      end_session(s, slot.timeout_behavior, LoopEvent::Type::kSessionTimedOut, now_ns, silence);
    }
  }
}

// Closed-loop sessions: which offered ticks each one answered in time, and its minimum rate.
void ControlLoop::book_answers(std::int64_t now_ns) noexcept {
  for (std::size_t s = 0; s < slots_.size(); ++s) {
    const SlotRuntime& slot = slots_[s];
    if (!slot.active) continue;
    AnswerBook& book = answers_[s];
    if (commands_ != nullptr && commands_->slots[s].generation == slot.generation) {
      const SlotActivity& activity = commands_->slots[s];
      // An answer older than the ticks kept here is long decided: it counts for nothing.
      const bool recent = tick_count_ - activity.answers_tick < recent_ticks_.size();
      const RecentTick& answered = recent_ticks_[activity.answers_tick % recent_ticks_.size()];
      if (book.take_answer(activity.answers_tick, offered_tick_, recent && answered.offered) && recent) {
        answer_round_trip_ns_ = std::max(answer_round_trip_ns_, activity.last_command_ns - answered.deadline_ns);
      }
    }
    book.close_overdue(offered_tick_, tick_count_, settings_.state_every_ticks);
    if (book.fell_below_minimum() || book.recovered()) {
      LoopEvent event;
      event.slot = static_cast<std::uint8_t>(s);
      event.generation = slot.generation;
      event.time_ns = now_ns;
      event.success_rate = book.counts().success_rate;
      if (book.recovered()) {
        event.type = LoopEvent::Type::kSuccessRateRecovered;
        post(event);
      } else if (slot.on_low_success_rate == LowRateAction::kFallback) {
        end_session(s, slot.timeout_behavior, LoopEvent::Type::kSessionRateTooLow, now_ns, 0);
      } else {
        event.type = LoopEvent::Type::kSuccessRateLow;
        post(event);
      }
    }
    book.end_tick();
  }
}

control::Gains ControlLoop::gains_for(std::size_t joint, const SlotRuntime* slot) const noexcept {
  control::Gains gains{model_.default_kp[joint], model_.default_kd[joint]};
  if (slot != nullptr) {
    if (!std::isnan(slot->default_kp[joint])) gains.kp = slot->default_kp[joint];
    if (!std::isnan(slot->default_kd[joint])) gains.kd = slot->default_kd[joint];
  }
  return gains;
}

// --- commands -------------------------------------------------------------------------------

void ControlLoop::take_commands() noexcept {
  if (const CommandSnapshot* fresh = channel_.commands.take()) commands_ = fresh;
}

void ControlLoop::apply_targets() noexcept {
  if (commands_ == nullptr) return;
  for (std::size_t j = 0; j < joint_count_; ++j) {
    const JointTarget& target = commands_->joints[j];
    JointOwner& owner = owners_[j];
    if (target.sequence == owner.applied_sequence) continue;
    if (owner.slot < 0 || target.generation != owner.generation) {
      // Written by a session that has ended (its generation started here before), or by one
      // whose start event this loop has not drained yet (the snapshot can be taken after this
      // tick drained the events); a later tick applies that one once the start has arrived.
      if (target.generation <= newest_started_generation_) drop_stale(owner, target);
      continue;
    }
    if (target.received_ns <= stale_before_ns_) {
      // Accepted before a safe state (e-stop, fault, maintenance, a lost link) ended: the
      // world it was meant for is gone. Only what the client sends from now on moves the joint.
      drop_stale(owner, target);
      continue;
    }
    owner.applied_sequence = target.sequence;
    apply_target(j, target, slots_[static_cast<std::uint8_t>(owner.slot)]);
    newest_sent_ns_ = std::max(newest_sent_ns_, target.sent_ns);
  }
}

void ControlLoop::drop_stale(JointOwner& owner, const JointTarget& target) noexcept {
  owner.applied_sequence = target.sequence;
  if (target.sequence != last_dropped_sequence_) {  // count each command once, not each joint
    last_dropped_sequence_ = target.sequence;
    channel_.dropped_stale.fetch_add(1, std::memory_order_relaxed);
  }
}

void ControlLoop::apply_target(std::size_t j, const JointTarget& target, const SlotRuntime& slot) noexcept {
  control::JointControl& joint = joints_[j];
  JointOwner& owner = owners_[j];
  const control::JointTargetUpdate& u = target.update;
  const control::Gains defaults = gains_for(j, &slot);

  if (slot.mode == ControlMode::kTorque) {
    joint.mode = JointMode::kTorque;
    joint.torque_nm = (u.fields & control::kHasTorque) != 0 ? u.torque : 0.0;
    return;
  }

  // POSITION or MIXED: a position target through the rate limiter.
  const std::int64_t stamp = target.sent_ns != 0 ? target.sent_ns : target.received_ns;
  const double position = u.position;
  double velocity = 0;
  std::int64_t interval = 0;
  if ((u.fields & control::kHasVelocity) != 0) {
    velocity = u.velocity;
    interval = owner.previous_target_time_ns != 0 ? stamp - owner.previous_target_time_ns : 0;
  } else if (owner.previous_target_time_ns != 0) {
    // No velocity given: estimate the stream's velocity from the last two targets, so a
    // low-rate stream is interpolated instead of stepped.
    interval = stamp - owner.previous_target_time_ns;
    constexpr std::int64_t kMaxStreamGapNs = 100'000'000;
    if (interval > 0 && interval <= kMaxStreamGapNs) {
      velocity = (position - owner.previous_target) / (static_cast<double>(interval) * 1e-9);
    }
  }
  owner.previous_target = position;
  owner.previous_target_time_ns = stamp;

  control::begin_tracking(joint, feedback_.joints[j], motion_limits_[j], dt_s_);
  joint.target_position = position;
  joint.target_velocity = control::clamp(velocity, -motion_limits_[j].velocity_max, motion_limits_[j].velocity_max);
  joint.target_time_ns = target.received_ns;
  joint.extrapolate_ns = std::clamp<std::int64_t>(interval, 0, 100'000'000);
  joint.kp = (u.fields & control::kHasKp) != 0 ? u.kp : defaults.kp;
  joint.kd = (u.fields & control::kHasKd) != 0 ? u.kd : defaults.kd;
  if (slot.mode == ControlMode::kMixed) {
    joint.track_kind = driver::JointCommandKind::kImpedance;
    joint.torque_nm = u.torque;
  } else {
    joint.track_kind = driver::JointCommandKind::kPosition;
    joint.torque_nm = 0;
  }
}

// --- safety ---------------------------------------------------------------------------------

void ControlLoop::update_estop(std::int64_t now_ns) noexcept {
  // A pressed e-stop input on the device engages robotd's e-stop as a client's request would;
  // it latches: releasing the button does not move anything until someone resets.
  const bool input_pressed = feedback_.estop_input;
  channel_.estop_input_pressed.store(input_pressed, std::memory_order_release);
  bool by_input = false;
  if (input_pressed && !channel_.estop.load(std::memory_order_acquire)) {
    channel_.estop.store(true, std::memory_order_release);
    by_input = true;
  }
  const bool engaged = channel_.estop.load(std::memory_order_acquire);
  if (engaged == estop_applied_) return;
  estop_applied_ = engaged;
  LoopEvent event;
  event.time_ns = now_ns;
  event.behavior = settings_.safe_behavior;
  event.by_estop_input = by_input;
  if (engaged) {
    enter_safe_state();
    event.type = LoopEvent::Type::kEstopApplied;
  } else {
    channel_.estop_reached_ns.store(0, std::memory_order_release);
    event.type = LoopEvent::Type::kEstopCleared;
  }
  post(event);
}

void ControlLoop::enter_safe_state() noexcept {
  if (safe_state_) return;
  for (std::size_t j = 0; j < joint_count_; ++j) {
    saved_modes_[j] = joints_[j].mode;
    saved_kd_[j] = joints_[j].kd;
    if (joints_[j].mode == JointMode::kIdle) continue;  // a joint nobody drives stays undriven
    // The safe behaviour with the joint's own gains: nothing a client set survives it.
    control::apply_behavior(joints_[j], settings_.safe_behavior, feedback_.joints[j], gains_for(j, nullptr),
                            motion_limits_[j], dt_s_);
  }
  safe_state_ = true;
}

void ControlLoop::leave_safe_state_if_clear(std::int64_t now_ns) noexcept {
  if (!safe_state_ || estop_applied_ || fault_latched_ || in_maintenance_ || reinit_pending_ || !have_feedback_) return;
  safe_state_ = false;
  stale_before_ns_ = now_ns;
  for (std::size_t j = 0; j < joint_count_; ++j) {
    control::JointControl& joint = joints_[j];
    switch (saved_modes_[j]) {
      // Never resume a stale target: whatever was tracking or applying torque now holds
      // where it is measured.
      case JointMode::kTrack:
      case JointMode::kTorque:
        control::hold_measured(joint, feedback_.joints[j], gains_for(j, nullptr));
        break;
      case JointMode::kDamping:
        joint.mode = JointMode::kDamping;
        joint.kd = saved_kd_[j];
        break;
      case JointMode::kZeroTorque:
        joint.mode = JointMode::kZeroTorque;
        break;
      case JointMode::kIdle:
        joint.mode = JointMode::kIdle;
        break;
    }
    owners_[j].previous_target_time_ns = 0;
  }
}

void ControlLoop::latch_io_fault(driver::IoResult result, std::int64_t now_ns) noexcept {
  const bool link_lost = result == driver::IoResult::kDisconnected;
  if (link_lost && io_fault_.code == 0) io_fault_.code = kFaultLinkLost;
  latch_fault(io_fault_, now_ns, link_lost);
}

void ControlLoop::latch_fault(const driver::FaultInfo& fault, std::int64_t now_ns, bool link_lost) noexcept {
  if (fault_latched_) return;
  fault_latched_ = true;
  link_lost_ = link_lost;
  fault_ = fault;
  enter_safe_state();
  LoopEvent event;
  event.type = LoopEvent::Type::kFaultLatched;
  event.time_ns = now_ns;
  event.fault = fault;
  event.behavior = settings_.safe_behavior;
  post(event);
  if (!channel_.black_box_frozen.exchange(true, std::memory_order_acq_rel)) {
    LoopEvent frozen;
    frozen.type = LoopEvent::Type::kBlackBoxFrozen;
    frozen.time_ns = now_ns;
    frozen.fault = fault;
    post(frozen);
  }
}

void ControlLoop::handle_maintenance(std::int64_t now_ns) noexcept {
  const bool requested = channel_.maintenance_requested.load(std::memory_order_acquire);
  // An e-stop or a shutdown pre-empts maintenance: it is not begun, and one that runs is
  // asked, on every tick, to give up, so the loop can reach the device again.
  const bool preempted = channel_.estop.load(std::memory_order_acquire) || shutdown_requested_ ||
                         channel_.shutdown_requested.load(std::memory_order_acquire);
  if (requested && !in_maintenance_) {
    if (preempted) {
      channel_.maintenance_declined.store(true, std::memory_order_release);
      return;
    }
    // Stop touching the driver and hand it to the maintenance thread.
    in_maintenance_ = true;
    enter_safe_state();
    channel_.maintenance_active.store(true, std::memory_order_release);
  } else if (requested && in_maintenance_ && preempted) {
    driver_.abort_maintenance();
  } else if (!requested && in_maintenance_) {
    in_maintenance_ = false;
    if (channel_.maintenance_clears_fault.exchange(false, std::memory_order_acq_rel)) {
      fault_latched_ = false;
      link_lost_ = false;
      fault_.clear();
    }
    have_feedback_ = false;
    reinit_pending_ = true;
    last_feedback_ns_ = now_ns;
    last_finite_ns_.fill(now_ns);
    measured_.fill(false);
    for (auto& joint : joints_) joint.setpoint_written = false;  // what was written before may mean nothing now
    channel_.maintenance_active.store(false, std::memory_order_release);
  }
}

void ControlLoop::read_feedback(std::int64_t now_ns) noexcept {
  const driver::IoResult result = driver_.read(read_buffer_, io_fault_);
  if (last_feedback_ns_ == 0) {
    last_feedback_ns_ = now_ns;
    last_finite_ns_.fill(now_ns);
  }
  if (result == driver::IoResult::kOk) {
    take_feedback(now_ns);
  } else if (is_link_problem(result)) {
    latch_io_fault(result, now_ns);
  }
  if (fault_latched_) return;
  if (now_ns - last_feedback_ns_ > settings_.feedback_timeout_ns) {
    driver::FaultInfo stale;
    char text[96];
    std::snprintf(text, sizeof(text), "no feedback from the driver for %lld ms",
                  static_cast<long long>((now_ns - last_feedback_ns_) / rt::kNsPerMs));
    stale.set(kFaultNoFeedback, text);
    latch_fault(stale, now_ns);
    return;
  }
  // Feedback arrives, but a joint's position or velocity has not been a number for too long.
  for (std::size_t j = 0; j < joint_count_; ++j) {
    if (now_ns - last_finite_ns_[j] <= settings_.feedback_timeout_ns) continue;
    driver::FaultInfo bad;
    char text[128];
    std::snprintf(text, sizeof(text), "joint '%s' has reported no finite position and velocity for %lld ms",
                  model_.joint_names[j].c_str(), static_cast<long long>((now_ns - last_finite_ns_[j]) / rt::kNsPerMs));
    bad.set(kFaultNonFiniteFeedback, text);
    latch_fault(bad, now_ns);
    return;
  }
}

void ControlLoop::take_feedback(std::int64_t now_ns) noexcept {
  // A non-finite position or velocity (a sensor glitch, a codec's "no value") never reaches a
  // setpoint: the joint keeps its last finite reading, for up to feedback_timeout (then the
  // device faults, read_feedback). Efforts pass as they are (robotd computes nothing from them).
  bool all_measured = true;
  for (std::size_t j = 0; j < joint_count_; ++j) {
    driver::JointFeedback& reading = read_buffer_.joints[j];
    const bool position_finite = std::isfinite(reading.position_rad);
    const bool velocity_finite = std::isfinite(reading.velocity_rad_s);
    if (!position_finite) reading.position_rad = feedback_.joints[j].position_rad;
    if (!velocity_finite) reading.velocity_rad_s = feedback_.joints[j].velocity_rad_s;
    if (position_finite && velocity_finite) {
      last_finite_ns_[j] = now_ns;
      measured_[j] = true;
    }
    all_measured = all_measured && measured_[j];
  }
  feedback_ = read_buffer_;
  feedback_.joint_count = joint_count_;
  last_feedback_ns_ = now_ns;
  // Until every joint has been measured there is nothing to hold or track from.
  if (!all_measured) return;
  have_feedback_ = true;
  if (reinit_pending_) {
    // The driver was out of the loop's hands: what a joint held before may mean something else
    // now (a reconnect, a new zero). Whatever tracks starts again from where it is measured.
    reinit_pending_ = false;
    for (std::size_t j = 0; j < joint_count_; ++j) {
      if (joints_[j].mode == JointMode::kTrack)
        control::hold_measured(joints_[j], feedback_.joints[j], gains_for(j, nullptr));
    }
  }
}

void ControlLoop::update_shutdown(std::int64_t now_ns) noexcept {
  if (!shutdown_requested_) shutdown_requested_ = channel_.shutdown_requested.load(std::memory_order_acquire);
  // The shutdown stop begins once maintenance has given the driver back.
  if (!shutdown_requested_ || in_maintenance_) return;
  if (!shutting_down_) {
    shutting_down_ = true;
    shutdown_started_ns_ = now_ns;
    for (std::size_t s = 0; s < slots_.size(); ++s) {
      if (slots_[s].active) {
        end_session(s, settings_.shutdown_behavior, LoopEvent::Type::kSessionEndedByShutdown, now_ns, 0);
      }
    }
    for (std::size_t j = 0; j < joint_count_; ++j) {
      if (joints_[j].mode != JointMode::kIdle) set_behavior(j, settings_.shutdown_behavior, gains_for(j, nullptr));
    }
  }
  if (now_ns - shutdown_started_ns_ >= settings_.shutdown_duration_ns) finished_.store(true, std::memory_order_release);
}

// --- output ---------------------------------------------------------------------------------

void ControlLoop::write_command(std::int64_t deadline_ns, std::int64_t now_ns) noexcept {
  // Nothing is commanded before the device has been measured, except the e-stop: that goes
  // out at once in every state, with every joint that would need a measured position to
  // hold left undriven.
  if (!have_feedback_ && !estop_applied_) return;
  frame_.tick = tick_count_;
  frame_.tick_deadline_ns = deadline_ns;
  frame_.estop = estop_applied_;
  frame_.newest_command_sent_ns = newest_sent_ns_;
  for (std::size_t j = 0; j < joint_count_; ++j) {
    if (!have_feedback_ && joints_[j].mode == JointMode::kTrack) {
      frame_.joints[j] = driver::JointCommand{};
      joints_[j].setpoint_written = false;
    } else {
      frame_.joints[j] = control::joint_output(joints_[j], feedback_.joints[j], motion_limits_[j], dt_s_, now_ns);
    }
    frame_.joints[j].owned = owners_[j].slot >= 0;
  }
  const driver::IoResult result = driver_.write(frame_, io_fault_);
  if (is_link_problem(result)) latch_io_fault(result, now_ns);
  // A device reporting a fault has still been handed the frame (driver.hpp); a lost link has not.
  if (result != driver::IoResult::kDisconnected && estop_applied_ &&
      channel_.estop_reached_ns.load(std::memory_order_relaxed) == 0) {
    channel_.estop_reached_ns.store(rt::monotonic_now_ns(), std::memory_order_release);
  }
}

DeviceState ControlLoop::current_state() const noexcept {
  if (finished_.load(std::memory_order_relaxed)) return DeviceState::kStopped;
  if (in_maintenance_) return DeviceState::kMaintenance;
  // A maintenance call that left the fault latched (a failed reconnect) leaves the device in
  // FAULT, not waiting for feedback that may never come.
  if (fault_latched_) return DeviceState::kFault;
  if (reinit_pending_) return DeviceState::kMaintenance;
  if (estop_applied_) return DeviceState::kEstop;
  if (!have_feedback_) return DeviceState::kConnecting;
  return DeviceState::kRunning;
}

void ControlLoop::publish(std::int64_t deadline_ns, std::int64_t now_ns) noexcept {
  const DeviceState state = current_state();
  channel_.device_state.store(state, std::memory_order_release);
  const bool due = tick_count_ % settings_.state_every_ticks == 0;
  // Closed-loop sessions answer the states of a running device (commands are refused otherwise).
  if (due && state == DeviceState::kRunning) {
    offered_tick_ = tick_count_;
    recent_ticks_[tick_count_ % recent_ticks_.size()].offered = true;
  }
  LoopState& out = channel_.state.write_buffer();
  out.tick = tick_count_;
  out.time_ns = now_ns;
  out.deadline_ns = deadline_ns;
  out.period_ns = period_ns_;
  out.state_due = due;
  out.state = state;
  out.estop = estop_applied_;
  out.fault = fault_;
  out.link_lost = link_lost_;
  out.feedback = feedback_;
  out.overruns = overruns_;
  out.rt_allocations = rt_allocations_;
  out.realtime = settings_.realtime;
  for (std::size_t s = 0; s < answers_.size(); ++s) out.answers[s] = answers_[s].counts();
  out.ready_ns = rt::monotonic_now_ns();
  if (due && settings_.state_every_ticks > 1) {
    channel_.due_state.write_buffer() = out;
    channel_.due_state.publish();
  }
  channel_.state.publish();
}

void ControlLoop::record_black_box(std::int64_t now_ns, std::int64_t wake_latency_ns) noexcept {
  if (channel_.black_box_freeze_requested.load(std::memory_order_acquire) &&
      !channel_.black_box_frozen.exchange(true, std::memory_order_acq_rel)) {
    LoopEvent frozen;
    frozen.type = LoopEvent::Type::kBlackBoxFrozen;
    frozen.time_ns = now_ns;
    post(frozen);
  }
  if (channel_.black_box_frozen.load(std::memory_order_acquire)) return;
  const std::uint64_t index = channel_.black_box_next.load(std::memory_order_relaxed);
  BlackBoxRecord& record = channel_.black_box[index % kBlackBoxTicks];
  record.tick = tick_count_;
  record.time_ns = now_ns;
  record.wake_latency_ns = wake_latency_ns;
  record.execution_ns = last_execution_ns_;
  record.state = current_state();
  record.joint_count = static_cast<std::uint8_t>(joint_count_);
  for (std::size_t j = 0; j < joint_count_; ++j) {
    record.joints[j] = BlackBoxJoint{
        static_cast<float>(feedback_.joints[j].position_rad), static_cast<float>(feedback_.joints[j].velocity_rad_s),
        static_cast<float>(frame_.joints[j].position_rad), static_cast<float>(frame_.joints[j].torque_nm),
        static_cast<std::uint8_t>(frame_.joints[j].kind)};
  }
  channel_.black_box_next.store(index + 1, std::memory_order_release);
}

void ControlLoop::post(const LoopEvent& event) noexcept {
  if (!channel_.loop_events.push(event)) channel_.lost_events.fetch_add(1, std::memory_order_relaxed);
}

}  // namespace robotd::device
