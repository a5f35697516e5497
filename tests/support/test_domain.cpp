#include "test_domain.hpp"

#include <fcntl.h>
#include <stdexcept>
#include <string>
#include <sys/file.h>
#include <unistd.h>

namespace robotd::testing {

namespace {
constexpr int kFirstDomain = 100;
constexpr int kLastDomain = 229;
}  // namespace

TestDomain::TestDomain() {
  for (int id = kFirstDomain + static_cast<int>(getpid() % 37); id <= kLastDomain; ++id) {
    const std::string path = "/tmp/robotd-test-domain-" + std::to_string(id) + ".lock";
    const int fd = open(path.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0666);
    if (fd < 0) continue;
    if (flock(fd, LOCK_EX | LOCK_NB) == 0) {
      id_ = id;
      lock_fd_ = fd;
      return;
    }
    close(fd);
  }
  throw std::runtime_error("no free test DDS domain id in 100..229");
}

TestDomain::~TestDomain() {
  if (lock_fd_ >= 0) close(lock_fd_);  // releases the flock
}

}  // namespace robotd::testing
