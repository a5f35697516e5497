// robotd_bench_subscribe: subscribes to /joint_states the way any client would and records
// the header stamp (CLOCK_REALTIME ns, unique per publication) of every sample of --device for
// --seconds, into --output (one stamp per line). The fan-out bench counts, per subscriber, how
// many of the samples robotd published in a window arrived.
// Prints one JSON line: {"received": N}.
#include <chrono>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include "robotd/client.hpp"

int main(int argc, char** argv) {
  CLI::App app{"record /joint_states stamps (bench tool)"};
  int domain = 0;
  std::string device = "arm";
  double seconds = 10;
  std::string output;
  app.add_option("--domain", domain)->required();
  app.add_option("--device", device);
  app.add_option("--seconds", seconds)->check(CLI::Range(0.1, 3600.0));
  app.add_option("--output", output)->required();
  CLI11_PARSE(app, argc, argv);

  robotd::ClientOptions options;
  options.domain_id = domain;
  options.node_name = "bench_subscribe";
  auto client = robotd::Client::connect(options);
  if (!client) {
    std::fprintf(stderr, "%s\n", client.error().message.c_str());
    return 1;
  }
  std::mutex mutex;
  std::vector<std::int64_t> stamps;
  stamps.reserve(static_cast<std::size_t>(seconds * 1100));
  auto subscription = client.value().on_joint_states([&](const robotd::JointState& state) {
    if (state.header.frame_id != device) return;
    const std::lock_guard lock(mutex);
    stamps.push_back(state.header.stamp.to_ns());
  });
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  subscription.reset();

  std::ofstream file(output);
  for (const auto stamp : stamps) file << stamp << '\n';
  std::printf("{\"received\": %zu}\n", stamps.size());
  return file ? 0 : 1;
}
