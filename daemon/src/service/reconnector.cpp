#include "service/reconnector.hpp"

#include <algorithm>

#include <spdlog/spdlog.h>

namespace robotd::service {
namespace {

constexpr auto kCheckPeriod = std::chrono::milliseconds(50);
constexpr auto kReportPeriod = std::chrono::seconds(10);  // "still unreachable" at most this often

double seconds_between(std::chrono::steady_clock::time_point from, std::chrono::steady_clock::time_point to) {
  return std::chrono::duration<double>(to - from).count();
}

}  // namespace

Reconnector::Reconnector(std::vector<device::Device*> devices, std::vector<DeviceObserver*> observers)
    : devices_(std::move(devices)), observers_(std::move(observers)), attempts_(devices_.size()) {}

Reconnector::~Reconnector() { stop(); }

void Reconnector::start() {
  thread_ = driver::NamedThread("reconnector", [this] { run(); });
}

void Reconnector::stop() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void Reconnector::run() {
  std::unique_lock lock(mutex_);
  while (!wake_.wait_for(lock, kCheckPeriod, [this] { return stopping_; })) {
    lock.unlock();
    const auto now = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < devices_.size(); ++i) try_device(i, now);
    lock.lock();
  }
}

void Reconnector::try_device(std::size_t index, std::chrono::steady_clock::time_point now) {
  device::Device& device = *devices_[index];
  const int interval_ms = device.config().reconnect_interval_ms;
  Attempts& attempts = attempts_[index];
  const device::LoopState state = observers_[index]->latest();
  const bool link_lost = state.state == DeviceState::kFault && state.link_lost;
  // An engaged e-stop pre-empts maintenance: reconnecting waits for its reset.
  const bool estopped = device.channel().estop.load(std::memory_order_acquire);
  if (interval_ms <= 0 || !link_lost || estopped) {
    attempts.lost = false;
    return;
  }
  const std::string& name = device.model().name;
  if (!attempts.lost) {
    attempts = Attempts{now, now, now, std::chrono::milliseconds(interval_ms), true};
    spdlog::warn("device '{}': link lost ({}); reconnecting after {} ms, backing off to every {} ms", name,
                 state.fault.text.data(), interval_ms,
                 std::max(interval_ms, device.config().reconnect_max_interval_ms));
  }
  if (now < attempts.next) return;
  attempts.next = now + attempts.delay;
  // Back off (doubling) so an absent controller is not hammered, up to reconnect_max_interval_ms.
  attempts.delay = std::min(
      2 * attempts.delay, std::chrono::milliseconds(std::max(interval_ms, device.config().reconnect_max_interval_ms)));
  auto recovered =
      device.run_maintenance([](driver::Driver& driver) { return driver.recover(); }, true, std::chrono::seconds(10));

  if (recovered) {
    spdlog::info("device '{}': reconnected after {:.1f} s; joints hold where they are", name,
                 seconds_between(attempts.lost_at, std::chrono::steady_clock::now()));
    attempts.lost = false;
  } else if (now - attempts.last_report >= kReportPeriod) {
    attempts.last_report = now;
    spdlog::warn("device '{}': still unreachable after {:.0f} s: {}", name, seconds_between(attempts.lost_at, now),
                 recovered.error().message);
  }
}

}  // namespace robotd::service
