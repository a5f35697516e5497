// What the driver shows in DeviceStatus.driver_values: the link, each bus's frame counts and
// rates, and every motor's mode, fault and temperature.
#include <cstdio>
#include <string>
#include <utility>

#include "driver/hightorque_driver.hpp"

namespace robotd::hightorque {
namespace {

std::string fixed(double value, int decimals) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.*f", decimals, value);
  return text;
}

/// A byte stream (the board's tty) also counts the bytes it skipped between packets.
std::string skipped_text(const BusParams& params, const BusCounters& counters) {
  if (params.kind != BusParams::Kind::kBoard) return "";
  return ", skipped " + std::to_string(counters.bytes_skipped) + " bytes";
}

}  // namespace

driver::Diagnostics HighTorqueDriver::diagnostics() const {
  const DriverSnapshot snapshot = snapshot_.load_non_rt();
  driver::Diagnostics values;
  values.emplace_back("link", snapshot.link_up ? "up" : "down");
  const int watchdog_ms = motor_timeout_ms_.load();
  values.emplace_back("motor_timeout_ms", std::to_string(watchdog_ms));
  values.emplace_back("motor_watchdog", watchdog_ms == 0 ? "DISARMED by params.motor_timeout_ms = 0: a motor keeps its "
                                                           "last command if robotd dies"
                                                         : "armed: a motor brakes " + std::to_string(watchdog_ms) +
                                                               " ms after its last command");
  for (std::size_t b = 0; b < params_.buses.size(); ++b) {
    const BusCounters& bus = snapshot.buses[b];
    const std::string prefix = "bus." + params_.buses[b].name;
    values.emplace_back(prefix, buses_[b]->describe());
    values.emplace_back(prefix + ".frames", "sent " + std::to_string(bus.frames_sent) + ", received " +
                                                std::to_string(bus.frames_received) + ", dropped " +
                                                std::to_string(bus.frames_dropped) +
                                                skipped_text(params_.buses[b], bus));
    values.emplace_back(prefix + ".rate",
                        fixed(bus.sent_per_s, 0) + " sent/s, " + fixed(bus.received_per_s, 0) + " received/s");
  }
  for (std::size_t m = 0; m < params_.motors.size(); ++m) {
    const MotorParams& params = params_.motors[m];
    const MotorStatus& status = snapshot.motors[m];
    std::string text = params_.buses[params.bus].name + " id " + std::to_string(params.id) + " · " +
                       mode_text(status.mode) + " · " + fault_text(status.fault);
    if (status.has_temperature) text += " · " + fixed(status.temperature_c, 0) + " °C";
    values.emplace_back("motor." + params.name, text);
  }
  if (imu_) {
    for (auto& line : imu_->diagnostics()) values.push_back(std::move(line));
  }
  return values;
}

}  // namespace robotd::hightorque
