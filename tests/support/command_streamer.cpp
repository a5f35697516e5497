// A client in its own process for tests that kill a client: acquires a session, prints
// "uuid <uuid>", then streams position commands holding the arm at its current position
// (or --position) at --rate Hz until it is killed.
#include <chrono>
#include <cstdio>
#include <thread>

#include <CLI/CLI.hpp>

#include "robotd/client.hpp"

int main(int argc, char** argv) {
  CLI::App app{"stream commands to robotd until killed (test helper)"};
  int domain = 0;
  std::string device = "arm";
  int timeout_ms = 500;
  std::string on_timeout = "DAMPING";
  double rate_hz = 1000;
  app.add_option("--domain", domain)->required();
  app.add_option("--device", device);
  app.add_option("--timeout-ms", timeout_ms);
  app.add_option("--on-timeout", on_timeout);
  app.add_option("--rate", rate_hz);
  CLI11_PARSE(app, argc, argv);

  robotd::ClientOptions options;
  options.domain_id = domain;
  options.node_name = "command_streamer";
  auto client = robotd::Client::connect(options);
  if (!client) return 1;
  const auto behavior = robotd::parse_behavior(on_timeout);
  if (!behavior) return 2;
  robotd::SessionRequest request;
  request.device = device;
  request.on_timeout = *behavior;
  request.timeout = std::chrono::milliseconds(timeout_ms);
  auto session = client.value().request_control(request);
  if (!session) {
    std::printf("refused %s\n", session.error().message.c_str());
    return 3;
  }
  auto state = client.value().next_joint_state(device, std::chrono::seconds(2));
  if (!state) return 4;
  std::vector<float> hold;
  for (const auto id : session.value().motor_ids()) {
    hold.push_back(static_cast<float>(state.value().position[static_cast<std::size_t>(id)]));
  }
  std::printf("uuid %s\n", session.value().uuid().c_str());
  std::fflush(stdout);
  const auto period =
      std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(1.0 / rate_hz));
  auto next = std::chrono::steady_clock::now();
  while (true) {
    (void)session.value().send_positions(hold);
    next += period;
    std::this_thread::sleep_until(next);
  }
}
