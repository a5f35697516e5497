// CLOCK_MONOTONIC in nanoseconds: the one time base of robotd's loops, deadlines and sessions.
#pragma once

#include <cerrno>
#include <cstdint>
#include <ctime>

#include "robotd/driver/monotonic_clock.hpp"

namespace robotd::rt {

inline constexpr std::int64_t kNsPerSecond = 1'000'000'000;
inline constexpr std::int64_t kNsPerMs = 1'000'000;

using driver::monotonic_now_ns;  // the same clock drivers stamp with

inline std::int64_t realtime_now_ns() noexcept {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * kNsPerSecond + ts.tv_nsec;
}

/// Sleeps until the absolute CLOCK_MONOTONIC time `deadline_ns` (retrying on signals).
inline void sleep_until_ns(std::int64_t deadline_ns) noexcept {
  timespec ts{static_cast<time_t>(deadline_ns / kNsPerSecond), static_cast<long>(deadline_ns % kNsPerSecond)};
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

}  // namespace robotd::rt
