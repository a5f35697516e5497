// End to end: robotd speaks sd_notify to the socket systemd would give it. READY once up,
// WATCHDOG pings at half of WatchdogSec while every loop ticks (and none while one hangs),
// STOPPING on SIGTERM. A datagram socket stands in for systemd.
#include <chrono>
#include <optional>
#include <string>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>
#include <vector>

#include <gtest/gtest.h>

#include "robotd_fixture.hpp"

namespace robotd::testing {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

class NotifySocket {
 public:
  NotifySocket() : path_("/tmp/robotd-test-notify-" + std::to_string(getpid())) {
    fd_ = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    path_.copy(address.sun_path, sizeof(address.sun_path) - 1);
    unlink(path_.c_str());
    if (bind(fd_, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0) ADD_FAILURE() << "bind failed";
  }
  NotifySocket(const NotifySocket&) = delete;
  NotifySocket& operator=(const NotifySocket&) = delete;
  ~NotifySocket() {
    close(fd_);
    unlink(path_.c_str());
  }

  const std::string& path() const { return path_; }

  /// The next datagram, or nullopt after `timeout`.
  std::optional<std::string> receive(std::chrono::milliseconds timeout) {
    timeval tv{static_cast<time_t>(timeout.count() / 1000), static_cast<suseconds_t>(timeout.count() % 1000 * 1000)};
    setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof(tv));
    char buffer[4096];
    const ssize_t n = recv(fd_, buffer, sizeof(buffer), 0);
    if (n <= 0) return std::nullopt;
    return std::string(buffer, static_cast<std::size_t>(n));
  }

  /// Waits for a datagram containing `text`; returns when it arrived.
  std::optional<Clock::time_point> wait_for(const std::string& text, std::chrono::milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    while (Clock::now() < deadline) {
      const auto message = receive(std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()));
      if (message && message->find(text) != std::string::npos) return Clock::now();
    }
    return std::nullopt;
  }

 private:
  std::string path_;
  int fd_ = -1;
};

class SystemdNotifyTest : public RobotdTest {};

TEST_F(SystemdNotifyTest, ReadyThenWatchdogWhileLoopsTickThenStopping) {
  NotifySocket systemd;
  // WatchdogSec=200ms: robotd pings every 100 ms.
  start_robotd(nullptr, {"NOTIFY_SOCKET=" + systemd.path(), "WATCHDOG_USEC=200000"});
  ASSERT_TRUE(systemd.wait_for("READY=1", 5s)) << "robotd never said READY=1";

  std::vector<Clock::time_point> pings;
  const auto listen_until = Clock::now() + 1s;
  while (Clock::now() < listen_until) {
    if (auto at = systemd.wait_for("WATCHDOG=1", 500ms)) pings.push_back(*at);
  }
  EXPECT_GE(pings.size(), 7U) << "expected a ping about every 100 ms";

  // A driver that hangs for 800 ms stops the loop: robotd must stop pinging, so systemd
  // would restart it, and must count the missed ticks.
  ASSERT_TRUE(client().device_call("arm", "stall", R"({"ms": 800})"));
  const auto stalled_at = Clock::now();
  std::chrono::milliseconds longest_gap{0};
  auto last_ping = stalled_at;
  while (Clock::now() - stalled_at < 1500ms) {
    if (auto at = systemd.wait_for("WATCHDOG=1", 1500ms)) {
      longest_gap = std::max(longest_gap, std::chrono::duration_cast<std::chrono::milliseconds>(*at - last_ping));
      last_ping = *at;
    }
  }
  EXPECT_GE(longest_gap, 500ms) << "robotd kept pinging the watchdog while its loop hung";
  EXPECT_NE(robotd_->log().find("not pinging the systemd watchdog: loop of 'arm' is not ticking"), std::string::npos)
      << robotd_->log();
  EXPECT_GE(device_status().loop.overruns, 700U) << "the hung ticks were not counted as overruns";
  EXPECT_TRUE(systemd.wait_for("WATCHDOG=1", 1s)) << "pings did not resume once the loop ticked again";

  ::kill(robotd_->pid(), SIGTERM);
  EXPECT_TRUE(systemd.wait_for("STOPPING=1", 5s)) << "robotd never said STOPPING=1";
  const auto status = robotd_->terminate(10s);
  ASSERT_TRUE(status.has_value());
  EXPECT_EQ(*status, 0);
}

}  // namespace
}  // namespace robotd::testing
