// CLOCK_MONOTONIC in nanoseconds: the time base of CommandFrame deadlines, of robotd's loop and
// of drivers' timeouts. One system call, no allocation: safe on the RT thread.
#pragma once

#include <cstdint>
#include <ctime>

namespace robotd::driver {

inline std::int64_t monotonic_now_ns() noexcept {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return static_cast<std::int64_t>(now.tv_sec) * 1'000'000'000 + now.tv_nsec;
}

}  // namespace robotd::driver
