// A client in its own process for tests that kill a client: acquires a session, prints
// "uuid <uuid> session <public session id>", then streams position commands holding the arm at its current position
// (plus
// --offset) at --rate Hz until it is killed (or for --seconds, then prints "sent <n>"). With --uuid it requests nothing
// and streams
// --position to every motor in the name of that session instead, as a client that learned another's uuid would: it
// prints "streaming" once a command is written, or "failed <why>" if none can be. It connects as
// ClientOptions::from_environment() says (ROBOTD_DDS_SECURITY_* included).
#include <chrono>
#include <cstdio>
#include <thread>

#include <CLI/CLI.hpp>

#include "robotd/client.hpp"

namespace {

using Clock = std::chrono::steady_clock;

/// Calls `send` every `period` for `seconds` (0: until killed), then prints how many it sent.
template <class Send>
int stream(Clock::duration period, double seconds, Send send) {
  const auto start = Clock::now();
  std::uint64_t sent = 0;
  for (auto next = start; seconds <= 0 || Clock::now() - start < std::chrono::duration<double>(seconds);
       next += period) {
    if (send()) ++sent;
    std::this_thread::sleep_until(next);
  }
  std::printf("sent %llu\n", static_cast<unsigned long long>(sent));
  return 0;
}

int stream_in_the_name_of(robotd::Client& client, const std::string& uuid, const std::string& device, int motors,
                          float position_rad, Clock::duration period, double seconds) {
  robotd::ControlCommand command;
  command.uuid = uuid;
  command.device = device;
  for (int id = 0; id < motors; ++id) {
    command.motor_ids.push_back(id);
    command.positions.push_back(position_rad);
  }
  auto written = client.publish(command);
  if (!written) {
    std::printf("failed %s\n", written.error().message.c_str());
    return 5;
  }
  std::printf("streaming\n");
  std::fflush(stdout);
  return stream(period, seconds, [&] { return static_cast<bool>(client.publish(command)); });
}

int hold_a_session(robotd::Client& client, const std::string& device, const std::string& on_timeout, int timeout_ms,
                   float offset_rad, Clock::duration period, double seconds) {
  const auto behavior = robotd::parse_behavior(on_timeout);
  if (!behavior) return 2;
  robotd::SessionRequest request;
  request.device = device;
  request.on_timeout = *behavior;
  request.timeout = std::chrono::milliseconds(timeout_ms);
  // The state first: the session's timeout runs from the grant, and on a loaded machine the first
  // joint state can take longer than timeout_ms to arrive.
  auto state = client.next_joint_state(device, std::chrono::seconds(2));
  if (!state) return 4;
  auto session = client.request_control(request);
  if (!session) {
    std::printf("refused %s\n", session.error().message.c_str());
    return 3;
  }
  std::vector<float> hold;
  for (const auto id : session.value().motor_ids()) {
    hold.push_back(static_cast<float>(state.value().position[static_cast<std::size_t>(id)]) + offset_rad);
  }
  std::printf("uuid %s session %s\n", session.value().uuid().c_str(), session.value().session_id().c_str());
  std::fflush(stdout);
  return stream(period, seconds, [&] { return static_cast<bool>(session.value().send_positions(hold)); });
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"stream commands to robotd until killed (test helper)"};
  int domain = 0;
  std::string device = "arm";
  int timeout_ms = 500;
  std::string on_timeout = "DAMPING";
  double rate_hz = 1000;
  double seconds = 0;
  std::string uuid;
  int motors = 6;
  float position_rad = 0;
  float offset_rad = 0;
  app.add_option("--domain", domain)->required();
  app.add_option("--device", device);
  app.add_option("--timeout-ms", timeout_ms);
  app.add_option("--on-timeout", on_timeout);
  app.add_option("--rate", rate_hz);
  app.add_option("--seconds", seconds, "stop after this long and print how many were sent (0: until killed)");
  app.add_option("--uuid", uuid, "stream in the name of this session instead of requesting one");
  app.add_option("--motors", motors, "with --uuid: command motors 0..N-1");
  app.add_option("--position", position_rad, "with --uuid: the position commanded to every motor, rad");
  app.add_option("--offset", offset_rad, "with a session: command the positions found at the start plus this, rad");
  CLI11_PARSE(app, argc, argv);

  robotd::ClientOptions options = robotd::ClientOptions::from_environment();
  options.domain_id = domain;
  options.node_name = "command_streamer";
  auto client = robotd::Client::connect(options);
  if (!client) {
    std::printf("failed %s\n", client.error().message.c_str());
    return 1;
  }
  const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / rate_hz));
  if (!uuid.empty()) return stream_in_the_name_of(client.value(), uuid, device, motors, position_rad, period, seconds);
  return hold_a_session(client.value(), device, on_timeout, timeout_ms, offset_rad, period, seconds);
}
