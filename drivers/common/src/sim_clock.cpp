#include "robotd/sim_control/sim_clock.hpp"

#include <cerrno>

#include "robotd/driver/monotonic_clock.hpp"

namespace robotd::sim_control {

std::int64_t monotonic_ns() { return driver::monotonic_now_ns(); }

timespec to_timespec(std::int64_t ns) {
  return timespec{.tv_sec = static_cast<time_t>(ns / 1'000'000'000), .tv_nsec = static_cast<long>(ns % 1'000'000'000)};
}

std::int64_t sleep_until_next_pass(std::int64_t wake_ns, std::int64_t now_ns, std::int64_t period_ns,
                                   const volatile std::sig_atomic_t& stop) {
  std::int64_t next_ns = wake_ns + period_ns;
  if (next_ns < now_ns) next_ns = now_ns + period_ns;  // overran: start afresh, do not race
  const timespec wake = to_timespec(next_ns);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &wake, nullptr) == EINTR && stop == 0) {
  }
  return next_ns;
}

}  // namespace robotd::sim_control
