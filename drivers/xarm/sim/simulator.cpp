#include "simulator.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <ctime>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <utility>

#include <spdlog/spdlog.h>

namespace robotd::xarm::sim {
namespace {

constexpr std::int64_t kLoopPeriodNs = 1'000'000;
constexpr int kCommandReadsPerPass = 64;
/// A client that reads nothing while this much is queued for it is cut off.
constexpr std::size_t kCommandMaxQueuedBytes = std::size_t{4} * 1024 * 1024;

}  // namespace

Simulator::Simulator(SimOptions options, const ArmModel& model)
    : options_(std::move(options)), controller_(options_, model, monotonic_ns()) {}

Result<void> Simulator::open() {
  auto listener = transport::listen_tcp(transport::Endpoint{options_.host, options_.port});
  if (!listener) return make_error(listener.error().code, "the command port: " + listener.error().message);
  listener_ = std::move(listener).value();
  const std::array<std::pair<ReportKind, std::optional<std::uint16_t>>, 4> ports = {
      {{ReportKind::kReal, options_.report_port},
       {ReportKind::kNormal, options_.normal_report_port},
       {ReportKind::kRealtime, options_.realtime_report_port},
       {ReportKind::kRich, options_.rich_report_port}}};
  for (const auto& [kind, port] : ports) {
    if (!port) continue;
    auto report_listener = transport::listen_tcp(transport::Endpoint{options_.host, *port});
    if (!report_listener) {
      return make_error(report_listener.error().code, "the " + std::string(report_kind_name(kind)) +
                                                          " report port: " + report_listener.error().message);
    }
    reports_.emplace_back(kind, std::move(report_listener).value(), options_.report_force_torque, monotonic_ns());
  }
  if (!options_.control_path.empty()) {
    control_server_.emplace(options_.control_path);
    if (auto opened = control_server_->open(); !opened) return opened;
  }
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
    for (ReportServer& report : reports_) report.serve();
    const std::int64_t now = monotonic_ns();
    controller_.advance(now);
    send_feedback();
    for (ReportServer& report : reports_) report.publish_if_due(now, controller_, reports_silenced_);
    for (Client& client : clients_) flush(client);
    for (ReportServer& report : reports_) report.flush();
    drop_closed_clients();
    if (now >= next_pass_ns) {
      next_pass_ns += kLoopPeriodNs;
      if (next_pass_ns < now) next_pass_ns = now + kLoopPeriodNs;  // overran: start afresh, do not race
    }
    std::int64_t wake_ns = next_pass_ns;
    for (const ReportServer& report : reports_) wake_ns = std::min(wake_ns, report.next_due_ns());
    wait_until(wake_ns);
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
  for (const ReportServer& report : reports_) report.add_poll_fds(fds);
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
    Client client;
    client.id = next_client_id_++;
    client.socket = std::move(socket);
    client.peer = peer ? peer.value() : transport::Endpoint{};
    if (!options_.quiet) spdlog::info("client {} connected from {}", client.id, client.peer.to_string());
    clients_.push_back(std::move(client));
  }
}

void Simulator::read_client(Client& client) {
  std::array<std::uint8_t, 8192> bytes{};
  for (int i = 0; i < kCommandReadsPerPass && !client.closed; ++i) {
    const ssize_t n = ::recv(client.socket.fd(), bytes.data(), bytes.size(), 0);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return;
    if (n <= 0) {  // orderly close, or reset
      client.closed = true;
      return;
    }
    controller_.advance(monotonic_ns());  // each request sees the arm as it is when it arrives
    send_feedback();                      // what happened before it, before its reply
    client.frames.append(ByteView(bytes.data(), static_cast<std::size_t>(n)));
    while (true) {
      auto frame = client.frames.next();
      if (!frame) {
        spdlog::warn("client {} ({}): {}; closing the connection", client.id, client.peer.to_string(),
                     frame.error().message);
        client.closed = true;
        return;
      }
      if (!frame.value()) break;
      const Frame& request = *frame.value();
      client.last_transaction_id = request.transaction_id;
      client.last_protocol = request.protocol;
      send_reply(client, controller_.handle(request, client.id));
    }
  }
}

void Simulator::send(Client& client, const Frame& frame) {
  const Bytes bytes = encode_frame(frame);
  client.output.append(bytes.begin(), bytes.end());
}

void Simulator::send_reply(Client& client, const Frame& reply) {
  if (replies_to_drop_ > 0) {
    --replies_to_drop_;
    ++replies_dropped_;
    return;
  }
  send(client, reply);
  ++replies_sent_;
}

void Simulator::send_feedback() {
  for (const Feedback& feedback : controller_.take_feedback()) {
    const auto client = std::find_if(clients_.begin(), clients_.end(),
                                     [&](const Client& c) { return c.id == feedback.client && !c.closed; });
    if (client == clients_.end()) continue;  // its client left: nobody to tell
    send(*client, feedback.frame);
    ++feedback_frames_sent_;
  }
}

void Simulator::flush(Client& client) {
  if (client.closed || client.output.empty()) return;
  std::size_t sent = 0;
  const transport::SendResult result = transport::send_some(client.socket.fd(), client.output, sent);
  client.output.erase(0, sent);
  if (result == transport::SendResult::kClosed) client.closed = true;
  if (client.output.size() > kCommandMaxQueuedBytes) {
    spdlog::warn("client {} ({}) reads nothing; disconnecting it", client.id, client.peer.to_string());
    client.closed = true;
  }
}

void Simulator::drop_closed_clients() {
  std::erase_if(clients_, [this](const Client& client) {
    if (!client.closed) return false;
    controller_.forget_client(client.id);
    if (!options_.quiet) spdlog::info("client {} disconnected", client.id);
    return true;
  });
}

}  // namespace robotd::xarm::sim
