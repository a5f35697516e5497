// The startup self-check: what this machine and process allow for real-time work, so a
// timing problem is traced to its cause (kernel, limits, governor) instead of guessed at.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "robotd/result.hpp"

namespace robotd::rt {

struct EnvironmentReport {
  bool preempt_rt_kernel = false;
  std::string kernel;
  std::string rtprio_limit;   // RLIMIT_RTPRIO, "unlimited" or a number
  std::string memlock_limit;  // RLIMIT_MEMLOCK
  bool can_use_fifo = false;  // root / CAP_SYS_NICE or rtprio > 0
  std::string cpu_governor;   // cpu0's scaling governor, "unknown" without cpufreq
  int cpu_count = 0;
  std::vector<std::string> warnings;  // things that will hurt timing, in plain words
};

EnvironmentReport inspect_environment();
std::string describe(const EnvironmentReport& report);

/// A PM QoS request on /dev/cpu_dma_latency, held while this object lives: CPUs stay out of
/// idle states whose exit takes longer than the requested time, so a loop's timer wake-up is
/// not delayed by waking the CPU. (cyclictest holds the same request while it measures.)
class CpuLatencyRequest {
 public:
  /// Requests `latency_us` (0 = stay in the shallowest idle state).
  static Result<CpuLatencyRequest> hold(std::int32_t latency_us);
  CpuLatencyRequest(CpuLatencyRequest&& other) noexcept;
  CpuLatencyRequest& operator=(CpuLatencyRequest&& other) noexcept;
  CpuLatencyRequest(const CpuLatencyRequest&) = delete;
  CpuLatencyRequest& operator=(const CpuLatencyRequest&) = delete;
  ~CpuLatencyRequest();

 private:
  explicit CpuLatencyRequest(int fd) : fd_(fd) {}
  int fd_ = -1;
};

}  // namespace robotd::rt
