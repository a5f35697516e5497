// Servo mode: into it when a session streams, servo_j every servo period while it does, back to
// position mode when it ends; the e-stop's set_state(4) and the way back from it.
#include <algorithm>
#include <cmath>
#include <memory>

#include "driver/controller_link.hpp"
#include "driver/xarm_fault.hpp"

namespace robotd::xarm {
namespace {

constexpr auto kStepTimeout = std::chrono::milliseconds(2000);
constexpr auto kServoReplyTimeout = std::chrono::milliseconds(500);
/// The box must show servo mode and a state that moves within this after the replies.
constexpr auto kConfirmWait = std::chrono::milliseconds(1000);
/// At most this long for the arm to settle on the last servo_j before position mode resets it.
constexpr auto kLeaveWait = std::chrono::milliseconds(300);
/// servo_j frames whose replies are outstanding before the stream skips a period: the box or
/// the network is not keeping up, and queueing more only adds latency.
constexpr std::size_t kMaxServoInFlight = 4;
/// How often clean_err probes whether the box's e-stop button was released (robotd's e-stop on).
constexpr auto kEstopProbePeriod = std::chrono::milliseconds(500);
/// Steps stay this far inside the arm's joint speed limit (180 °/s; C24 beyond it).
constexpr double kStepMargin = 0.9;

bool moves(int state) { return state != kStateStopped && state != kStateReset; }

}  // namespace

std::string_view servo_phase_name(ServoPhase phase) {
  switch (phase) {
    case ServoPhase::kPosition:
      return "position mode";
    case ServoPhase::kEntering:
      return "entering servo mode";
    case ServoPhase::kServo:
      return "servo mode (streaming servo_j)";
    case ServoPhase::kLeaving:
      return "leaving servo mode";
  }
  return "?";
}

void ControllerLink::drive_servo(Clock::time_point now) {
  // Never wait for the RT thread's store: with io_priority at or above the loop's (or a loop
  // without SCHED_FIFO) the writer may not get the CPU back while this thread waits. A store in
  // progress means the previous target, one servo period longer.
  (void)target_.try_load(target_read_);
  const StreamTarget target = target_read_;
  follow_estop(target, now);
  if (target.estop) return;
  switch (phase_) {
    case ServoPhase::kPosition:
      if (target.active && codes_.error == 0 && servo_fault_.code == 0) enter_servo(now);
      return;
    case ServoPhase::kEntering:
      if (confirm_after_ == 0) return;  // replies still awaited
      if (latest_.sequence > confirm_after_ + 1 && latest_.mode == kModeServo && moves(latest_.state)) {
        phase_ = ServoPhase::kServo;
        last_sent_ = latest_.position_rad;
        next_servo_at_ = now;
        last_servo_at_ = {};
        leave_requested_at_ = {};
      } else if (now > confirm_deadline_) {
        refuse_servo("the arm stayed " + motion_state_text(latest_.state) + " in " + mode_text(latest_.mode) +
                     " mode after set_mode(1) and set_state(0)" +
                     (settings_.enable_for_servo ? "" : " (enable is manual: call motion_en first)"));
      }
      return;
    case ServoPhase::kServo:
      if (target.active) {
        leave_requested_at_ = {};
        if (codes_.error == 0 && servo_fault_.code == 0) stream(target, now);
        return;
      }
      if (leave_requested_at_ == Clock::time_point{}) leave_requested_at_ = now;
      if (at_rest() || now - leave_requested_at_ > kLeaveWait) leave_servo(now);
      return;
    case ServoPhase::kLeaving:
      return;
  }
}

void ControllerLink::follow_estop(const StreamTarget& target, Clock::time_point now) {
  if (target.estop && is_estop_error(codes_.error) && now >= next_estop_probe_at_) {
    // The box latches its e-stop errors past the button's release; robotd's own e-stop holds the
    // arm meanwhile, so trying clean_err is how the driver learns the button is out again.
    next_estop_probe_at_ = now + kEstopProbePeriod;
    send(plain_request(Register::kCleanErr), now, kStepTimeout, [](const Result<Reply>&) {});
  }
  if (target.estop && !estop_sent_) {
    estop_sent_ = true;
    ++generation_;  // replies to a mode change in flight no longer decide anything
    phase_ = ServoPhase::kPosition;
    send(set_state_request(kStateStopped), now, kStepTimeout, [](const Result<Reply>&) {});
    return;
  }
  if (!target.estop && estop_sent_) {
    // robotd's e-stop was reset: out of STOPPED. A session still streaming re-enters servo mode.
    estop_sent_ = false;
    if (!target.active) leave_servo(now);
  }
}

void ControllerLink::enter_servo(Clock::time_point now) {
  std::vector<Request> steps;
  if (settings_.enable_for_servo) steps.push_back(motion_enable_request(8, true));
  steps.push_back(set_mode_request(kModeServo));
  steps.push_back(set_state_request(kStateStart));
  phase_ = ServoPhase::kEntering;
  confirm_after_ = 0;
  ++link_counters_.servo_entries;
  const std::uint64_t generation = ++generation_;
  send_sequence(steps, now, [this, generation](bool ok, const std::string& why) {
    if (generation != generation_) return;
    if (!ok) {
      refuse_servo(why);
      return;
    }
    confirm_after_ = std::max<std::uint64_t>(latest_.sequence, 1);
    confirm_deadline_ = Clock::now() + kConfirmWait;
  });
}

void ControllerLink::refuse_servo(const std::string& why) {
  phase_ = ServoPhase::kPosition;
  servo_fault_.set(kServoRefusedFault, ("servo mode refused: " + why).c_str());
  latest_.fault = arm_fault(codes_.error, servo_fault_);
  feedback_.store(latest_);
}

void ControllerLink::leave_servo(Clock::time_point now) {
  phase_ = ServoPhase::kLeaving;
  const std::uint64_t generation = ++generation_;
  send_sequence({set_mode_request(kModePosition), set_state_request(kStateStart)}, now,
                [this, generation](bool /*ok*/, const std::string& /*why*/) {
                  if (generation == generation_) phase_ = ServoPhase::kPosition;
                });
}

void ControllerLink::send_sequence(const std::vector<Request>& requests, Clock::time_point now,
                                   std::function<void(bool ok, const std::string& why)> done) {
  struct Progress {
    std::size_t remaining = 0;
    bool ok = true;
    std::string why;
    std::function<void(bool, const std::string&)> done;
  };
  auto progress = std::make_shared<Progress>();
  progress->remaining = requests.size();
  progress->done = std::move(done);
  for (const Request& request : requests) {
    send(request, now, kStepTimeout, [progress, reg = request.reg](Result<Reply> reply) {
      if (progress->ok && !reply) {
        progress->ok = false;
        progress->why = reply.error().message;
      } else if (progress->ok && reply.value().status.invalid) {
        progress->ok = false;
        progress->why = "the control box refused " + register_name(reg) + " as invalid";
      }
      if (--progress->remaining == 0) progress->done(progress->ok, progress->why);
    });
  }
}

void ControllerLink::stream(const StreamTarget& target, Clock::time_point now) {
  if (now < next_servo_at_) return;
  next_servo_at_ += settings_.servo_period;
  if (next_servo_at_ <= now) next_servo_at_ = now + settings_.servo_period;  // late: skip, do not burst
  if (transactions_.in_flight(static_cast<std::uint8_t>(Register::kServoJ)) >= kMaxServoInFlight) {
    ++link_counters_.skipped_frames;
    return;
  }
  const double period_s = std::chrono::duration<double>(settings_.servo_period).count();
  const double max_step = kStepMargin * kMaxJointSpeedRadS * period_s;
  bool clipped = false;
  for (std::size_t j = 0; j < settings_.dof; ++j) {
    const double wanted = target.joints_rad[j] - last_sent_[j];
    const double step = std::clamp(wanted, -max_step, max_step);
    clipped = clipped || step != wanted;
    last_sent_[j] += step;
  }
  send(servo_j_request(last_sent_), now, kServoReplyTimeout, [](const Result<Reply>&) {});
  ++link_counters_.servo_frames;
  if (clipped) ++link_counters_.clipped_frames;
  if (last_servo_at_ != Clock::time_point{}) {
    const auto interval = std::chrono::duration_cast<std::chrono::nanoseconds>(now - last_servo_at_).count();
    link_counters_.servo_interval_max_ns = std::max(link_counters_.servo_interval_max_ns, interval);
  }
  last_servo_at_ = now;
}

bool ControllerLink::at_rest() const {
  constexpr double kAtTargetRad = 2e-3;
  constexpr double kAtRestRadS = 0.01;
  for (std::size_t j = 0; j < settings_.dof; ++j) {
    if (std::fabs(latest_.velocity_rad_s[j]) > kAtRestRadS) return false;
    if (std::fabs(last_sent_[j] - latest_.position_rad[j]) > kAtTargetRad) return false;
  }
  return true;
}

}  // namespace robotd::xarm
