// robotd_bench_stream: acquires every motor of a device and streams position commands (a slow
// sine, so the arm really moves) at --rate Hz for --seconds on absolute deadlines, the way a
// real-time client would. Each command carries its CLOCK_MONOTONIC publish time
// (ControlCommand.sent_steady_ns), which is what the command-latency bench measures against.
// With --sweep-seconds T the period is lengthened by period / (rate × T), so the client's
// phase against robotd's tick moves once through a whole period every T seconds: a client that
// is not phase-locked to robotd sees every phase, which is what the latency bench measures.
// With --aligned the client keeps no clock of its own: each command goes out through
// Session::send_aligned, --lead-us before robotd's next tick (one per tick; --rate is ignored).
// Prints one JSON line: {"sent": N, "failed": N, "rate_hz": R, "seconds": S}.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

#include <CLI/CLI.hpp>

#include "robotd/client.hpp"

int main(int argc, char** argv) {
  CLI::App app{"stream position commands to robotd (bench tool)"};
  int domain = 0;
  std::string device = "arm";
  double rate_hz = 1000;
  double seconds = 10;
  double sweep_seconds = 0;
  bool aligned = false;
  int lead_us = static_cast<int>(robotd::kDefaultSendLead.count());
  app.add_option("--domain", domain)->required();
  app.add_option("--sweep-seconds", sweep_seconds, "drift through one period of phase every this many seconds")
      ->check(CLI::Range(0.1, 3600.0));
  app.add_option("--device", device);
  app.add_option("--rate", rate_hz)->check(CLI::Range(1.0, 10000.0));
  app.add_option("--seconds", seconds)->check(CLI::Range(0.1, 3600.0));
  app.add_flag("--aligned", aligned, "send each command --lead-us before robotd's next tick (send_aligned)");
  app.add_option("--lead-us", lead_us, "with --aligned: how long before the tick")->check(CLI::Range(0, 100000));
  CLI11_PARSE(app, argc, argv);

  robotd::ClientOptions options;
  options.domain_id = domain;
  options.node_name = "bench_stream";
  auto client = robotd::Client::connect(options);
  if (!client) {
    std::fprintf(stderr, "%s\n", client.error().message.c_str());
    return 1;
  }
  robotd::SessionRequest request;
  request.device = device;
  request.timeout = std::chrono::milliseconds(500);
  auto session = client.value().request_control(request);
  if (!session) {
    std::fprintf(stderr, "%s\n", session.error().message.c_str());
    return 1;
  }
  const std::size_t joints = session.value().motor_ids().size();
  const double period_s = 1.0 / rate_hz;
  const double drift_s = sweep_seconds > 0 ? period_s / (rate_hz * sweep_seconds) : 0.0;
  const auto period = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(period_s + drift_s));
  const auto start = std::chrono::steady_clock::now();
  const auto end =
      start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(seconds));
  long sent = 0;
  long failed = 0;
  std::vector<float> positions(joints);
  robotd::Command command;
  for (auto next = start; next < end; next += period) {
    if (aligned) {
      next = std::chrono::steady_clock::now();
    } else {
      std::this_thread::sleep_until(next);
    }
    const double t = std::chrono::duration<double>(next - start).count();
    for (std::size_t j = 0; j < joints; ++j) positions[j] = static_cast<float>(0.2 * std::sin(2.0 * M_PI * 0.25 * t));
    command.positions = positions;
    const auto published = aligned ? session.value().send_aligned(command, std::chrono::microseconds(lead_us))
                                   : session.value().command(command);
    if (published) {
      ++sent;
    } else {
      ++failed;
    }
  }
  (void)session.value().release(robotd::Behavior::kKeep);
  std::printf("{\"sent\": %ld, \"failed\": %ld, \"rate_hz\": %g, \"seconds\": %g}\n", sent, failed, rate_hz, seconds);
  return 0;
}
