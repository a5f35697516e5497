// A 1 kHz thread that calls a driver's read() and write() the way robotd's RT loop does, with
// the command a test sets, for driver tests that run without robotd.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <mutex>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "robotd/driver/driver.hpp"

namespace robotd::testing {

class DriverLoop {
 public:
  DriverLoop(driver::Driver& driver, std::size_t joint_count);
  DriverLoop(const DriverLoop&) = delete;
  DriverLoop& operator=(const DriverLoop&) = delete;
  ~DriverLoop();

  void set_command(const driver::CommandFrame& command);
  /// Pauses the calls (as robotd does for recover()) while `work` runs.
  template <class Work>
  auto paused(Work work) {
    pause();
    auto result = work();
    paused_ = false;
    return result;
  }
  driver::Feedback feedback();
  driver::IoResult last_read() const { return last_read_.load(); }
  driver::IoResult last_write() const { return last_write_.load(); }
  /// How many write() calls have reported kFault.
  int write_faults() const { return write_faults_.load(); }
  /// The text of the last fault read() or write() reported.
  std::string fault_text();
  /// Waits until `done(*this)` or the timeout.
  template <class Done>
  bool wait_for(Done done, std::chrono::milliseconds timeout = std::chrono::seconds(5)) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
      if (done(*this)) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return false;
  }

 private:
  void pause();
  void run();
  void tick();

  driver::Driver& driver_;
  std::mutex mutex_;
  driver::CommandFrame command_;
  driver::Feedback feedback_;
  driver::FaultInfo fault_;
  std::atomic<driver::IoResult> last_read_{driver::IoResult::kNoNewData};
  std::atomic<driver::IoResult> last_write_{driver::IoResult::kOk};
  std::atomic<int> write_faults_{0};
  std::atomic<bool> paused_{false};
  std::atomic<bool> idle_{false};
  std::atomic<bool> running_{true};
  std::thread thread_;
};

/// A frame that positions the first q.size() joints at q, owned by a session when `owned`;
/// `joint_count` joints in all (0: q.size()).
driver::CommandFrame position_frame(std::span<const double> q, bool owned = true, std::size_t joint_count = 0);
/// Whether each of the first q.size() joints of `feedback` is within `tolerance` of q.
bool joints_near(const driver::Feedback& feedback, std::span<const double> q, double tolerance);
/// The value of `key` in the driver's diagnostics, or "(no <key>)".
std::string diagnostic(const driver::Driver& driver, const std::string& key);
/// The names of the ops that set needs_free_motors, in the driver's order.
std::vector<std::string> ops_needing_free_motors(const driver::DeviceDescription& description);

}  // namespace robotd::testing
