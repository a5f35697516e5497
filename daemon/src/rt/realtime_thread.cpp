#include "rt/realtime_thread.hpp"

#include <array>
#include <cerrno>
#include <future>
#include <pthread.h>
#include <sched.h>
#include <system_error>

namespace robotd::rt {
namespace {

void prefault_stack() {
  std::array<volatile unsigned char, kStackPrefaultBytes> stack{};
  for (std::size_t i = 0; i < stack.size(); i += 4096) stack[i] = 1;
}

struct Setup {
  bool ok = true;
  ThreadStart start;
};

Setup configure_current_thread(const ThreadSettings& settings) {
  Setup setup;
  std::string& report = setup.start.report;

  if (settings.cpu >= 0) {
    cpu_set_t cpus;
    CPU_ZERO(&cpus);
    CPU_SET(static_cast<std::size_t>(settings.cpu), &cpus);
    const int rc = pthread_setaffinity_np(pthread_self(), sizeof(cpus), &cpus);
    if (rc != 0) {
      report +=
          "pinning to CPU " + std::to_string(settings.cpu) + " refused (" + std::generic_category().message(rc) + "); ";
      if (settings.policy == RealtimePolicy::kRequire) setup.ok = false;
    } else {
      report += "pinned to CPU " + std::to_string(settings.cpu) + "; ";
    }
  }

  if (settings.policy == RealtimePolicy::kOff) {
    report += "realtime off by config (SCHED_OTHER)";
  } else {
    sched_param param{};
    param.sched_priority = settings.priority;
    const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
    if (rc == 0) {
      setup.start.realtime = true;
      report += "SCHED_FIFO priority " + std::to_string(settings.priority);
    } else {
      report += "SCHED_FIFO priority " + std::to_string(settings.priority) + " refused (" +
                std::generic_category().message(rc) +
                "): running SCHED_OTHER; grant CAP_SYS_NICE or raise RLIMIT_RTPRIO (LimitRTPRIO= in the unit)";
      if (settings.policy == RealtimePolicy::kRequire) setup.ok = false;
    }
  }
  prefault_stack();
  return setup;
}

}  // namespace

Result<ThreadStart> start_thread(driver::NamedThread& thread, const ThreadSettings& settings,
                                 std::function<void()> body) {
  std::promise<Setup> ready;
  auto ready_future = ready.get_future();
  thread = driver::NamedThread(
      settings.name,
      [&ready, settings, body = std::move(body)] {
        const Setup setup = configure_current_thread(settings);
        const bool run = setup.ok;
        ready.set_value(setup);  // `ready` must not be touched after this line
        if (run) body();
      },
      kLoopStackBytes);
  const Setup setup = ready_future.get();
  if (!setup.ok) {
    thread.join();
    return make_error(ErrorCode::kRefused, "realtime: require, but " + setup.start.report);
  }
  return setup.start;
}

bool run_current_thread_fifo(int priority) noexcept {
  if (priority <= 0) return true;
  sched_param param{};
  param.sched_priority = priority;
  return pthread_setschedparam(pthread_self(), SCHED_FIFO, &param) == 0;
}

}  // namespace robotd::rt
