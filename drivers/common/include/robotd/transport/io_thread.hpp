// A driver's link thread: named, on SCHED_FIFO when asked, stopped and woken early through an
// eventfd that its loop polls next to its sockets.
#pragma once

#include <atomic>
#include <functional>
#include <string>

#include "robotd/driver/named_thread.hpp"
#include "robotd/result.hpp"

namespace robotd::transport {

class IoThread {
 public:
  IoThread() = default;
  IoThread(const IoThread&) = delete;
  IoThread& operator=(const IoThread&) = delete;
  ~IoThread() { stop(); }

  /// Creates the wake eventfd and runs `body` on a new thread named `name` (at most 15
  /// characters) with driver::kThreadStackBytes of stack, at SCHED_FIFO `fifo_priority` when above 0 (best effort:
  /// without the right to it the thread runs with normal scheduling). `body` loops until stopping().
  Result<void> start(const std::string& name, int fifo_priority, std::function<void()> body);
  /// Sets stopping(), wakes the thread, joins it and closes the eventfd. Safe when not started.
  void stop() noexcept;
  bool running() const { return thread_.joinable(); }
  bool stopping() const { return stop_.load(std::memory_order_acquire); }

  /// Makes the eventfd readable: a poll that includes wake_fd() returns.
  void wake() const noexcept;
  /// Clears the wake-ups so far; the loop calls it once per turn.
  void drain() const noexcept;
  int wake_fd() const { return wake_fd_; }

 private:
  int wake_fd_ = -1;
  driver::NamedThread thread_;
  std::atomic<bool> stop_{false};
};

}  // namespace robotd::transport
