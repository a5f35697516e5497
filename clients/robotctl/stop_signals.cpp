#include "stop_signals.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <poll.h>
#include <string>
#include <sys/eventfd.h>
#include <sys/signalfd.h>
#include <system_error>
#include <unistd.h>
#include <utility>

namespace robotctl {
namespace {

sigset_t stop_signal_set() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  return set;
}

robotd::Error system_error(const char* what) {
  return robotd::make_error(robotd::ErrorCode::kTransport,
                            std::string(what) + " failed: " + std::generic_category().message(errno));
}

timespec to_timespec(std::chrono::nanoseconds duration) {
  const auto seconds = std::chrono::duration_cast<std::chrono::seconds>(duration);
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(seconds.count());
  ts.tv_nsec = static_cast<long>((duration - seconds).count());
  return ts;
}

}  // namespace

robotd::Result<StopSignals> StopSignals::install() {
  const sigset_t set = stop_signal_set();
  if (pthread_sigmask(SIG_BLOCK, &set, nullptr) != 0) return system_error("blocking SIGINT and SIGTERM");
  const int signal_fd = signalfd(-1, &set, SFD_CLOEXEC | SFD_NONBLOCK);
  if (signal_fd < 0) return system_error("signalfd");
  const int wake_fd = eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  if (wake_fd < 0) {
    const robotd::Error error = system_error("eventfd");
    close(signal_fd);
    return error;
  }
  return StopSignals(signal_fd, wake_fd);
}

StopSignals::StopSignals(StopSignals&& other) noexcept
    : signal_fd_(std::exchange(other.signal_fd_, -1)),
      wake_fd_(std::exchange(other.wake_fd_, -1)),
      received_signal_(other.received_signal_) {}

StopSignals& StopSignals::operator=(StopSignals&& other) noexcept {
  if (this != &other) {
    std::swap(signal_fd_, other.signal_fd_);
    std::swap(wake_fd_, other.wake_fd_);
    received_signal_ = other.received_signal_;
  }
  return *this;
}

StopSignals::~StopSignals() {
  if (signal_fd_ >= 0) close(signal_fd_);
  if (wake_fd_ >= 0) close(wake_fd_);
}

StopSignals::Wake StopSignals::wait(std::optional<std::chrono::steady_clock::time_point> deadline) {
  while (received_signal_ == 0) {
    std::array<pollfd, 2> fds{};
    fds[0].fd = signal_fd_;
    fds[0].events = POLLIN;
    fds[1].fd = wake_fd_;
    fds[1].events = POLLIN;
    std::optional<timespec> timeout;
    if (deadline) {
      timeout = to_timespec(
          std::max(*deadline - std::chrono::steady_clock::now(), std::chrono::steady_clock::duration::zero()));
    }
    const int ready = ppoll(fds.data(), fds.size(), timeout ? &*timeout : nullptr, nullptr);
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) return Wake::kDeadline;
    if ((fds[0].revents & POLLIN) != 0) {
      signalfd_siginfo info{};
      if (read(signal_fd_, &info, sizeof info) == static_cast<ssize_t>(sizeof info)) {
        received_signal_ = static_cast<int>(info.ssi_signo);
      }
      continue;
    }
    std::uint64_t count = 0;
    if (read(wake_fd_, &count, sizeof count) == static_cast<ssize_t>(sizeof count)) return Wake::kWoken;
  }
  return Wake::kStopSignal;
}

void StopSignals::wake() {
  const std::uint64_t one = 1;
  // A full counter already means "woken"; nothing is lost if this write fails.
  (void)write(wake_fd_, &one, sizeof one);
}

void StopSignals::restore_default_action() {
  const sigset_t set = stop_signal_set();
  pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
}

}  // namespace robotctl
