// robotd_bench_flood: --writers command writers on /control_command, each publishing a position
// command for every motor under a uuid robotd never gave out, at --rate Hz each for --seconds,
// on absolute deadlines (a late period is caught up, not skipped). Each writer has the client
// library's writer QoS, so robotd sees --writers foreign clients. Waits until robotd's command
// reader is matched before it starts. Prints one JSON line: {"sent": N, "failed": N}.
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include "wire/participant.hpp"
#include "wire/qos.hpp"
#include "wire/topic_io.hpp"
#include "wire/topics.hpp"

namespace {

constexpr int kWriterDepth = 8;  // the client library's command writer
// robotd's uuids are random version-4 uuids: this one is never given out.
constexpr const char* kNeverGivenOut = "00000000-0000-4000-8000-000000000000";

template <class T>
T must(robotd::Result<T> result) {
  if (!result) throw std::runtime_error(result.error().message);
  return std::move(result.value());
}

int run(int argc, char** argv) {
  CLI::App app{"flood /control_command with commands under a uuid robotd never gave out (bench tool)"};
  int domain = 0;
  int writers = 1;
  double rate_hz = 10000;
  double seconds = 3;
  std::string device = "arm";
  int motors = 6;
  app.add_option("--domain", domain)->required();
  app.add_option("--writers", writers, "foreign writers in this process")->check(CLI::Range(1, 64));
  app.add_option("--rate", rate_hz, "commands per second per writer")->check(CLI::Range(1.0, 100000.0));
  app.add_option("--seconds", seconds)->check(CLI::Range(0.1, 3600.0));
  app.add_option("--device", device);
  app.add_option("--motors", motors, "command motors 0..N-1")->check(CLI::Range(1, 64));
  CLI11_PARSE(app, argc, argv);

  robotd::wire::DdsSettings settings;
  settings.domain_id = domain;
  auto participant = must(robotd::wire::Participant::create(settings));
  const auto qos = robotd::wire::reliable_qos(kWriterDepth);
  std::vector<robotd::wire::TopicWriter<robotd::ControlCommand>> flood;
  flood.reserve(static_cast<std::size_t>(writers));
  for (int i = 0; i < writers; ++i) {
    flood.push_back(must(robotd::wire::TopicWriter<robotd::ControlCommand>::create(
        participant, robotd::wire::kControlCommandTopic, qos.get())));
  }
  const auto match_deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  for (const auto& writer : flood) {
    while (writer.matched_readers() == 0 && std::chrono::steady_clock::now() < match_deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }

  robotd::ControlCommand command;
  command.uuid = kNeverGivenOut;
  command.device = device;
  for (int id = 0; id < motors; ++id) {
    command.motor_ids.push_back(id);
    command.positions.push_back(1.0F);
  }
  const auto period =
      std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(1.0 / rate_hz));
  const auto start = std::chrono::steady_clock::now();
  const auto end =
      start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(seconds));
  long sent = 0;
  long failed = 0;
  for (auto next = start; next < end; next += period) {
    std::this_thread::sleep_until(next);
    for (const auto& writer : flood) {
      if (writer.write(command)) {
        ++sent;
      } else {
        ++failed;
      }
    }
  }
  std::printf("{\"sent\": %ld, \"failed\": %ld}\n", sent, failed);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "robotd_bench_flood: %s\n", e.what());
    return 1;
  }
}
