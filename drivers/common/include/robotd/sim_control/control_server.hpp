// A simulator's control channel for tests: a unix stream socket; each request is one JSON
// object on a line, each reply one JSON object on a line ({"ok": true, …} or {"ok": false,
// "error": "…"}). Polled from the simulator's loop: non-blocking, single-threaded. Each
// simulator's README lists its ops.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "robotd/result.hpp"

namespace robotd::sim_control {

class ControlServer {
 public:
  using Handler = std::function<nlohmann::json(const nlohmann::json& request)>;

  explicit ControlServer(std::string path) : path_(std::move(path)) {}
  ControlServer(const ControlServer&) = delete;
  ControlServer& operator=(const ControlServer&) = delete;
  ~ControlServer() { close(); }

  /// Listens at the path; refuses when another process is listening there.
  Result<void> open();
  void close() noexcept;
  /// Accepts clients, reads what they sent, answers each complete line through `handler`
  /// (a line that is not a JSON object gets an error reply without reaching it).
  void poll(const Handler& handler);
  const std::string& path() const { return path_; }

 private:
  struct Client {
    int fd = -1;
    std::string input;
    std::string output;
  };
  /// Reads and answers; false when the client is gone or misbehaved.
  bool serve(Client& client, const Handler& handler);

  std::string path_;
  int listener_ = -1;
  std::vector<Client> clients_;
};

}  // namespace robotd::sim_control
