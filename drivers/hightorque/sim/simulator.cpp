#include "simulator.hpp"

#include <utility>

#include <spdlog/spdlog.h>

namespace robotd::hightorque::sim {
namespace {

constexpr std::int64_t kLoopPeriodNs = 1'000'000;
constexpr std::int64_t kStepNs = 1'000'000;
constexpr double kStepS = 1e-3;
constexpr int kMaxStepsPerLoop = 50;  // behind by more: the motors' clock slips instead

}  // namespace

Simulator::Simulator(SimOptions options) : options_(std::move(options)) {
  const std::int64_t now = monotonic_ns();
  for (const BusSpec& spec : options_.buses) buses_.push_back(std::make_unique<Bus>(spec, options_, now));
}

Result<void> Simulator::open() {
  for (const auto& bus : buses_) {
    if (auto opened = bus->open(); !opened) {
      close_all();
      return opened;
    }
  }
  if (!options_.control_path.empty()) {
    control_server_.emplace(options_.control_path);
    if (auto opened = control_server_->open(); !opened) {
      close_all();
      return opened;
    }
  }
  return {};
}

void Simulator::close_all() {
  if (control_server_) control_server_->close();
  for (const auto& bus : buses_) bus->close();
}

void Simulator::run(const volatile std::sig_atomic_t& stop) {
  const std::int64_t start = monotonic_ns();
  physics_ns_ = start;
  std::int64_t wake_ns = start;
  const sim_control::ControlServer::Handler handler = [this](const nlohmann::json& request) {
    return control(request);
  };
  while (stop == 0) {
    const std::int64_t now = monotonic_ns();
    if (control_server_) control_server_->poll(handler);
    for (const auto& bus : buses_) {
      bus->reopen_if_due(now);
      bus->poll(now);
    }
    step_physics(now);
    for (const auto& bus : buses_) bus->send_due(now);
    log_events();

    wake_ns = sim_control::sleep_until_next_pass(wake_ns, now, kLoopPeriodNs, stop);
  }
  close_all();
}

void Simulator::step_physics(std::int64_t now_ns) {
  int steps = 0;
  while (physics_ns_ + kStepNs <= now_ns) {
    if (++steps > kMaxStepsPerLoop) {
      physics_ns_ = now_ns;  // descheduled for long: the simulated motors lose that time
      break;
    }
    physics_ns_ += kStepNs;
    for (const auto& bus : buses_) {
      for (SimMotor& motor : bus->motors()) motor.step(kStepS, physics_ns_);
    }
  }
}

void Simulator::log_events() {
  for (const auto& bus : buses_) {
    for (SimMotor& motor : bus->motors()) {
      if (motor.take_event() && !options_.quiet) {
        spdlog::info("{} motor {}: {} ({}), fault 0x{:02X} ({}), {:.1f} °C", bus->spec().path, motor.id(),
                     mode_text(static_cast<std::uint8_t>(motor.mode())), static_cast<int>(motor.mode()), motor.fault(),
                     fault_text(motor.fault()), motor.temperature_c());
      }
    }
  }
}

}  // namespace robotd::hightorque::sim
