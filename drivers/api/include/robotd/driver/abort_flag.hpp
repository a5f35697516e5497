// What Driver::abort_maintenance() sets and a driver's recover() and reset_zero() look at in each
// of their waits: one atomic, so robotd's RT loop may set it on every tick.
//
//   void abort_maintenance() noexcept override { abort_.request(); }
//   Result<void> MyDriver::recover() {
//     abort_.clear();  // a request that came before this recover() is not meant for it
//     return abort_.verdict(reconnect(), "recover");  // every wait: if (!abort_.sleep_for(…)) …
//   }
#pragma once

#include <atomic>
#include <chrono>
#include <future>
#include <string_view>

#include "robotd/result.hpp"

namespace robotd::driver {

class AbortFlag {
 public:
  /// Any thread, the RT loop included: one atomic store.
  void request() noexcept { requested_.store(true, std::memory_order_release); }
  void clear() noexcept { requested_.store(false, std::memory_order_release); }
  bool requested() const noexcept { return requested_.load(std::memory_order_acquire); }

  /// Sleeps `duration`, looking at the flag every millisecond; false, at once, when it is set.
  bool sleep_for(std::chrono::nanoseconds duration) const;

  /// What recover() or reset_zero() (`what`) returns: `result`, or, when it failed after an
  /// abort was requested, "aborted: an e-stop or shutdown pre-empted <what> (<the step>)".
  Result<void> verdict(Result<void> result, std::string_view what) const;

 private:
  std::atomic<bool> requested_{false};
};

/// "aborted: an e-stop or shutdown pre-empted <what>", ErrorCode::kRefused.
Error aborted_error(std::string_view what);

/// Waits up to `timeout` for `future`; with `abort`, a millisecond at a time, ending early when
/// it is requested. True when the future is ready.
template <class T>
bool wait_ready(const std::future<T>& future, std::chrono::nanoseconds timeout, const AbortFlag* abort) {
  if (abort == nullptr) return future.wait_for(timeout) == std::future_status::ready;
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (future.wait_for(std::chrono::milliseconds(1)) != std::future_status::ready) {
    if (abort->requested() || std::chrono::steady_clock::now() >= until) return false;
  }
  return true;
}

}  // namespace robotd::driver
