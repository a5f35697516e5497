#include "service_rig.hpp"

#include <array>
#include <atomic>
#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <thread>

#include "client_commands.hpp"
#include "control/behavior_map.hpp"
#include "dds/command_gate.hpp"
#include "device/black_box.hpp"
#include "device/device.hpp"
#include "invariant_checker.hpp"
#include "plant_driver.hpp"
#include "plugin/plugin_loader.hpp"
#include "service/device_observer.hpp"
#include "service/device_services.hpp"
#include "service/session_service.hpp"

namespace robotd::safety {
namespace {

constexpr auto kHandOffWait = std::chrono::seconds(5);  // a service thread's step, however loaded the machine

// The sessions' clock follows the rig's simulated time (one rig runs at a time).
std::atomic<std::int64_t> simulated_ns{0};
std::int64_t simulated_now_ns() noexcept { return simulated_ns.load(); }

// What the state publisher tells the services in robotd: the loop's latest state.
class LatestState final : public service::DeviceObserver {
 public:
  device::LoopState latest() const override {
    const std::lock_guard lock(mutex_);
    return state_;
  }
  nlohmann::json loop_timing(bool /*samples*/, bool /*reset*/) override { return nlohmann::json::object(); }
  void set(const device::LoopState& state) {
    const std::lock_guard lock(mutex_);
    state_ = state;
  }

 private:
  mutable std::mutex mutex_;
  device::LoopState state_;
};

// A service call on a thread of its own, as robotd's service workers run them.
class ServiceCall {
 public:
  explicit ServiceCall(std::function<bool()> work)
      : thread_([this, work = std::move(work)] {
          succeeded_.store(work());
          done_.store(true);
        }) {}
  ServiceCall(const ServiceCall&) = delete;
  ServiceCall& operator=(const ServiceCall&) = delete;
  ~ServiceCall() { thread_.join(); }

  bool done() const { return done_.load(); }
  bool succeeded() const { return succeeded_.load(); }

 private:
  std::atomic<bool> done_{false};
  std::atomic<bool> succeeded_{false};
  std::thread thread_;  // last: it starts once the flags exist
};

// Waits (real time, bounded) until `ready`; false if it never was.
template <class Ready>
bool wait_until(Ready ready) {
  const auto deadline = std::chrono::steady_clock::now() + kHandOffWait;
  while (!ready()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::microseconds(50));
  }
  return true;
}

class ServiceRig {
 public:
  ServiceRig(const Scenario& scenario, std::FILE* trace) : trace_(trace), spec_(scenario.device) {
    auto plant = std::make_unique<PlantDriver>(spec_);
    plant_ = plant.get();
    config::DeviceConfig config;
    config.path = "devices[0]";
    config.name = "dev";
    config.driver = "plant";
    config.realtime = rt::RealtimePolicy::kOff;
    config.limit_policy = spec_.policy;
    config.safe_behavior = spec_.safe;
    config.shutdown_behavior = spec_.shutdown;
    config.shutdown_ms = spec_.shutdown_ms;
    config.feedback_timeout_ms = spec_.feedback_timeout_ms;
    config.reconnect_interval_ms = 0;
    device_ = std::make_unique<device::Device>(config, plugin::LoadedDriver::built_in(std::move(plant), "plant"));
    configured_ = device_->configure();
    if (configured_) configured_ = device_->start(device::Device::LoopRunner::kCaller);
    sessions_ = std::make_unique<service::SessionService>(
        std::vector<device::Device*>{device_.get()}, session::SessionLimits{}, [] {}, &simulated_now_ns);
    gate_ = std::make_unique<dds::CommandGate>(std::vector<device::Device*>{device_.get()}, *sessions_, surface_);
    black_box_ = std::make_unique<device::BlackBox>(device_->channel(), device_->model());
    services_ = std::make_unique<service::DeviceServices>(
        std::vector<device::Device*>{device_.get()}, std::vector<device::BlackBox*>{black_box_.get()},
        std::vector<service::DeviceObserver*>{&observer_}, *sessions_);
    device::LoopSettings settings;
    settings.safe_behavior = control::applied_behavior(spec_.safe, device_->model().behaviors);
    settings.shutdown_behavior = control::applied_behavior(spec_.shutdown, device_->model().behaviors);
    settings.shutdown_duration_ns = static_cast<std::int64_t>(spec_.shutdown_ms) * kMsNs;
    checker_ = std::make_unique<InvariantChecker>(spec_, settings);
  }

  ~ServiceRig() {
    // Let every service call finish before the services go away: a recover or reset_zero waits
    // for the device to run again, so clear what keeps it from running and tick on.
    plant_->fault_code = 0;
    plant_->link_up = true;
    plant_->silent = false;
    plant_->estop_input = false;
    plant_->non_finite = {};
    device_->channel().estop.store(false);
    for (int i = 0; i < 20'000 && !all_calls_done() && device_->running(); ++i) (void)tick(0);
    if (device_->running()) device_->request_stop();
    while (device_->running()) (void)tick(0);
    maintenance_.reset();
    calls_.clear();
  }

  RunResult run(const std::vector<Event>& events) {
    RunResult result;
    if (!configured_) {
      result.violation = Violation{"setup", "the device did not start: " + configured_.error().message, 0};
      return result;
    }
    for (const Event& event : events) {
      ++result.events_run;
      if (!device_->running()) break;
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
  std::optional<Violation> apply(const Event& event) {
    switch (event.kind) {
      case Event::Kind::kTick:
        for (int i = 0; i < event.count && device_->running(); ++i) {
          if (auto broken = tick(event.latency_us)) return broken;
        }
        return std::nullopt;
      case Event::Kind::kStart:
        return start(event);
      case Event::Kind::kRelease:
        release(event);
        return std::nullopt;
      case Event::Kind::kCommand:
      case Event::Kind::kKeepalive:
        return command(event);
      case Event::Kind::kEstop:
        estop(event.on);
        return std::nullopt;
      case Event::Kind::kEstopInput:
        plant_->estop_input = event.on;
        return std::nullopt;
      case Event::Kind::kFault:
        plant_->fault_code = event.code;
        return std::nullopt;
      case Event::Kind::kLink:
        plant_->link_up = event.on;
        return std::nullopt;
      case Event::Kind::kSilence:
        plant_->silent = event.on;
        return std::nullopt;
      case Event::Kind::kNonFinite:
        if (event.joint < spec_.joints)
          plant_->non_finite[event.joint][static_cast<std::size_t>(event.field)] = event.on;
        return std::nullopt;
      case Event::Kind::kTeleport:
        if (event.joint < spec_.joints) plant_->teleport(event.joint, event.value);
        return std::nullopt;
      case Event::Kind::kNarrow:
        // What robotd does after a device op (and after a reconnect): take what the driver describes.
        if (event.joint < spec_.joints) {
          plant_->narrow(event.joint, event.value);
          device_->narrow_to_described();
          checker_->on_limits_narrowed(*device_->limits());
        }
        return std::nullopt;
      case Event::Kind::kRecover:
      case Event::Kind::kResetZero:
        return maintain(event);
      case Event::Kind::kShutdown:
        device_->request_stop();
        checker_->on_shutdown_requested();
        return std::nullopt;
    }
    return std::nullopt;
  }

  std::optional<Violation> tick(int latency_us) {
    deadline_ns_ += kPeriodNs;
    if (now_ns_ > deadline_ns_) deadline_ns_ += ((now_ns_ - deadline_ns_) / kPeriodNs + 1) * kPeriodNs;
    now_ns_ = deadline_ns_ + static_cast<std::int64_t>(latency_us) * 1000;
    simulated_ns.store(now_ns_);
    commands_since_tick_ = 0;
    ++tick_;
    plant_->begin_tick();
    device_->tick(deadline_ns_, now_ns_);

    device::DeviceChannel& channel = device_->channel();
    events_.clear();
    while (auto event = channel.loop_events.pop()) events_.push_back(*event);
    if (const device::LoopState* published = channel.state.take()) state_ = *published;
    observer_.set(state_);
    ++ticks_in_state_[static_cast<std::size_t>(state_.state) % ticks_in_state_.size()];

    TickObservation observation;
    observation.tick = tick_;
    observation.now_ns = now_ns_;
    observation.read_result = plant_->read_called ? plant_->read_result : driver::IoResult::kNoNewData;
    observation.read = plant_->read_ok ? &plant_->read_feedback : nullptr;
    observation.wrote = plant_->wrote;
    observation.frame = &plant_->frame;
    observation.write_failed = plant_->wrote && !plant_->link_up;
    observation.state = &state_;
    observation.events = &events_;
    auto broken = checker_->check(observation);
    if (trace_ != nullptr) {
      std::fprintf(trace_, "tick %llu %s%s\n", static_cast<unsigned long long>(tick_),
                   std::string(to_string(state_.state)).c_str(),
                   plant_->wrote && plant_->frame.estop ? " ESTOP-FRAME" : "");
    }

    // The state publisher's job in robotd: sessions the loop ended leave the session table.
    for (const device::LoopEvent& event : events_) {
      if (device::ends_session(event.type)) {
        (void)sessions_->session_ended(0, event.slot, event.generation);
      }
      if (event.type == device::LoopEvent::Type::kSessionRateTooLow) ++ended_for_rate_;
      if (event.type == device::LoopEvent::Type::kSuccessRateLow) ++rate_warnings_;
    }
    plant_->advance(1e-9 * static_cast<double>(kPeriodNs));
    if (!broken) broken = settle_maintenance();
    return broken;
  }

  // After a tick, lets a maintenance call reach the next point the loop or the sessions can
  // see, so that the next tick finds it there whatever the machine's speed.
  std::optional<Violation> settle_maintenance() {
    if (!maintenance_) return std::nullopt;
    device::DeviceChannel& channel = device_->channel();
    bool reached = true;
    if (channel.maintenance_requested.load()) {
      // Declined by the loop, or its work released (done, failed, aborted): the call hands the
      // driver back. Otherwise, once the loop has let go, the work is running.
      if (channel.maintenance_declined.load() || plant_->maintenance_released()) {
        reached = wait_until([&] { return !channel.maintenance_requested.load() || maintenance_->done(); });
      } else if (channel.maintenance_active.load()) {
        reached = wait_until([&] { return plant_->in_maintenance_work() || !channel.maintenance_requested.load(); });
      }
    } else if (!channel.maintenance_active.load()) {
      // Handed back and taken back: the call ends its hold on the device and the device is free
      // for the next maintenance (the call may still be waiting to see it run, to reply).
      reached = wait_until([&] { return sessions_->maintenance_operation(0).empty() || maintenance_->done(); });
      maintenance_window_ = false;
      calls_.push_back(std::move(maintenance_));
      maintenance_.reset();
    }
    if (!reached) return Violation{"rig", "a maintenance call did not reach its next step in time", tick_};
    return std::nullopt;
  }

  std::int64_t between_ticks_ns() {
    const std::int64_t at = now_ns_ + static_cast<std::int64_t>(++commands_since_tick_) * 1000;
    simulated_ns.store(at);
    return at;
  }

  std::optional<Violation> start(const Event& event) {
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
    const std::int64_t granted_ns = between_ticks_ns();
    const RequestControlResponse response = sessions_->request_control(request);
    if (!response.success) return std::nullopt;
    ++granted_;
    if (maintenance_window_) {
      return Violation{"S1 maintenance holds the device",
                       "request_control was granted while " + maintenance_op_ + " had the device", tick_};
    }
    const auto granted = sessions_->authorize(response.uuid);
    session::SessionRecord record;
    record.uuid = response.uuid;
    record.slot = granted->slot;
    record.generation = granted->generation;
    record.motors = granted->motors;
    record.motor_ids = response.motor_ids;
    record.mode = granted->mode;
    record.applied_behavior = response.applied_behavior;
    record.timeout_ms = request.timeout_ms;
    record.default_kp = request.default_kp;
    record.default_kd = request.default_kd;
    record.min_command_success_rate = request.min_command_success_rate;
    record.on_low_success_rate = request.on_low_success_rate;
    record.granted_ns = granted_ns;
    checker_->on_start_posted(record);
    ClientSession& client = clients_[event.label];
    client.label = event.label;
    client.uuid = response.uuid;
    client.mode = request.control_mode;
    client.motors = granted->motors.to_ullong();
    return std::nullopt;
  }

  void release(const Event& event) {
    const auto client = clients_.find(event.label);
    if (client == clients_.end()) return;
    const auto session = sessions_->authorize(client->second.uuid);
    ReleaseControlRequest request;
    request.node_name = "client" + std::to_string(event.label);
    request.uuid = client->second.uuid;
    request.release_mode = event.behavior;
    const ReleaseControlResponse response = sessions_->release_control(request);
    if (response.success && session)
      checker_->on_release_posted(session->slot, session->generation, response.applied_behavior);
  }

  std::optional<Violation> command(const Event& event) {
    ClientSession client;
    if (const auto known = clients_.find(event.label); known != clients_.end()) client = known->second;
    if (client.uuid.empty()) client.uuid = "never-granted-" + std::to_string(event.label);
    const std::int64_t received_ns = between_ticks_ns();
    ControlCommand command = event.kind == Event::Kind::kKeepalive
                                 ? ControlCommand{}
                                 : client_command(client, event.seed, spec_, received_ns);
    command.uuid = client.uuid;
    command.answers_tick = answered_tick(event, state_.tick);
    const auto session = sessions_->authorize(command.uuid);
    const bool estopped = device_->channel().estop.load();
    const control::ValidatedCommand* accepted = gate_->handle(command, received_ns);
    if (accepted == nullptr) {
      ++rejected_;
      if (!session) ++rejected_unknown_;
      return std::nullopt;
    }
    ++accepted_;
    if (estopped) return Violation{"I3 e-stop first", "a command was accepted while the e-stop was engaged", tick_};
    if (command.answers_tick > tick_) {
      return Violation{
          "I10 closed loop",
          "the command gate accepted an answer to tick " + std::to_string(command.answers_tick) + ", which has not run",
          tick_};
    }
    checker_->on_command_accepted(session->generation, *accepted, received_ns, command.answers_tick);
    return std::nullopt;
  }

  void estop(bool engage) {
    device::DeviceChannel& channel = device_->channel();
    // One e-stop call after another, as an operator's: the last one has set (or refused) its flag.
    if (last_estop_ != nullptr) (void)wait_until([&] { return last_estop_->done(); });
    const bool before = channel.estop.load();
    EstopRequest request;
    request.node_name = "operator";
    request.engage = engage;
    auto call = std::make_unique<ServiceCall>([this, request] { return services_->estop(request).success; });
    // The e-stop service sets the flag at once; a reset is refused while the button is pressed.
    (void)wait_until([&] { return channel.estop.load() == engage || call->done(); });
    if (channel.estop.load() != before) checker_->on_estop(engage);
    last_estop_ = call.get();
    calls_.push_back(std::move(call));
  }

  std::optional<Violation> maintain(const Event& event) {
    if (maintenance_) return std::nullopt;  // one maintenance at a time (the device serialises them)
    device::DeviceChannel& channel = device_->channel();
    const bool sessions_active = sessions_->any_active(0);
    const bool running = state_.state == DeviceState::kRunning && !channel.estop.load();
    plant_->next_maintenance(event.count, event.fail);
    const bool zeroing = event.kind == Event::Kind::kResetZero;
    maintenance_op_ = zeroing ? "reset_zero" : "recover";
    maintenance_ = std::make_unique<ServiceCall>([this, zeroing] {
      if (zeroing) {
        ResetZeroRequest request;
        request.device = "dev";
        request.timeout_ms = 2000;
        return services_->reset_zero(request).success;
      }
      DeviceCallRequest request;
      request.device = "dev";
      request.op = "recover";
      return services_->device_call(request).success;
    });
    // The call checks, reserves the device and asks the loop for the driver, or refuses.
    if (!wait_until([&] { return channel.maintenance_requested.load() || maintenance_->done(); })) {
      return Violation{"rig", "the maintenance call neither asked for the driver nor refused", tick_};
    }
    if (maintenance_->done()) {  // refused
      calls_.push_back(std::move(maintenance_));
      maintenance_.reset();
      return std::nullopt;
    }
    checker_->on_maintenance_requested();
    maintenance_window_ = true;
    if (sessions_active && running) {
      return Violation{"S2 no maintenance under live sessions",
                       maintenance_op_ + " began on a RUNNING device while a session held its motors", tick_};
    }
    return std::nullopt;
  }

  bool all_calls_done() const {
    if (maintenance_ && !maintenance_->done()) return false;
    for (const auto& call : calls_) {
      if (!call->done()) return false;
    }
    return true;
  }

  std::FILE* trace_;
  DeviceSpec spec_;
  PlantDriver* plant_ = nullptr;  // owned by the device
  std::unique_ptr<device::Device> device_;
  Result<void> configured_;
  std::unique_ptr<service::SessionService> sessions_;
  dds::SurfaceCounterSet surface_;
  std::unique_ptr<dds::CommandGate> gate_;
  std::unique_ptr<device::BlackBox> black_box_;
  LatestState observer_;
  std::unique_ptr<service::DeviceServices> services_;
  std::unique_ptr<InvariantChecker> checker_;

  std::unique_ptr<ServiceCall> maintenance_;
  std::string maintenance_op_;
  bool maintenance_window_ = false;  // from a maintenance call's request until the loop took the driver back
  std::vector<std::unique_ptr<ServiceCall>> calls_;
  const ServiceCall* last_estop_ = nullptr;
  std::map<int, ClientSession> clients_;
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

RunResult run_scenario_through_services(const Scenario& scenario, std::FILE* trace) {
  auto rig = std::make_unique<ServiceRig>(scenario, trace);
  RunResult result = rig->run(scenario.events);
  rig.reset();
  return result;
}

}  // namespace robotd::safety
