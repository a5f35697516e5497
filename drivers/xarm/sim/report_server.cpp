#include "report_server.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>

#include <spdlog/spdlog.h>

namespace robotd::xarm::sim {
namespace {

/// A client that reads nothing while this much is queued for it is cut off.
constexpr std::size_t kReportMaxQueuedBytes = std::size_t{1} * 1024 * 1024;
constexpr int kReportReadsPerPass = 16;
constexpr std::int64_t kRealPeriodNs = 10'000'000;     // 100 Hz
constexpr std::int64_t kNormalPeriodNs = 200'000'000;  // 5 Hz
constexpr std::int64_t kRealtimePeriodNs = 4'000'000;  // 250 Hz

}  // namespace

ReportServer::ReportServer(ReportKind kind, transport::Socket listener, bool with_force_torque, std::int64_t now_ns)
    : kind_(kind),
      listener_(std::move(listener)),
      with_force_torque_(with_force_torque),
      period_ns_(period_ns(kind)),
      next_due_ns_(now_ns) {}

std::int64_t ReportServer::period_ns(ReportKind kind) {
  switch (kind) {
    case ReportKind::kReal:
      return kRealPeriodNs;
    case ReportKind::kNormal:
    case ReportKind::kRich:
      return kNormalPeriodNs;
    case ReportKind::kRealtime:
      return kRealtimePeriodNs;
  }
  return kRealPeriodNs;
}

void ReportServer::serve() {
  while (true) {
    transport::Socket socket(::accept4(listener_.fd(), nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC));
    if (!socket.is_open()) break;  // EAGAIN: nobody waiting
    const int yes = 1;
    setsockopt(socket.fd(), IPPROTO_TCP, TCP_NODELAY, &yes, sizeof(yes));
    clients_.push_back(Client{.socket = std::move(socket), .output = {}, .closed = false});
  }
  std::array<char, 512> ignored{};
  for (Client& client : clients_) {
    for (int i = 0; i < kReportReadsPerPass && !client.closed; ++i) {
      const ssize_t n = ::recv(client.socket.fd(), ignored.data(), ignored.size(), 0);
      if (n > 0 || (n < 0 && errno == EINTR)) continue;
      if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) break;
      client.closed = true;  // orderly close, or reset
    }
  }
}

void ReportServer::publish_if_due(std::int64_t now_ns, const Controller& controller, bool silenced) {
  if (now_ns < next_due_ns_) return;
  next_due_ns_ += period_ns_;
  if (next_due_ns_ <= now_ns) next_due_ns_ = now_ns + period_ns_;  // late: skip, do not burst
  if (silenced || clients_.empty()) return;
  const Bytes packet = encode_report(controller.report(now_ns), kind_, with_force_torque_);
  for (Client& client : clients_) {
    client.output.append(packet.begin(), packet.end());
    ++packets_sent_;
  }
}

void ReportServer::flush() {
  for (Client& client : clients_) {
    if (client.closed || client.output.empty()) continue;
    std::size_t sent = 0;
    if (transport::send_some(client.socket.fd(), client.output, sent) == transport::SendResult::kClosed) {
      client.closed = true;
    }
    client.output.erase(0, sent);
    if (client.output.size() > kReportMaxQueuedBytes) {
      spdlog::warn("a {} report client reads nothing; disconnecting it", report_kind_name(kind_));
      client.closed = true;
    }
  }
  std::erase_if(clients_, [](const Client& client) { return client.closed; });
}

void ReportServer::disconnect_all() { clients_.clear(); }

void ReportServer::add_poll_fds(std::vector<pollfd>& fds) const {
  fds.push_back(pollfd{.fd = listener_.fd(), .events = POLLIN, .revents = 0});
  for (const Client& client : clients_) {
    fds.push_back(pollfd{.fd = client.socket.fd(),
                         .events = static_cast<short>(POLLIN | (client.output.empty() ? 0 : POLLOUT)),
                         .revents = 0});
  }
}

}  // namespace robotd::xarm::sim
