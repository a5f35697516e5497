// Starting a device's loop thread with the scheduling the config asks for.
#pragma once

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

struct ThreadStart {
  bool realtime = false;  // SCHED_FIFO granted
  std::string report;     // what was asked, what was granted and why not
};

/// Starts `body` on a new thread configured per `settings`: SCHED_FIFO at `priority` (if the
/// policy is not kOff), CPU affinity, and a stack of 512 KiB whose first 256 KiB are prefaulted. Returns once the
/// thread is set up. With kRequire, a refused SCHED_FIFO or affinity is an error and `body` never runs.
Result<ThreadStart> start_thread(driver::NamedThread& thread, const ThreadSettings& settings,
                                 std::function<void()> body);

}  // namespace robotd::rt
