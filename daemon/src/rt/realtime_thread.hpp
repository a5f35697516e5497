// Starting a device's loop thread with the scheduling the config asks for.
#pragma once

#include <cstddef>
#include <functional>
#include <string>

#include "robotd/driver/named_thread.hpp"
#include "robotd/result.hpp"

namespace robotd::rt {

enum class RealtimePolicy { kRequire, kPrefer, kOff };

struct ThreadSettings {
  std::string name;  // shown by top/ps (max 15 chars)
  RealtimePolicy policy = RealtimePolicy::kPrefer;
  int priority = 80;  // SCHED_FIFO 1..99
  int cpu = -1;       // pin to this CPU, -1 = no pinning
};

// The loop touches this much of its stack up front so that it never page-faults on it: mlockall
// locks a page once it is touched (MCL_ONFAULT), so these pages then stay resident. The loop's
// deepest stack, driver read() and write() included, measured 8 KiB beyond the prefault's own
// frame; 256 KiB keeps the margin robotd always had.
inline constexpr std::size_t kStackPrefaultBytes = std::size_t{256} * 1024;
// The loop thread's stack: the prefaulted part and an ordinary thread's stack above it, for the
// frames that start the loop.
inline constexpr std::size_t kLoopStackBytes = kStackPrefaultBytes + driver::kThreadStackBytes;

struct ThreadStart {
  bool realtime = false;  // SCHED_FIFO granted
  std::string report;     // what was asked, what was granted and why not
};

/// Starts `body` on a new thread configured per `settings`: SCHED_FIFO at `priority` (if the
/// policy is not kOff), CPU affinity, and a stack of kLoopStackBytes of which kStackPrefaultBytes
/// are prefaulted. Returns once the
/// thread is set up. With kRequire, a refused SCHED_FIFO or affinity is an error and `body` never runs.
Result<ThreadStart> start_thread(driver::NamedThread& thread, const ThreadSettings& settings,
                                 std::function<void()> body);

/// Runs the calling thread SCHED_FIFO at `priority` (1..99); 0 leaves it as it is. Best effort:
/// false if the system refused (the caller has checked beforehand that SCHED_FIFO is permitted).
bool run_current_thread_fifo(int priority) noexcept;

}  // namespace robotd::rt
