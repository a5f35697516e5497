#include "driver/hightorque_driver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "robotd/driver/monotonic_clock.hpp"

namespace robotd::hightorque {
namespace {

constexpr std::int64_t kNsPerMs = 1'000'000;
constexpr std::int64_t kNsPerSecond = 1'000'000'000;
constexpr std::uint8_t kCommunicationTimeoutFault = 0x15;
constexpr Query kTickQuery = Query::kStateTemperature;
constexpr std::uint64_t kPublishEveryTicks = 10;
constexpr std::size_t kRequestsPerTick = 4;

}  // namespace

HighTorqueDriver::HighTorqueDriver() = default;
HighTorqueDriver::~HighTorqueDriver() { disconnect(); }

Result<void> HighTorqueDriver::configure(const nlohmann::json& params) {
  auto parsed = parse_hightorque_params(params);
  if (!parsed) return parsed.error();
  if (parsed.value().buses.size() > kMaxBuses) {
    return make_error(ErrorCode::kInvalidArgument, "buses: at most " + std::to_string(kMaxBuses) + " buses per device");
  }
  if (parsed.value().imu) {
    auto imu = imu::make_imu_source(*parsed.value().imu, "imu");
    if (!imu) return imu.error();
    imu_ = std::move(imu.value());
  }
  params_ = std::move(parsed.value());
  motor_timeout_ms_.store(params_.motor_timeout_ms);
  buses_.clear();
  motors_on_bus_.clear();
  for (auto& row : motor_at_) row.fill(-1);
  for (std::size_t b = 0; b < params_.buses.size(); ++b) {
    buses_.push_back(make_motor_bus(params_, b));
    motors_on_bus_.push_back(params_.motors_on(b));
    for (const std::size_t motor : motors_on_bus_.back()) {
      motor_at_[b][static_cast<std::size_t>(params_.motors[motor].id)] = static_cast<std::int16_t>(motor);
    }
  }
  return {};
}

driver::DeviceDescription HighTorqueDriver::describe() const {
  driver::DeviceDescription description;
  description.model = params_.model;
  description.native_rate_hz = 1000;
  description.supports_torque = true;
  description.supports_damping = true;
  description.supports_zero_torque = true;
  description.has_imu = imu_ != nullptr;
  for (const MotorParams& motor : params_.motors) {
    driver::JointDescription joint;
    joint.name = motor.name;
    joint.limits = motor.limits;
    joint.default_kp = motor.default_kp;
    joint.default_kd = motor.default_kd;
    joint.zero_position_rad = motor.zero_offset_rad;  // the motor's zero seen through the joint map
    description.joints.push_back(joint);
  }
  description.ops = {
      {"state",
       "{}: every motor's bus, CAN id, mode, fault, temperature (°C) and reply count, and each bus's frame counts"},
      {"motor_info", "{\"motor\": name or index}: the motor's firmware and hardware versions and model name"},
      {"set_motor_timeout",
       "{\"timeout_ms\": 20..1000}: every motor's own command timeout: without commands that long a motor brakes by "
       "itself (disarming it is only possible through params.motor_timeout_ms)",
       driver::kNeedsFreeMotors},
      {"reboot_motor",
       "{\"motor\": name or index}: soft-reboots a motor robotd does not hold (no session, no KEEP or DAMPING, no "
       "e-stop; on a board bus its whole port), which comes back free-wheeling; then re-arms its watchdog",
       driver::kNeedsFreeMotors},
  };
  return description;
}

// ---- Link -----------------------------------------------------------------------------------

Result<void> HighTorqueDriver::connect() {
  abort_.clear();
  return connect_and_start();
}

Result<void> HighTorqueDriver::connect_and_start() {
  disconnect();
  if (auto opened = open_and_probe(); !opened) {
    disconnect();
    return opened;
  }
  if (imu_) {
    if (auto started = imu_->start(); !started) {
      disconnect();
      return started;
    }
  }
  connected_.store(true, std::memory_order_release);
  return {};
}

Result<void> HighTorqueDriver::open_and_probe() {
  for (std::size_t b = 0; b < buses_.size(); ++b) {
    if (auto opened = buses_[b]->open(abort_); !opened) {
      if (abort_.requested()) return opened;  // a board start-up pre-empted: the caller's verdict names it
      return make_error(ErrorCode::kNotAvailable, "bus '" + params_.buses[b].name + "' (" + buses_[b]->describe() +
                                                      "): " + opened.error().message);
    }
  }
  const std::int64_t now_ns = driver::monotonic_now_ns();
  for (auto& motor : motors_) motor = MotorRuntime{};
  for (auto& bus : bus_runtime_) bus = BusRuntime{.last_reply_ns = now_ns};
  second_started_ns_ = now_ns;
  std::vector<std::size_t> all(params_.motors.size());
  for (std::size_t m = 0; m < all.size(); ++m) all[m] = m;
  // The motors' own watchdog first: from here on they brake by themselves if robotd goes away.
  send_to_motors(all, SystemRequest::Kind::kCommandTimeout, motor_timeout_ms_.load());
  auto answered =
      await_motor_states(all, std::chrono::milliseconds(params_.connect_timeout_ms), "after the link opened");
  if (!answered) return make_error(ErrorCode::kNotAvailable, answered.error().message);
  link_up_ = true;
  const std::int64_t ready_ns = driver::monotonic_now_ns();  // the loop starts counting silence here
  for (auto& bus : bus_runtime_) bus.last_reply_ns = ready_ns;
  for (auto& motor : motors_) motor.status.last_reply_ns = ready_ns;
  return {};
}

void HighTorqueDriver::disconnect() noexcept {
  connected_.store(false, std::memory_order_release);
  if (imu_) imu_->stop();
  for (auto& bus : buses_) bus->close();
  link_up_ = false;
}

Result<void> HighTorqueDriver::recover() {
  abort_.clear();
  if (!connected_.load(std::memory_order_acquire) || !link_up_) return abort_.verdict(connect_and_start(), "recover");
  const Result<void> cleared = clear_faults();
  if (cleared || abort_.requested()) restart_silence_checks();
  return abort_.verdict(cleared, "recover");
}

void HighTorqueDriver::restart_silence_checks() noexcept {
  // The loop was paused and sent nothing: after a maintenance that succeeded, or that an e-stop
  // or a shutdown aborted, the silence checks start over, as after connect(), so that the pause
  // is not taken for a lost link.
  const std::int64_t resumed_ns = driver::monotonic_now_ns();
  for (auto& motor : motors_) motor.status.last_reply_ns = resumed_ns;
  for (auto& bus : bus_runtime_) bus.last_reply_ns = resumed_ns;
}

Result<void> HighTorqueDriver::clear_faults() {
  // A motor that rebooted or lost power came back with its own watchdog disarmed.
  std::vector<std::size_t> all(params_.motors.size());
  for (std::size_t m = 0; m < all.size(); ++m) all[m] = m;
  send_to_motors(all, SystemRequest::Kind::kCommandTimeout, motor_timeout_ms_.load());
  std::vector<std::size_t> faulted;
  for (std::size_t m = 0; m < params_.motors.size(); ++m) {
    if (motors_[m].status.fault != 0) faulted.push_back(m);
  }
  // A motor clears its fault on a stop command once the cause is gone; the query makes it say
  // so (a board answers no admin command with a state).
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(params_.reply_timeout_ms);
  std::string still;
  do {
    send_to_motors(faulted, SystemRequest::Kind::kStop);
    send_to_motors(faulted, SystemRequest::Kind::kQuery);
    if (!abort_.sleep_for(std::chrono::milliseconds(5))) return driver::aborted_error("waiting for faults to clear");
    drain_buses();
    still.clear();
    for (const std::size_t m : faulted) {
      if (motors_[m].status.fault != 0) {
        still += (still.empty() ? "" : "; ") + params_.motors[m].name + ": " + fault_text(motors_[m].status.fault);
      }
    }
  } while (!still.empty() && std::chrono::steady_clock::now() < deadline);
  if (!still.empty()) return make_error(ErrorCode::kRefused, "motors still report a fault: " + still);
  for (auto& motor : motors_) motor.fault_since_ns = 0;
  return {};
}

void HighTorqueDriver::drain_buses() noexcept {
  reply_time_ns_ = driver::monotonic_now_ns();
  for (std::size_t b = 0; b < buses_.size(); ++b) {
    draining_bus_ = b;
    (void)buses_[b]->receive(*this);
  }
}

void HighTorqueDriver::send_to_motors(std::span<const std::size_t> motors, SystemRequest::Kind kind, int value) {
  for (const std::size_t m : motors) {
    const MotorParams& motor = params_.motors[m];
    (void)buses_[motor.bus]->send_system(SystemRequest{.kind = kind, .motor = motor.id, .value = value});
  }
}

Result<void> HighTorqueDriver::await_motor_states(std::span<const std::size_t> motors,
                                                  std::chrono::milliseconds timeout, const char* what) {
  const std::int64_t asked_ns = driver::monotonic_now_ns();
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  auto next_ask = std::chrono::steady_clock::now();
  std::string missing;
  while (true) {
    if (std::chrono::steady_clock::now() >= next_ask) {
      std::vector<std::size_t> silent;
      for (const std::size_t m : motors) {
        if (motors_[m].status.last_reply_ns < asked_ns) silent.push_back(m);
      }
      send_to_motors(silent, SystemRequest::Kind::kQuery);
      next_ask += std::chrono::milliseconds(50);
    }
    if (!abort_.sleep_for(std::chrono::milliseconds(1))) {
      return driver::aborted_error("waiting for the motors to answer " + std::string(what));
    }
    drain_buses();
    missing.clear();
    for (const std::size_t m : motors) {
      if (motors_[m].status.last_reply_ns < asked_ns) {
        const MotorParams& motor = params_.motors[m];
        missing += (missing.empty() ? "" : ", ") + motor.name + " (bus '" + params_.buses[motor.bus].name + "' id " +
                   std::to_string(motor.id) + ")";
      }
    }
    if (missing.empty()) return {};
    if (std::chrono::steady_clock::now() >= deadline) break;
  }
  return make_error(ErrorCode::kTimeout, "no answer " + std::string(what) + " within " +
                                             std::to_string(timeout.count()) + " ms from " + missing +
                                             ": are the motors powered, and are bus and id right?");
}

// ---- Replies --------------------------------------------------------------------------------

void HighTorqueDriver::on_reply(const Reply& reply) noexcept {
  const std::size_t bus = draining_bus_;
  if (reply.kind != Reply::Kind::kState) {
    (void)replies_.push(BusReply{bus, reply});
    return;
  }
  const MotorState& state = reply.state;
  if (state.motor <= 0 || state.motor > kMaxMotorId) return;
  const std::int16_t index = motor_at_[bus][static_cast<std::size_t>(state.motor)];
  if (index < 0) return;  // a motor the joint map does not know: ignored
  const MotorParams& motor = params_.motors[static_cast<std::size_t>(index)];
  MotorRuntime& runtime = motors_[static_cast<std::size_t>(index)];
  const std::int64_t now_ns = reply_time_ns_;
  MotorStatus& status = runtime.status;
  status.position_rad = motor.direction * state.position_rad + motor.zero_offset_rad;
  status.velocity_rad_s = motor.direction * state.velocity_rad_s;
  status.torque_nm = motor.direction * state.torque_nm;
  if (state.query != Query::kCompact) status.mode = state.mode;
  if (state.fault != 0 && status.fault != state.fault) runtime.fault_since_ns = now_ns;
  status.fault = state.fault;
  if (state.temperature_c) {
    status.temperature_c = *state.temperature_c;
    status.has_temperature = true;
  }
  status.last_reply_ns = now_ns;
  ++status.replies;
  bus_runtime_[bus].last_reply_ns = now_ns;
}

// ---- RT thread ------------------------------------------------------------------------------

driver::IoResult HighTorqueDriver::read(driver::Feedback& out, driver::FaultInfo& fault) noexcept {
  if (!connected_.load(std::memory_order_acquire)) {
    fault.set(kNotConnectedFault, "not connected");
    return driver::IoResult::kDisconnected;
  }
  const std::int64_t now_ns = driver::monotonic_now_ns();
  reply_time_ns_ = now_ns;
  for (std::size_t b = 0; b < buses_.size(); ++b) {
    draining_bus_ = b;
    if (buses_[b]->receive(*this) == BusIo::kClosed) {
      std::snprintf(fault.text.data(), fault.text.size(), "bus '%s': the link closed", params_.buses[b].name.c_str());
      fault.code = kLinkLostFault;
      link_up_ = false;
      return driver::IoResult::kDisconnected;
    }
    const std::int64_t silent_ms = (now_ns - bus_runtime_[b].last_reply_ns) / kNsPerMs;
    if (silent_ms > params_.feedback_timeout_ms) {
      std::snprintf(fault.text.data(), fault.text.size(), "bus '%s': no motor answered for %lld ms",
                    params_.buses[b].name.c_str(), static_cast<long long>(silent_ms));
      fault.code = kLinkLostFault;
      link_up_ = false;
      return driver::IoResult::kDisconnected;
    }
  }
  out.joint_count = params_.motors.size();
  for (std::size_t m = 0; m < params_.motors.size(); ++m) {
    const MotorStatus& status = motors_[m].status;
    out.joints[m] = driver::JointFeedback{status.position_rad, status.velocity_rad_s, status.torque_nm};
  }
  if (imu_) {
    std::int64_t stamp_ns = 0;
    out.has_imu = imu_->latest(out.imu, stamp_ns);
  }
  publish(now_ns);
  // Replies to a tick's frames arrive during that tick and are read at the next; the feedback is
  // each motor's newest reply, kept fresh by the silence checks above.
  return driver::IoResult::kOk;
}

driver::IoResult HighTorqueDriver::write(const driver::CommandFrame& command, driver::FaultInfo& fault) noexcept {
  if (!connected_.load(std::memory_order_acquire)) {
    fault.set(kNotConnectedFault, "not connected");
    return driver::IoResult::kDisconnected;
  }
  ++ticks_;
  send_tick(command);
  if (const RebootRequest* reboot = reboot_.take()) reboot_.answer(decide_reboot(command, reboot->motor));
  for (std::size_t i = 0; i < kRequestsPerTick; ++i) {
    const auto queued = requests_.pop();
    if (!queued) break;
    (void)buses_[queued->bus]->send_system(queued->request);
  }
  return motor_fault(driver::monotonic_now_ns(), fault) ? driver::IoResult::kFault : driver::IoResult::kOk;
}

void HighTorqueDriver::send_tick(const driver::CommandFrame& command) noexcept {
  std::array<BlockSlot, driver::kMaxJoints> commanded;
  std::array<int, driver::kMaxJoints> idle{};
  for (std::size_t b = 0; b < buses_.size(); ++b) {
    std::size_t commanded_count = 0;
    std::size_t idle_count = 0;
    for (const std::size_t m : motors_on_bus_[b]) {
      const driver::JointCommand& joint = command.joints[m];
      motors_[m].status.owned = joint.owned;
      if (command.estop || joint.kind == driver::JointCommandKind::kNone) {
        idle[idle_count++] = params_.motors[m].id;
      } else {
        commanded[commanded_count++] = to_motor_frame(m, joint);
      }
    }
    if (command.estop) {
      (void)buses_[b]->send_brake(std::span(idle).first(idle_count), kTickQuery);
    } else {
      (void)buses_[b]->send_commands(std::span(commanded).first(commanded_count), std::span(idle).first(idle_count),
                                     kTickQuery);
    }
  }
}

HighTorqueDriver::RebootOutcome HighTorqueDriver::decide_reboot(const driver::CommandFrame& command,
                                                                std::size_t motor) noexcept {
  using Verdict = RebootOutcome::Verdict;
  if (command.estop) return {.verdict = Verdict::kEstop};
  const MotorParams& target = params_.motors[motor];
  const bool whole_port = params_.buses[target.bus].kind == BusParams::Kind::kBoard;  // the board reboots a port
  for (const std::size_t m : motors_on_bus_[target.bus]) {
    if (m != motor && !whole_port) continue;
    const driver::JointCommand& joint = command.joints[m];
    if (joint.owned) return {.verdict = Verdict::kOwned, .blocking_motor = m};
    if (joint.holds()) return {.verdict = Verdict::kHeld, .blocking_motor = m};
  }
  switch (
      buses_[target.bus]->send_system(SystemRequest{.kind = SystemRequest::Kind::kSoftReboot, .motor = target.id})) {
    case BusIo::kOk:
      return {.verdict = Verdict::kSent, .blocking_motor = 0, .replies_at_send = motors_[motor].status.replies};
    case BusIo::kBusy:
      return {.verdict = Verdict::kBusBusy};
    case BusIo::kClosed:
      break;
  }
  return {.verdict = Verdict::kLinkClosed};
}

BlockSlot HighTorqueDriver::to_motor_frame(std::size_t m, const driver::JointCommand& joint) const noexcept {
  const MotorParams& motor = params_.motors[m];
  BlockSlot slot;
  slot.motor = motor.id;
  MotorCommand& out = slot.command;
  out.mode = Mode::kMit;
  out.position_rad = motor.direction * (joint.position_rad - motor.zero_offset_rad);
  out.velocity_rad_s = motor.direction * joint.velocity_rad_s;
  out.torque_nm = motor.direction * joint.torque_nm;
  out.kp = joint.kp;
  out.kd = joint.kd;
  if (joint.kind == driver::JointCommandKind::kPosition && joint.kp == 0 && joint.kd == 0) {
    out.kp = motor.default_kp;  // a position command with no gains servos with the joint's defaults
    out.kd = motor.default_kd;
  }
  return slot;
}

bool HighTorqueDriver::motor_fault(std::int64_t now_ns, driver::FaultInfo& fault) noexcept {
  for (std::size_t m = 0; m < params_.motors.size(); ++m) {
    const MotorRuntime& runtime = motors_[m];
    const MotorParams& motor = params_.motors[m];
    const std::int64_t silent_ms = (now_ns - runtime.status.last_reply_ns) / kNsPerMs;
    // A whole bus gone quiet is a lost link, which the next read() reports.
    const std::int64_t bus_silent_ms = (now_ns - bus_runtime_[motor.bus].last_reply_ns) / kNsPerMs;
    if (silent_ms > params_.feedback_timeout_ms && bus_silent_ms <= params_.feedback_timeout_ms) {
      std::snprintf(fault.text.data(), fault.text.size(), "motor %s (bus '%s' id %d) silent for %lld ms",
                    motor.name.c_str(), params_.buses[motor.bus].name.c_str(), motor.id,
                    static_cast<long long>(silent_ms));
      fault.code = kMotorSilentFault;
      return true;
    }
    const std::uint8_t code = runtime.status.fault;
    if (code == 0) continue;
    // A motor whose watchdog fired while robotd was away or paused clears it on our next
    // command; only a timeout that persists while we command it is a fault.
    if (code == kCommunicationTimeoutFault &&
        (now_ns - runtime.fault_since_ns) / kNsPerMs <= params_.feedback_timeout_ms) {
      continue;
    }
    std::snprintf(fault.text.data(), fault.text.size(), "motor %s (bus '%s' id %d): %s (0x%02X)", motor.name.c_str(),
                  params_.buses[motor.bus].name.c_str(), motor.id, fault_text(code), code);
    fault.code = code;
    return true;
  }
  return false;
}

void HighTorqueDriver::publish(std::int64_t now_ns) noexcept {
  if (now_ns - second_started_ns_ >= kNsPerSecond) {
    const double seconds = static_cast<double>(now_ns - second_started_ns_) / kNsPerSecond;
    for (std::size_t b = 0; b < buses_.size(); ++b) {
      BusRuntime& runtime = bus_runtime_[b];
      rates_[b].sent_per_s = static_cast<double>(buses_[b]->frames_sent() - runtime.sent_at_second) / seconds;
      rates_[b].received_per_s =
          static_cast<double>(buses_[b]->frames_received() - runtime.received_at_second) / seconds;
      runtime.sent_at_second = buses_[b]->frames_sent();
      runtime.received_at_second = buses_[b]->frames_received();
    }
    second_started_ns_ = now_ns;
  }
  if (ticks_ % kPublishEveryTicks != 0) return;
  DriverSnapshot snapshot;
  snapshot.link_up = link_up_;
  snapshot.ticks = ticks_;
  for (std::size_t m = 0; m < params_.motors.size(); ++m) snapshot.motors[m] = motors_[m].status;
  for (std::size_t b = 0; b < buses_.size(); ++b) {
    snapshot.buses[b] = rates_[b];
    snapshot.buses[b].frames_sent = buses_[b]->frames_sent();
    snapshot.buses[b].frames_received = buses_[b]->frames_received();
    snapshot.buses[b].frames_dropped = buses_[b]->frames_dropped();
    snapshot.buses[b].bytes_skipped = buses_[b]->bytes_skipped();
  }
  snapshot_.store(snapshot);
}

}  // namespace robotd::hightorque
