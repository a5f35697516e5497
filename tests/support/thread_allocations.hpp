// Counts the calling thread's operator new calls, so a unit test can show that a hot path (a
// codec's encode, a kinematics solve) does not allocate. Linking robotd_thread_allocations
// replaces the binary's global operator new and delete.
#pragma once

#include <cstddef>

namespace robotd::testing {

/// How many times this thread has called operator new so far.
std::size_t allocations_on_this_thread();

}  // namespace robotd::testing
