// The clock every simulator's loop runs on: CLOCK_MONOTONIC in nanoseconds, and the timespec its
// absolute deadlines and ppoll timeouts take.
#pragma once

#include <cstdint>
#include <ctime>

namespace robotd::sim_control {

/// CLOCK_MONOTONIC in ns.
std::int64_t monotonic_ns();
/// `ns` (a duration or a CLOCK_MONOTONIC time) as a timespec.
timespec to_timespec(std::int64_t ns);

}  // namespace robotd::sim_control
