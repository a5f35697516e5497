// The allocation counter (tests/support/alloc_counter.cpp) in robotd, for the tests that check
// the RT loops make no heap allocation along the way.
#pragma once

#include <string>
#include <vector>

#include "sanitizer_build.hpp"

namespace robotd::testing {

/// Whether robotd runs with the counter, so that its loops report rt_heap_allocations. Not in
/// sanitizer builds: the counter's malloc goes straight to glibc, around the sanitizer's
/// allocator, and ASan refuses to start behind a preloaded library. There robotd runs without
/// it, reports rt_heap_allocations -1, and the tests check everything else.
inline constexpr bool kCountsAllocations = !kSanitizerBuild;

/// The environment that preloads the counter into robotd (empty if !kCountsAllocations).
inline std::vector<std::string> allocation_counter_environment() {
  if (!kCountsAllocations) return {};
  return {std::string("LD_PRELOAD=") + ALLOC_COUNTER_LIBRARY};
}

}  // namespace robotd::testing
