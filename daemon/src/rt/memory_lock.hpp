// Keeping robotd's memory in RAM without making it all resident. mlockall locks each page as it
// is first touched (MCL_ONFAULT) instead of faulting in every mapping up front: a thread's stack
// costs what the thread uses, not the whole reservation. What the RT loops need without a fault
// is made resident explicitly: their stacks (rt::start_thread prefaults them), the code and
// constant data of every loaded object (lock_loaded_objects), and their heap data, which is
// written (so resident, then locked) before a loop starts or before it is handed to a loop.
#pragma once

#include <string>

namespace robotd::rt {

/// mlockall(MCL_CURRENT | MCL_FUTURE | MCL_ONFAULT). Returns "" on success, else why it failed.
std::string lock_memory();

/// Faults in and locks every segment of every object loaded now (the executable, the shared
/// libraries, the driver plugins): the loop's code and constants, rare paths such as an e-stop
/// included, never page-fault. Returns "" on success, else what could not be locked and why.
std::string lock_loaded_objects();

}  // namespace robotd::rt
