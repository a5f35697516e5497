#include "robotd/transport/io_thread.hpp"

#include <cerrno>
#include <cstdint>
#include <pthread.h>
#include <sched.h>
#include <sys/eventfd.h>
#include <system_error>
#include <unistd.h>

namespace robotd::transport {

Result<void> IoThread::start(const std::string& name, int fifo_priority, std::function<void()> body) {
  stop();
  wake_fd_ = eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
  if (wake_fd_ < 0) {
    return make_error(ErrorCode::kTransport,
                      "cannot create an eventfd for " + name + " (" + std::generic_category().message(errno) + ")");
  }
  stop_.store(false, std::memory_order_release);
  thread_ = driver::NamedThread(name, [fifo_priority, body = std::move(body)] {
    if (fifo_priority > 0) {
      sched_param param{};
      param.sched_priority = fifo_priority;
      pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
    }
    body();
  });
  return {};
}

void IoThread::stop() noexcept {
  if (thread_.joinable()) {
    stop_.store(true, std::memory_order_release);
    wake();
    thread_.join();
  }
  if (wake_fd_ >= 0) ::close(wake_fd_);
  wake_fd_ = -1;
}

void IoThread::wake() const noexcept {
  if (wake_fd_ < 0) return;
  const std::uint64_t one = 1;
  [[maybe_unused]] const ssize_t written = ::write(wake_fd_, &one, sizeof(one));
}

void IoThread::drain() const noexcept {
  std::uint64_t count = 0;
  while (::read(wake_fd_, &count, sizeof(count)) > 0) {
  }
}

}  // namespace robotd::transport
