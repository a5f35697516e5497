// How robotctl's long-running verbs wait: for SIGINT/SIGTERM, for a wake() from another thread
// (a subscription callback), or for a deadline, whichever comes first, without polling.
//
// Install it first in main(), before the DDS participant exists: it blocks the stop signals in
// the calling thread, every thread started later inherits that mask, and the signals then
// reach robotctl only through its signalfd.
#pragma once

#include <chrono>
#include <optional>

#include "robotd/result.hpp"

namespace robotctl {

class StopSignals {
 public:
  enum class Wake { kDeadline, kWoken, kStopSignal };

  static robotd::Result<StopSignals> install();

  StopSignals(StopSignals&& other) noexcept;
  StopSignals& operator=(StopSignals&& other) noexcept;
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;
  ~StopSignals();

  /// Sleeps until `deadline`, a wake() or a stop signal. Once a stop signal has arrived,
  /// returns kStopSignal at once.
  Wake wait_until(std::chrono::steady_clock::time_point deadline) { return wait(deadline); }
  /// Sleeps until a wake() or a stop signal.
  Wake wait_for_wake() { return wait(std::nullopt); }
  /// Ends the current or the next wait with kWoken. Safe from any thread.
  void wake();
  /// SIGINT or SIGTERM once one has arrived, else 0.
  int received_signal() const { return received_signal_; }
  /// For verbs with nothing to clean up: SIGINT and SIGTERM end the process as usual again.
  void restore_default_action();

 private:
  StopSignals(int signal_fd, int wake_fd) : signal_fd_(signal_fd), wake_fd_(wake_fd) {}
  Wake wait(std::optional<std::chrono::steady_clock::time_point> deadline);

  int signal_fd_ = -1;
  int wake_fd_ = -1;
  int received_signal_ = 0;
};

}  // namespace robotctl
