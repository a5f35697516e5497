// The clock every simulator's loop runs on: CLOCK_MONOTONIC in nanoseconds, and the timespec its
// absolute deadlines and ppoll timeouts take.
#pragma once

#include <csignal>
#include <cstdint>
#include <ctime>

namespace robotd::sim_control {

/// CLOCK_MONOTONIC in ns.
std::int64_t monotonic_ns();
/// `ns` (a duration or a CLOCK_MONOTONIC time) as a timespec.
timespec to_timespec(std::int64_t ns);

/// A fixed-rate loop's pacing: sleeps until one period after its last wake-up `wake_ns`
/// (absolute, so passes do not drift) and returns that time. A pass that overran (`now_ns` past
/// the next wake-up) starts afresh one period after `now_ns` instead of racing to catch up.
/// Signals do not cut the sleep short unless `stop` is set.
std::int64_t sleep_until_next_pass(std::int64_t wake_ns, std::int64_t now_ns, std::int64_t period_ns,
                                   const volatile std::sig_atomic_t& stop);

}  // namespace robotd::sim_control
