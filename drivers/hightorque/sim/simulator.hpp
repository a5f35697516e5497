// robotd-hightorque-sim's loop: one thread, every millisecond on absolute CLOCK_MONOTONIC
// deadlines: serve the control channel, read every bus (applying and answering each request at
// once), step every motor's physics to now in 1 ms steps, send the status pushes and garbage due.
#pragma once

#include <csignal>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "bus.hpp"
#include "robotd/sim_control/control_server.hpp"
#include "robotd/sim_control/sim_clock.hpp"
#include "sim_options.hpp"

namespace robotd::hightorque::sim {

class Simulator {
 public:
  explicit Simulator(SimOptions options);

  /// Opens every bus and the control socket; the error says which and why.
  Result<void> open();
  /// Runs the loop until `stop` is non-zero (set from a signal handler).
  void run(const volatile std::sig_atomic_t& stop);

  /// One control-channel request and its reply (control_ops.cpp).
  nlohmann::json control(const nlohmann::json& request);

 private:
  void step_physics(std::int64_t now_ns);
  void log_events();
  void close_all();

  // control_ops.cpp
  nlohmann::json state() const;
  Bus& bus_of(const nlohmann::json& request, const std::string& op);
  SimMotor& motor_of(const nlohmann::json& request, const std::string& op);

  SimOptions options_;
  std::vector<std::unique_ptr<Bus>> buses_;
  std::optional<sim_control::ControlServer> control_server_;
  std::int64_t physics_ns_ = 0;
};

using sim_control::monotonic_ns;
using sim_control::to_timespec;

}  // namespace robotd::hightorque::sim
