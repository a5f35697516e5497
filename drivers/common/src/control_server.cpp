#include "robotd/sim_control/control_server.hpp"

#include <array>
#include <cerrno>
#include <sys/socket.h>
#include <unistd.h>

#include "robotd/sim_control/control_request.hpp"
#include "robotd/transport/unix_socket.hpp"

namespace robotd::sim_control {
namespace {

constexpr std::size_t kMaxLine = std::size_t{64} * 1024;
constexpr int kMaxClients = 16;

}  // namespace

Result<void> ControlServer::open() {
  close();
  if (transport::unix_socket_in_use(path_)) {
    return make_error(ErrorCode::kNotAvailable, "control socket " + path_ + " is in use by another process");
  }
  auto listener = transport::listen_unix_socket(path_, SOCK_STREAM, kMaxClients);
  if (!listener) return listener.error();
  listener_ = listener.value();
  return {};
}

void ControlServer::close() noexcept {
  for (const Client& client : clients_) ::close(client.fd);
  clients_.clear();
  if (listener_ >= 0) {
    ::close(listener_);
    unlink(path_.c_str());
  }
  listener_ = -1;
}

void ControlServer::poll(const Handler& handler) {
  if (listener_ < 0) return;
  while (clients_.size() < static_cast<std::size_t>(kMaxClients)) {
    const int fd = accept4(listener_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd < 0) break;
    clients_.push_back(Client{.fd = fd, .input = {}, .output = {}});
  }
  for (auto it = clients_.begin(); it != clients_.end();) {
    if (serve(*it, handler)) {
      ++it;
    } else {
      ::close(it->fd);
      it = clients_.erase(it);
    }
  }
}

bool ControlServer::serve(Client& client, const Handler& handler) {
  std::array<char, 4096> chunk{};
  bool peer_closed = false;
  while (true) {
    const ssize_t n = recv(client.fd, chunk.data(), chunk.size(), MSG_DONTWAIT);
    if (n > 0) {
      client.input.append(chunk.data(), static_cast<std::size_t>(n));
      continue;
    }
    if (n == 0 || (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) peer_closed = true;
    break;
  }
  for (auto newline = client.input.find('\n'); newline != std::string::npos; newline = client.input.find('\n')) {
    const std::string line = client.input.substr(0, newline);
    client.input.erase(0, newline + 1);
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;  // blank line
    nlohmann::json reply;
    const nlohmann::json request = nlohmann::json::parse(line, nullptr, false);
    if (request.is_discarded() || !request.is_object()) {
      reply = error_reply("the request is not a JSON object: send one object per line, e.g. {\"op\":\"state\"}");
    } else {
      reply = handler(request);
    }
    client.output += reply.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    client.output += '\n';
  }
  if (client.input.size() > kMaxLine) {
    client.output += error_reply("request line longer than 65536 bytes").dump() + "\n";
    client.input.clear();
  }
  while (!client.output.empty()) {
    const ssize_t n = send(client.fd, client.output.data(), client.output.size(), MSG_DONTWAIT | MSG_NOSIGNAL);
    if (n <= 0) {
      if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) break;  // rest next poll
      return false;
    }
    client.output.erase(0, static_cast<std::size_t>(n));
  }
  // A client that half-closed after its request still gets the reply (sent above).
  return !peer_closed;
}

}  // namespace robotd::sim_control
