#include "rt/realtime_environment.hpp"

#include <cerrno>
#include <fcntl.h>
#include <fstream>
#include <sstream>
#include <sys/resource.h>
#include <sys/utsname.h>
#include <system_error>
#include <unistd.h>
#include <utility>

namespace robotd::rt {
namespace {

std::string read_first_line(const char* path) {
  std::ifstream file(path);
  std::string line;
  if (file) std::getline(file, line);
  return line;
}

std::string limit_text(int resource) {
  rlimit limit{};
  if (getrlimit(resource, &limit) != 0) return "unknown";
  if (limit.rlim_cur == RLIM_INFINITY) return "unlimited";
  return std::to_string(limit.rlim_cur);
}

bool fifo_allowed() {
  if (geteuid() == 0) return true;
  rlimit limit{};
  return getrlimit(RLIMIT_RTPRIO, &limit) == 0 && limit.rlim_cur > 0;
}

}  // namespace

EnvironmentReport inspect_environment() {
  EnvironmentReport report;
  utsname name{};
  if (uname(&name) == 0) report.kernel = std::string(name.release) + " " + name.version;
  report.preempt_rt_kernel =
      read_first_line("/sys/kernel/realtime") == "1" || report.kernel.find("PREEMPT_RT") != std::string::npos;
  report.rtprio_limit = limit_text(RLIMIT_RTPRIO);
  report.memlock_limit = limit_text(RLIMIT_MEMLOCK);
  report.can_use_fifo = fifo_allowed();
  report.cpu_governor = read_first_line("/sys/devices/system/cpu/cpu0/cpufreq/scaling_governor");
  if (report.cpu_governor.empty()) report.cpu_governor = "unknown (no cpufreq)";
  report.cpu_count = static_cast<int>(sysconf(_SC_NPROCESSORS_ONLN));

  if (!report.preempt_rt_kernel) {
    report.warnings.emplace_back("kernel is not PREEMPT_RT: expect wake-up latencies of tens to hundreds of µs");
  }
  if (!report.can_use_fifo) {
    report.warnings.emplace_back("SCHED_FIFO not permitted (RLIMIT_RTPRIO " + report.rtprio_limit +
                                 ", not root): loops will run SCHED_OTHER");
  }
  if (report.cpu_governor != "performance" && report.cpu_governor.rfind("unknown", 0) != 0) {
    report.warnings.emplace_back("CPU governor is '" + report.cpu_governor +
                                 "': frequency changes add latency; 'performance' is recommended");
  }
  return report;
}

std::string describe(const EnvironmentReport& report) {
  std::ostringstream out;
  out << "kernel " << report.kernel << (report.preempt_rt_kernel ? " (PREEMPT_RT)" : " (not PREEMPT_RT)")
      << "; RLIMIT_RTPRIO " << report.rtprio_limit << "; RLIMIT_MEMLOCK " << report.memlock_limit << "; SCHED_FIFO "
      << (report.can_use_fifo ? "permitted" : "not permitted") << "; CPU governor " << report.cpu_governor << "; "
      << report.cpu_count << " CPUs online";
  return out.str();
}

Result<CpuLatencyRequest> CpuLatencyRequest::hold(std::int32_t latency_us) {
  const int fd = open("/dev/cpu_dma_latency", O_WRONLY | O_CLOEXEC);
  if (fd < 0) {
    return make_error(ErrorCode::kRefused,
                      "cannot open /dev/cpu_dma_latency (" + std::generic_category().message(errno) +
                          "): CPUs may enter deep idle states, which adds tens of µs to loop wake-ups; give robotd "
                          "write access (systemd/90-robotd-cpu-dma-latency.rules) or set daemon.cpu_dma_latency_us "
                          "to -1 to stop asking");
  }
  if (write(fd, &latency_us, sizeof(latency_us)) != static_cast<ssize_t>(sizeof(latency_us))) {
    const std::string reason = std::generic_category().message(errno);
    close(fd);
    return make_error(ErrorCode::kRefused, "writing /dev/cpu_dma_latency failed (" + reason + ")");
  }
  return CpuLatencyRequest(fd);
}

CpuLatencyRequest::CpuLatencyRequest(CpuLatencyRequest&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}

CpuLatencyRequest& CpuLatencyRequest::operator=(CpuLatencyRequest&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) close(fd_);
    fd_ = std::exchange(other.fd_, -1);
  }
  return *this;
}

CpuLatencyRequest::~CpuLatencyRequest() {
  if (fd_ >= 0) close(fd_);  // closing the file withdraws the request
}

}  // namespace robotd::rt
