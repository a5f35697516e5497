// Brings devices back after a lost link: while a device's latched fault is a lost link (its
// driver reported kDisconnected: simulator gone, cable pulled, controller rebooting), try the
// driver's recover() after reconnect_interval_ms, then at doubling intervals up to
// reconnect_max_interval_ms, with the loop paused as for a manual recover.
// Once it succeeds the joints hold where they are measured. Faults the device itself reports
// are left for a person to read and recover explicitly.
#pragma once

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <vector>

#include "device/device.hpp"
#include "robotd/driver/named_thread.hpp"
#include "service/device_observer.hpp"

namespace robotd::service {

class Reconnector {
 public:
  Reconnector(std::vector<device::Device*> devices, std::vector<DeviceObserver*> observers);
  Reconnector(const Reconnector&) = delete;
  Reconnector& operator=(const Reconnector&) = delete;
  ~Reconnector();

  void start();
  void stop();

 private:
  struct Attempts {
    std::chrono::steady_clock::time_point next{};
    std::chrono::steady_clock::time_point lost_at{};
    std::chrono::steady_clock::time_point last_report{};
    std::chrono::milliseconds delay{};  // before the attempt after next
    bool lost = false;
  };
  void run();
  void try_device(std::size_t index, std::chrono::steady_clock::time_point now);

  std::vector<device::Device*> devices_;
  std::vector<DeviceObserver*> observers_;
  std::vector<Attempts> attempts_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  driver::NamedThread thread_;
};

}  // namespace robotd::service
