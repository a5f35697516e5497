#include "loop_rig.hpp"

#include <cmath>

#include "control/behavior_map.hpp"
#include "control/limit_narrowing.hpp"
#include "device/command_admission.hpp"
#include "service/session_events.hpp"

namespace robotd::safety {
namespace {

// The maintenance thread of Device::run_maintenance, one step per tick: ask the loop to let go
// of the driver, run the work for as long as the scenario says (or until the loop aborts it),
// hand the driver back.
class MaintenanceThread {
 public:
  MaintenanceThread(device::DeviceChannel& channel, PlantDriver& plant) : channel_(channel), plant_(plant) {}

  bool busy() const { return phase_ != Phase::kIdle; }

  void request(const Event& event) {
    channel_.maintenance_requested.store(true);
    phase_ = Phase::kRequested;
    reset_zero_ = event.kind == Event::Kind::kResetZero;
    ticks_ = event.count;
    fail_ = event.fail;
  }

  /// After each tick: what the thread does once the loop has acted.
  void step() {
    switch (phase_) {
      case Phase::kIdle:
        return;
      case Phase::kRequested:
        if (channel_.maintenance_declined.exchange(false)) {  // an e-stop or shutdown is pending
          channel_.maintenance_requested.store(false);
          phase_ = Phase::kIdle;
        } else if (channel_.maintenance_active.load()) {
          phase_ = Phase::kWorking;
          plant_.abort_requested.store(false);  // recover() and reset_zero() clear the request when they start
        }
        return;
      case Phase::kWorking:
        if (plant_.abort_requested) {
          finish(false);
        } else if (--ticks_ <= 0) {
          bool ok = !fail_;
          if (ok && reset_zero_) {
            std::vector<int> joints(driver::kMaxJoints);
            for (std::size_t j = 0; j < joints.size(); ++j) joints[j] = static_cast<int>(j);
            ok = plant_.reset_zero(joints).ok();
          } else if (ok) {
            ok = plant_.recover().ok();
          }
          finish(ok);
        }
        return;
      case Phase::kEnding:
        if (!channel_.maintenance_active.load()) phase_ = Phase::kIdle;
        return;
    }
  }

 private:
  enum class Phase { kIdle, kRequested, kWorking, kEnding };

  void finish(bool ok) {
    channel_.maintenance_clears_fault.store(ok && !reset_zero_);
    channel_.maintenance_requested.store(false);
    phase_ = Phase::kEnding;
  }

  device::DeviceChannel& channel_;
  PlantDriver& plant_;
  Phase phase_ = Phase::kIdle;
  bool reset_zero_ = false;
  int ticks_ = 0;
  bool fail_ = false;
};

class LoopRig {
 public:
  LoopRig(const Scenario& scenario, std::FILE* trace)
      : trace_(trace),
        spec_(scenario.device),
        model_(spec_.model()),
        plant_(spec_),
        sessions_({&model_}, session::SessionLimits{}),
        mailbox_(*channel_),
        maintenance_(*channel_, plant_),
        checker_(spec_, settings()) {
    loop_ = std::make_unique<device::ControlLoop>(plant_, model_, *channel_, settings());
  }

  RunResult run(const std::vector<Event>& events) {
    RunResult result;
    for (const Event& event : events) {
      ++result.events_run;
      if (loop_->finished()) break;
      if (trace_ != nullptr && event.kind != Event::Kind::kTick) std::fprintf(trace_, "  %s\n", to_text(event).c_str());
      result.violation = apply(event);
      if (result.violation) break;
    }
    result.ticks = tick_;
    result.commands_accepted = accepted_;
    result.commands_rejected = rejected_;
    result.commands_unknown_session = rejected_unknown_;
    result.sessions_granted = granted_;
    result.sessions_ended_for_rate = ended_for_rate_;
    result.rate_warnings = rate_warnings_;
    result.ticks_in_state = ticks_in_state_;
    return result;
  }

 private:
  device::LoopSettings settings() const {
    device::LoopSettings settings;
    settings.rate_hz = 1000;
    settings.feedback_timeout_ns = static_cast<std::int64_t>(spec_.feedback_timeout_ms) * kMsNs;
    settings.safe_behavior = control::applied_behavior(spec_.safe, model_.behaviors);
    settings.shutdown_behavior = control::applied_behavior(spec_.shutdown, model_.behaviors);
    settings.shutdown_duration_ns = static_cast<std::int64_t>(spec_.shutdown_ms) * kMsNs;
    settings.warmup_ticks = 1'000'000'000;
    return settings;
  }

  std::optional<Violation> apply(const Event& event) {
    switch (event.kind) {
      case Event::Kind::kTick:
        for (int i = 0; i < event.count && !loop_->finished(); ++i) {
          if (auto broken = tick(event.latency_us)) return broken;
        }
        return std::nullopt;
      case Event::Kind::kStart:
        start(event);
        return std::nullopt;
      case Event::Kind::kRelease:
        release(event);
        return std::nullopt;
      case Event::Kind::kCommand:
      case Event::Kind::kKeepalive:
        command(event);
        return std::nullopt;
      case Event::Kind::kEstop:
        // The e-stop service: engage at once; a reset is refused while the button is pressed.
        if (event.on) {
          channel_->estop.store(true);
          checker_.on_estop(true);
        } else if (!channel_->estop_input_pressed.load()) {
          channel_->estop.store(false);
          checker_.on_estop(false);
        }
        return std::nullopt;
      case Event::Kind::kEstopInput:
        plant_.estop_input = event.on;
        return std::nullopt;
      case Event::Kind::kFault:
        plant_.fault_code = event.code;
        return std::nullopt;
      case Event::Kind::kLink:
        plant_.link_up = event.on;
        return std::nullopt;
      case Event::Kind::kSilence:
        plant_.silent = event.on;
        return std::nullopt;
      case Event::Kind::kNonFinite:
        if (event.joint < spec_.joints)
          plant_.non_finite[event.joint][static_cast<std::size_t>(event.field)] = event.on;
        return std::nullopt;
      case Event::Kind::kTeleport:
        if (event.joint < spec_.joints) plant_.teleport(event.joint, event.value);
        return std::nullopt;
      case Event::Kind::kNarrow:
        if (event.joint < spec_.joints) narrow(event);
        return std::nullopt;
      case Event::Kind::kRecover:
      case Event::Kind::kResetZero:
        maintain(event);
        return std::nullopt;
      case Event::Kind::kShutdown:
        channel_->shutdown_requested.store(true);
        checker_.on_shutdown_requested();
        return std::nullopt;
    }
    return std::nullopt;
  }

  std::optional<Violation> tick(int latency_us) {
    // As ControlLoop::run: the next deadline, or the first one still ahead after a late tick.
    deadline_ns_ += kPeriodNs;
    if (now_ns_ > deadline_ns_) deadline_ns_ += ((now_ns_ - deadline_ns_) / kPeriodNs + 1) * kPeriodNs;
    now_ns_ = deadline_ns_ + static_cast<std::int64_t>(latency_us) * 1000;
    commands_since_tick_ = 0;
    ++tick_;
    plant_.begin_tick();
    loop_->tick(deadline_ns_, now_ns_);

    events_.clear();
    while (auto event = channel_->loop_events.pop()) events_.push_back(*event);
    const device::LoopState* published = channel_->state.take();
    if (published != nullptr) state_ = *published;
    ++ticks_in_state_[static_cast<std::size_t>(state_.state) % ticks_in_state_.size()];

    TickObservation observation;
    observation.tick = tick_;
    observation.now_ns = now_ns_;
    observation.read_result = plant_.read_called ? plant_.read_result : driver::IoResult::kNoNewData;
    observation.read = plant_.read_ok ? &plant_.read_feedback : nullptr;
    observation.wrote = plant_.wrote;
    observation.frame = &plant_.frame;
    observation.write_failed = plant_.wrote && !plant_.link_up;
    observation.state = &state_;
    observation.events = &events_;
    auto broken = checker_.check(observation);
    if (trace_ != nullptr) write_trace(observation);

    // The service side learns what the loop did (the publisher thread's job in robotd).
    for (const device::LoopEvent& event : events_) {
      if (device::ends_session(event.type)) {
        (void)sessions_.end(0, event.slot, event.generation);
      }
      if (event.type == device::LoopEvent::Type::kSessionRateTooLow) ++ended_for_rate_;
      if (event.type == device::LoopEvent::Type::kSuccessRateLow) ++rate_warnings_;
    }
    maintenance_.step();
    plant_.advance(1e-9 * static_cast<double>(kPeriodNs));
    return broken;
  }

  void write_trace(const TickObservation& tick) const {
    std::fprintf(trace_, "tick %llu t=%.6f %s%s%s", static_cast<unsigned long long>(tick.tick),
                 static_cast<double>(tick.now_ns) * 1e-9, std::string(to_string(tick.state->state)).c_str(),
                 tick.wrote ? "" : " (no write)", tick.wrote && tick.frame->estop ? " ESTOP-FRAME" : "");
    for (const auto& event : *tick.events) {
      std::fprintf(trace_, " [event %d gen %u]", static_cast<int>(event.type), event.generation);
    }
    std::fprintf(trace_, "\n");
    for (std::size_t j = 0; j < spec_.joints; ++j) {
      const driver::JointCommand& c = tick.frame->joints[j];
      const double q = tick.read != nullptr ? tick.read->joints[j].position_rad : NAN;
      std::fprintf(trace_, "    j%zu q=%.9g | kind=%d p=%.12g v=%.9g kp=%.6g kd=%.6g tau=%.6g%s\n", j, q,
                   static_cast<int>(c.kind), c.position_rad, c.velocity_rad_s, c.kp, c.kd, c.torque_nm,
                   c.owned ? " owned" : "");
    }
  }

  std::int64_t between_ticks_ns() { return now_ns_ + static_cast<std::int64_t>(++commands_since_tick_) * 1000; }

  void start(const Event& event) {
    // SessionService::request_control: only a RUNNING device grants.
    if (channel_->device_state.load() != DeviceState::kRunning) return;
    RequestControlRequest request;
    request.node_name = "client" + std::to_string(event.label);
    for (std::size_t j = 0; j < spec_.joints; ++j) {
      if ((event.motors >> j & 1U) != 0) request.motor_ids.push_back(static_cast<std::int32_t>(j));
    }
    request.control_mode = event.mode;
    request.default_behavior = event.behavior;
    request.timeout_ms = event.timeout_ms;
    request.min_command_success_rate = static_cast<float>(event.min_rate);
    request.on_low_success_rate = event.on_low;
    const std::size_t motor_count = request.motor_ids.empty() ? spec_.joints : request.motor_ids.size();
    if (event.default_kp >= 0) request.default_kp.assign(motor_count, static_cast<float>(event.default_kp));
    if (event.default_kd >= 0) request.default_kd.assign(motor_count, static_cast<float>(event.default_kd));
    const std::string uuid = "uuid-" + std::to_string(event.label) + "-" + std::to_string(tick_);
    auto granted = sessions_.grant(request, uuid, "id-" + std::to_string(event.label), between_ticks_ns(), 0);
    if (!granted) return;
    const session::SessionRecord& record = granted.value();
    if (!channel_->post(service::session_start_event(record))) {
      (void)sessions_.release(record.uuid);
      return;
    }
    ++granted_;
    checker_.on_start_posted(record);
    ClientSession& client = clients_[event.label];
    client.label = event.label;
    client.uuid = record.uuid;
    client.mode = record.mode;
    client.motors = record.motors.to_ullong();
  }

  void release(const Event& event) {
    const auto client = clients_.find(event.label);
    if (client == clients_.end()) return;
    auto released = sessions_.release(client->second.uuid);
    if (!released) return;
    const session::SessionRecord& record = released.value();
    const Behavior applied = control::applied_behavior(event.behavior, model_.behaviors);
    if (channel_->post(service::session_release_event(record, applied))) {
      checker_.on_release_posted(record.slot, record.generation, applied);
    }
  }

  void command(const Event& event) {
    ClientSession client;
    if (const auto known = clients_.find(event.label); known != clients_.end()) client = known->second;
    if (client.uuid.empty()) client.uuid = "never-granted-" + std::to_string(event.label);
    const std::int64_t received_ns = between_ticks_ns();
    ControlCommand command = event.kind == Event::Kind::kKeepalive
                                 ? ControlCommand{}
                                 : client_command(client, event.seed, spec_, received_ns);
    command.uuid = client.uuid;
    // The mailbox takes whatever the command names, a tick not run yet too: the command gate
    // refuses those in robotd (the service layer), the loop must not count them before they run.
    command.answers_tick = answered_tick(event, state_.tick);

    // CommandIntake::handle: the session, then the device's state, then the validator.
    const session::SessionRecord* record = sessions_.find(command.uuid);
    if (record == nullptr || device::command_refusal(*channel_)) {
      ++rejected_;
      if (record == nullptr) ++rejected_unknown_;
      return;
    }
    const control::SessionView view{model_.name, record->mode, record->motors};
    const control::Verdict verdict = control::validate_command(command, view, model_, limits_, validated_);
    if (verdict.rejection) {
      ++rejected_;
      return;
    }
    mailbox_.post(record->slot, record->generation, validated_, received_ns, command.sent_steady_ns,
                  command.answers_tick);
    checker_.on_command_accepted(record->generation, validated_, received_ns, command.answers_tick);
    ++accepted_;
  }

  void maintain(const Event& event) {
    if (maintenance_.busy()) return;  // Device::run_maintenance runs one at a time
    if (event.kind == Event::Kind::kResetZero) {
      // DeviceServices::reset_zero: refused while a session is active or the device is not RUNNING.
      if (sessions_.any_active(0) || channel_->device_state.load() != DeviceState::kRunning) return;
    }
    maintenance_.request(event);
    checker_.on_maintenance_requested();
  }

  // Device::narrow_limits: the driver's new description narrows the limits, handed to the loop.
  void narrow(const Event& event) {
    plant_.narrow(event.joint, event.value);
    std::vector<driver::JointLimits> reported;
    for (const auto& joint : plant_.describe().joints) reported.push_back(joint.limits);
    if (!control::narrow_limits(limits_, reported, model_.joint_names)) return;
    device::LimitSet& out = channel_->limits.write_buffer();
    for (std::size_t j = 0; j < limits_.size(); ++j) out.joints[j] = device::motion_limits(limits_[j]);
    channel_->limits.publish();
    checker_.on_limits_narrowed(limits_);
  }

  std::FILE* trace_;
  DeviceSpec spec_;
  control::DeviceModel model_;
  std::vector<driver::JointLimits> limits_ = model_.limits;  // the device's limits now
  PlantDriver plant_;
  std::unique_ptr<device::DeviceChannel> channel_ = std::make_unique<device::DeviceChannel>();
  session::SessionTable sessions_;
  device::CommandMailbox mailbox_;
  MaintenanceThread maintenance_;
  InvariantChecker checker_;
  std::unique_ptr<device::ControlLoop> loop_;

  std::map<int, ClientSession> clients_;
  control::ValidatedCommand validated_;
  device::LoopState state_;
  std::vector<device::LoopEvent> events_;
  std::int64_t deadline_ns_ = 1'000 * kMsNs;
  std::int64_t now_ns_ = 1'000 * kMsNs;
  int commands_since_tick_ = 0;
  std::uint64_t tick_ = 0;
  std::uint64_t accepted_ = 0;
  std::uint64_t rejected_ = 0;
  std::uint64_t rejected_unknown_ = 0;
  std::uint64_t granted_ = 0;
  std::uint64_t ended_for_rate_ = 0;
  std::uint64_t rate_warnings_ = 0;
  std::array<std::uint64_t, 7> ticks_in_state_{};
};

}  // namespace

RunResult run_scenario(const Scenario& scenario, std::FILE* trace) {
  auto rig = std::make_unique<LoopRig>(scenario, trace);
  return rig->run(scenario.events);
}

}  // namespace robotd::safety
