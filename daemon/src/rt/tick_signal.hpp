// How a device's RT loop wakes its state publisher right after a tick: a counter the loop bumps
// and a futex wake, only when the publisher sleeps on it. The RT side takes no lock, allocates
// nothing and never blocks (FUTEX_WAKE returns at once); the waiting side may wait with a
// timeout, so it still does its own periodic work while the loop is not ticking.
#pragma once

#include <atomic>
#include <climits>
#include <cstdint>
#include <ctime>
#include <linux/futex.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace robotd::rt {

class TickSignal {
 public:
  /// RT side: one more tick is ready.
  void notify() noexcept {
    count_.fetch_add(1, std::memory_order_seq_cst);
    if (waiting_.load(std::memory_order_seq_cst)) futex(FUTEX_WAKE_PRIVATE, INT_MAX, nullptr);
  }

  /// The count of ticks notified so far (wraps; compare for inequality only).
  std::uint32_t count() const noexcept { return count_.load(std::memory_order_acquire); }

  /// Waiting side: returns once count() differs from `seen`, or after `timeout_ns`.
  void wait(std::uint32_t seen, std::int64_t timeout_ns) noexcept {
    waiting_.store(true, std::memory_order_seq_cst);
    // Checked after announcing the wait: a notify() between the two either sees waiting_ or
    // changed count_ before this load, so no wake-up is lost (FUTEX_WAIT re-checks the value too).
    if (count_.load(std::memory_order_seq_cst) == seen) {
      const timespec timeout{static_cast<time_t>(timeout_ns / 1'000'000'000),
                             static_cast<long>(timeout_ns % 1'000'000'000)};
      futex(FUTEX_WAIT_PRIVATE, seen, &timeout);
    }
    waiting_.store(false, std::memory_order_relaxed);
  }

 private:
  void futex(int op, std::uint32_t value, const timespec* timeout) noexcept {
    (void)syscall(SYS_futex, reinterpret_cast<std::uint32_t*>(&count_), op, value, timeout, nullptr, 0);
  }

  static_assert(sizeof(std::atomic<std::uint32_t>) == sizeof(std::uint32_t));
  std::atomic<std::uint32_t> count_{0};
  std::atomic<bool> waiting_{false};
};

}  // namespace robotd::rt
