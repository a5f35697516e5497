#include "simulator.hpp"

#include <algorithm>
#include <arpa/inet.h>
#include <array>
#include <cerrno>
#include <ctime>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <utility>

#include <spdlog/spdlog.h>

namespace robotd::realman::sim {
namespace {

constexpr std::int64_t kLoopPeriodNs = 1'000'000;
constexpr int kMaxReadsPerPass = 64;
/// A client that reads nothing while this much is queued for it is cut off.
constexpr std::size_t kMaxQueuedBytes = std::size_t{4} * 1024 * 1024;

}  // namespace

Simulator::Simulator(SimOptions options, const ArmModel& model)
    : options_(std::move(options)), controller_(options_, model, monotonic_ns()) {}

Result<void> Simulator::open() {
  auto listener = transport::listen_tcp(transport::Endpoint{options_.host, options_.port});
  if (!listener) return listener.error();
  auto udp = transport::bind_udp(transport::Endpoint{options_.host, 0});
  if (!udp) return udp.error();
  if (!options_.control_path.empty()) {
    control_server_.emplace(options_.control_path);
    if (auto opened = control_server_->open(); !opened) return opened;
  }
  listener_ = std::move(listener).value();
  udp_ = std::move(udp).value();
  return {};
}

void Simulator::run(const volatile std::sig_atomic_t& stop) {
  std::int64_t next_pass_ns = monotonic_ns();
  const sim_control::ControlServer::Handler handler = [this](const nlohmann::json& request) {
    return control(request);
  };
  while (stop == 0) {
    if (control_server_) control_server_->poll(handler);
    accept_clients();
    for (Client& client : clients_) read_client(client);
    const std::int64_t now = monotonic_ns();
    controller_.advance(now);
    send_events();
    push_if_due(now);
    for (Client& client : clients_) flush(client);
    drop_closed_clients();
    if (now >= next_pass_ns) {
      next_pass_ns += kLoopPeriodNs;
      if (next_pass_ns < now) next_pass_ns = now + kLoopPeriodNs;  // overran: start afresh, do not race
    }
    wait_until(controller_.pushing() && !push_silenced_ ? std::min(next_pass_ns, next_push_ns_) : next_pass_ns);
  }
  if (control_server_) control_server_->close();
}

void Simulator::wait_until(std::int64_t wake_ns) {
  std::vector<pollfd> fds;
  fds.reserve(clients_.size() + 1);
  fds.push_back(pollfd{.fd = listener_.fd(), .events = POLLIN, .revents = 0});
  for (const Client& client : clients_) {
    fds.push_back(pollfd{.fd = client.socket.fd(),
                         .events = static_cast<short>(POLLIN | (client.output.empty() ? 0 : POLLOUT)),
                         .revents = 0});
  }
  const std::int64_t left_ns = wake_ns - monotonic_ns();
  if (left_ns <= 0) return;
  const timespec timeout = to_timespec(left_ns);
  ppoll(fds.data(), fds.size(), &timeout, nullptr);  // EINTR: the loop checks `stop`
}

void Simulator::accept_clients() {
  while (true) {
    transport::Socket socket(::accept4(listener_.fd(), nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC));
    if (!socket.is_open()) return;  // EAGAIN: nobody waiting
    const int yes = 1;
    setsockopt(socket.fd(), IPPROTO_TCP, TCP_NODELAY, &yes, sizeof(yes));
    auto peer = transport::peer_endpoint(socket.fd());
    Client client{.id = next_client_id_++,
                  .socket = std::move(socket),
                  .peer = peer ? peer.value() : transport::Endpoint{},
                  .lines = LineSplitter{},
                  .output = {},
                  .closed = false};
    ++clients_accepted_;
    if (!options_.quiet) spdlog::info("client {} connected from {}", client.id, client.peer.to_string());
    clients_.push_back(std::move(client));
  }
}

void Simulator::read_client(Client& client) {
  std::array<char, 8192> bytes{};
  for (int i = 0; i < kMaxReadsPerPass && !client.closed; ++i) {
    const ssize_t n = ::recv(client.socket.fd(), bytes.data(), bytes.size(), 0);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return;
    if (n <= 0) {  // orderly close, or reset
      client.closed = true;
      return;
    }
    const std::int64_t received_ns = monotonic_ns();
    client.lines.append(std::string_view(bytes.data(), static_cast<std::size_t>(n)));
    while (auto line = client.lines.next()) {
      const nlohmann::json reply = controller_.handle(*line, client.id, received_ns);
      if (!reply.is_null()) send_reply(client, reply);
    }
  }
}

void Simulator::send_reply(Client& client, const nlohmann::json& reply) {
  if (replies_to_drop_ > 0) {
    --replies_to_drop_;
    ++replies_dropped_;
    return;
  }
  client.output += frame(reply);
  ++replies_sent_;
}

void Simulator::send_events() {
  for (Event& event : controller_.take_events()) {
    const auto client = std::find_if(clients_.begin(), clients_.end(),
                                     [&](const Client& c) { return c.id == event.client && !c.closed; });
    if (client == clients_.end()) continue;  // its client left: nobody to tell
    client->output += frame(event.message);
    ++events_sent_;
  }
}

void Simulator::flush(Client& client) {
  if (client.closed || client.output.empty()) return;
  std::size_t sent = 0;
  const transport::SendResult result = transport::send_some(client.socket.fd(), client.output, sent);
  client.output.erase(0, sent);
  if (result == transport::SendResult::kClosed) client.closed = true;
  if (client.output.size() > kMaxQueuedBytes) {
    spdlog::warn("client {} ({}) reads nothing; disconnecting it", client.id, client.peer.to_string());
    client.closed = true;
  }
}

void Simulator::drop_closed_clients() {
  const auto closed = std::remove_if(clients_.begin(), clients_.end(), [this](const Client& client) {
    if (client.closed && !options_.quiet) spdlog::info("client {} disconnected", client.id);
    return client.closed;
  });
  clients_.erase(closed, clients_.end());
}

std::optional<transport::Endpoint> Simulator::push_destination() const {
  const PushConfig& push = controller_.push_config();
  const auto port = static_cast<std::uint16_t>(push.port);
  if (!push.ip.empty()) return transport::Endpoint{push.ip, port};
  const auto latest = std::find_if(clients_.rbegin(), clients_.rend(),
                                   [](const Client& client) { return !client.closed && !client.peer.host.empty(); });
  if (latest == clients_.rend()) return std::nullopt;
  return transport::Endpoint{latest->peer.host, port};
}

void Simulator::push_if_due(std::int64_t now_ns) {
  if (!controller_.pushing()) return;
  const std::int64_t period_ns = controller_.push_config().period_ns();
  if (period_ns != push_period_ns_) {  // enabled, or a new cycle: the schedule starts now
    push_period_ns_ = period_ns;
    next_push_ns_ = now_ns;
  }
  if (now_ns < next_push_ns_) return;
  next_push_ns_ += period_ns;
  if (next_push_ns_ <= now_ns) next_push_ns_ = now_ns + period_ns;  // late: skip, do not burst
  if (push_silenced_) return;
  const auto destination = push_destination();
  if (!destination) return;
  if (send_datagram(*destination, controller_.push_datagram(now_ns))) {
    ++pushes_sent_;
  } else {
    ++push_failures_;
  }
}

bool Simulator::send_datagram(const transport::Endpoint& destination, std::string_view bytes) {
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(destination.port);
  if (inet_pton(AF_INET, destination.host.c_str(), &address.sin_addr) != 1) return false;
  const ssize_t n = ::sendto(udp_.fd(), bytes.data(), bytes.size(), MSG_NOSIGNAL,
                             reinterpret_cast<const sockaddr*>(&address), sizeof(address));  // NOLINT: sockets API
  return n == static_cast<ssize_t>(bytes.size());
}

}  // namespace robotd::realman::sim
