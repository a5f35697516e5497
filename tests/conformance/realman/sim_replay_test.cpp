// The vendor SDK's recorded sessions replayed against a fresh robotd-realman-sim over its real TCP
// socket: every request as the SDK sent it, every reply compared with the recorded one. Fields
// that depend on when the reply was made (masks.json) are compared by presence and type only.
#include <array>
#include <chrono>
#include <optional>
#include <string>
#include <sys/socket.h>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "codec/realman_codec.hpp"
#include "conformance_report.hpp"
#include "realman_sim_process.hpp"
#include "realman_transcript.hpp"
#include "robotd/transport/ip_socket.hpp"
#include "vector_file.hpp"

namespace robotd::realman::conformance {
namespace {

using namespace std::chrono_literals;
using nlohmann::json;
using robotd::conformance::Outcome;
using robotd::conformance::record;
using Clock = std::chrono::steady_clock;

// Long enough for the longest recorded wait (a gripper stroke at the speed the SDK used).
constexpr auto kLineTimeout = 10s;

/// One TCP client of the simulator, reading CR LF lines.
class Client {
 public:
  explicit Client(std::uint16_t port) {
    auto connected = transport::connect_tcp(transport::Endpoint{"127.0.0.1", port}, 1000ms);
    if (!connected) throw std::runtime_error(connected.error().message);
    socket_ = std::move(connected).value();
  }
  void send_line(const std::string& line) {
    const std::string bytes = line + std::string(kMessageTerminator);
    std::size_t offset = 0;
    while (offset < bytes.size()) {
      std::size_t sent = 0;
      if (transport::send_some(socket_.fd(), std::string_view(bytes).substr(offset), sent) ==
          transport::SendResult::kClosed) {
        throw std::runtime_error("the simulator closed the connection");
      }
      offset += sent;
      if (sent == 0) std::this_thread::sleep_for(1ms);
    }
  }
  std::optional<std::string> next_line() {
    const auto deadline = Clock::now() + kLineTimeout;
    while (true) {
      if (auto line = lines_.next()) return line;
      if (Clock::now() >= deadline) return std::nullopt;
      if (!transport::wait_readable(socket_.fd(), 10ms)) continue;
      std::array<char, 8192> bytes{};
      const ssize_t n = ::recv(socket_.fd(), bytes.data(), bytes.size(), 0);
      if (n <= 0) return std::nullopt;
      lines_.append(std::string_view(bytes.data(), static_cast<std::size_t>(n)));
    }
  }

 private:
  transport::Socket socket_;
  LineSplitter lines_;
};

/// Replaces each masked field (masks.json: message key → JSON pointers) by its type's name.
json masked(json message, const json& masks) {
  const std::string key = message_key(message);
  if (!masks.contains(key)) return message;
  for (const json& path : masks.at(key).at("fields")) {
    const json::json_pointer pointer(path.get<std::string>());
    if (message.contains(pointer)) message[pointer] = std::string("<masked ") + message[pointer].type_name() + ">";
  }
  return message;
}

/// Whether a recorded reply tells that a planned move started, or that one ended.
bool starts_a_move(const json& reply) {
  return reply.value("receive_state", false) && message_key(reply) != "movej_canfd";
}
bool ends_a_move(const json& reply) {
  return message_key(reply) == "current_trajectory_state" && reply.value("device", 0) == 0;
}

void replay(const Session& session, const json& masks) {
  std::vector<std::string> options = {"--quiet"};
  options.insert(options.end(), session.sim_options.begin(), session.sim_options.end());
  testing::RealmanSimProcess sim(options);
  for (const Connection& connection : session.connections) {
    Client client(sim.port());
    Clock::time_point stream_start;
    int stream_frames = 0;  // frames sent of the stream under way
    bool moving = false;    // between a planned move's acceptance and its end, as recorded
    for (const Exchange& exchange : connection.exchanges) {
      const json request = json::parse(exchange.request);
      // The stream goes out at the rate the SDK sent it (the simulator judges the speed by it), and
      // what follows it one period after its last frame, as the SDK waited: the arm takes a frame
      // at its next 1 ms step, so a query in the same segment would find the frame before.
      const bool frame = message_key(request) == "movej_canfd";
      if (frame && stream_frames == 0) stream_start = Clock::now();
      if (frame || stream_frames > 0) {
        std::this_thread::sleep_until(stream_start +
                                      std::chrono::duration<double>(session.stream_period_s * stream_frames));
      }
      stream_frames = frame ? stream_frames + 1 : 0;
      client.send_line(exchange.request);
      for (const std::string& recorded : exchange.replies) {
        const auto line = client.next_line();
        const json recorded_json = json::parse(recorded);
        const auto mask = [&](json message) {
          message = masked(std::move(message), masks.at("always"));
          return moving ? masked(std::move(message), masks.at("while_moving")) : message;
        };
        const json expected = mask(recorded_json);
        const json actual = line ? mask(json::parse(*line, nullptr, false)) : json("<no reply>");
        if (starts_a_move(recorded_json)) moving = true;
        if (ends_a_move(recorded_json)) moving = false;
        const bool same = actual == expected;
        record("replies", same ? Outcome::passed : Outcome::failed);
        EXPECT_TRUE(same) << session.name << " connection " << connection.id << ": " << exchange.request
                          << "\n  recorded: " << recorded << "\n  replayed: " << line.value_or("<none>");
      }
    }
  }
}

TEST(RealmanSimReplay, EveryRecordedSessionGetsTheRecordedReplies) {
  const json masks = robotd::conformance::load_json("masks.json");
  const std::vector<Session> sessions = load_sessions();
  ASSERT_FALSE(sessions.empty());
  for (const Session& session : sessions) replay(session, masks);
}

}  // namespace
}  // namespace robotd::realman::conformance
