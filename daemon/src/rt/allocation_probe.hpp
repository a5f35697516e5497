// Counts heap allocations made by the calling thread, when robotd runs with the allocation
// counter preloaded (LD_PRELOAD=librobotd_alloc_counter.so, see tests/support). The RT loop
// reports the count it made after warm-up in DeviceStatus, which is how the "no allocation on
// the RT thread" rule is proven rather than asserted.
#pragma once

#include <cstdint>

extern "C" std::uint64_t robotd_alloc_counter_thread_count() __attribute__((weak));

namespace robotd::rt {

/// Allocations by this thread so far, or -1 when no counter is loaded.
inline std::int64_t thread_allocation_count() noexcept {
  if (robotd_alloc_counter_thread_count == nullptr) return -1;
  return static_cast<std::int64_t>(robotd_alloc_counter_thread_count());
}

}  // namespace robotd::rt
