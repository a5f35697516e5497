// robotd_bench_reset_zero: calls /reset_zero on a device once for every line read on stdin, so a
// bench can start the zeroing and then do something while it runs (engage the e-stop). Neither
// robotctl nor the Python client offers /reset_zero. Prints one JSON line per call:
// {"ok": true|false, "message": "..."} (robotd's refusal, e.g. the zeroing aborted by an e-stop).
// Ends at the end of stdin.
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "robotd/client.hpp"

int main(int argc, char** argv) {
  CLI::App app{"call /reset_zero once per line on stdin (bench tool)"};
  int domain = 0;
  std::string device = "arm";
  std::vector<std::int32_t> motors;
  int timeout_ms = 10'000;
  app.add_option("--domain", domain)->required();
  app.add_option("--device", device);
  app.add_option("--motors", motors, "motor ids to zero (default: all)");
  app.add_option("--timeout-ms", timeout_ms)->check(CLI::Range(100, 60'000));
  CLI11_PARSE(app, argc, argv);

  robotd::ClientOptions options;
  options.domain_id = domain;
  options.node_name = "bench_reset_zero";
  auto client = robotd::Client::connect(options);
  if (!client) {
    std::cerr << client.error().message << "\n";
    return 1;
  }
  std::cout << nlohmann::json{{"ready", true}}.dump() << std::endl;
  for (std::string line; std::getline(std::cin, line);) {
    const auto zeroed = client.value().reset_zero(device, motors, std::chrono::milliseconds(timeout_ms));
    std::cout << nlohmann::json{{"ok", zeroed.ok()}, {"message", zeroed ? "zeroed" : zeroed.error().message}}.dump()
              << std::endl;
  }
  return 0;
}
