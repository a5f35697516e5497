// robotd_bench_pingpong: the DDS baseline for command latency. The same message type and size
// as a client's 6-joint ControlCommand, the same QoS as the client's command writer and
// robotd's command reader, the same loopback configuration. "pong" echoes every ping; "ping"
// sends at --rate Hz for --seconds and measures each round trip on CLOCK_MONOTONIC.
// ping prints one JSON line: {"oneway_ns": [round trip / 2, ...], "lost": N}.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include "wire/participant.hpp"
#include "wire/qos.hpp"
#include "wire/topic_io.hpp"

namespace {

constexpr int kWriterDepth = 8;   // the client library's command writer
constexpr int kReaderDepth = 64;  // robotd's command reader

std::int64_t now_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

robotd::ControlCommand command_like_a_client() {
  robotd::ControlCommand command;
  command.uuid = "00000000-0000-0000-0000-000000000000";
  command.device = "arm";
  command.motor_ids = {0, 1, 2, 3, 4, 5};
  command.positions = {0.1F, 0.2F, 0.3F, 0.4F, 0.5F, 0.6F};
  return command;
}

template <class T>
T must(robotd::Result<T> result) {
  if (!result) throw std::runtime_error(result.error().message);
  return std::move(result.value());
}

int run(int argc, char** argv) {
  CLI::App app{"DDS ping-pong with robotd's command type and QoS (bench tool)"};
  int domain = 0;
  std::string role;
  double rate_hz = 1000;
  double seconds = 10;
  app.add_option("--domain", domain)->required();
  app.add_option("--role", role)->required()->check(CLI::IsMember({"ping", "pong"}));
  app.add_option("--rate", rate_hz)->check(CLI::Range(1.0, 10000.0));
  app.add_option("--seconds", seconds)->check(CLI::Range(0.1, 3600.0));
  CLI11_PARSE(app, argc, argv);

  robotd::wire::DdsSettings settings;
  settings.domain_id = domain;
  auto participant = must(robotd::wire::Participant::create(settings));
  const auto writer_qos = robotd::wire::reliable_qos(kWriterDepth);
  const auto reader_qos = robotd::wire::reliable_qos(kReaderDepth);
  const bool ping = role == "ping";
  auto writer = must(robotd::wire::TopicWriter<robotd::ControlCommand>::create(
      participant, ping ? "rt/bench_ping" : "rt/bench_pong", writer_qos.get()));
  auto reader = must(robotd::wire::TopicReader<robotd::ControlCommand>::create(
      participant, ping ? "rt/bench_pong" : "rt/bench_ping", reader_qos.get()));
  robotd::wire::Entity waitset(dds_create_waitset(participant.handle()));
  dds_waitset_attach(waitset.get(), dds_create_readcondition(reader.handle(), DDS_ANY_STATE), 0);

  if (!ping) {  // echo until killed
    while (true) {
      dds_waitset_wait(waitset.get(), nullptr, 0, DDS_SECS(1));
      reader.take_each([&](robotd::ControlCommand&& sample, const dds_sample_info_t&) { (void)writer.write(sample); });
    }
  }

  // Wait until both directions are matched, so no ping is sent into the void.
  const auto match_deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while ((writer.matched_readers() == 0 || reader.matched_writers() == 0) &&
         std::chrono::steady_clock::now() < match_deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  std::mutex mutex;
  std::vector<std::int64_t> oneway_ns;
  std::atomic<bool> receiving{true};
  std::thread receiver([&] {
    while (receiving.load()) {
      dds_waitset_wait(waitset.get(), nullptr, 0, DDS_MSECS(100));
      reader.take_each([&](robotd::ControlCommand&& sample, const dds_sample_info_t&) {
        const std::int64_t round_trip = now_ns() - sample.sent_steady_ns;
        const std::lock_guard lock(mutex);
        oneway_ns.push_back(round_trip / 2);
      });
    }
  });

  robotd::ControlCommand command = command_like_a_client();
  const auto period =
      std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(1.0 / rate_hz));
  const auto start = std::chrono::steady_clock::now();
  const auto end =
      start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(seconds));
  long sent = 0;
  for (auto next = start; next < end; next += period) {
    std::this_thread::sleep_until(next);
    command.sent_steady_ns = now_ns();
    if (writer.write(command)) ++sent;
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the last pongs
  receiving.store(false);
  receiver.join();

  const std::lock_guard lock(mutex);
  std::string samples;
  for (const auto value : oneway_ns) samples += (samples.empty() ? "" : ",") + std::to_string(value);
  std::printf("{\"sent\": %ld, \"lost\": %ld, \"oneway_ns\": [%s]}\n", sent, sent - static_cast<long>(oneway_ns.size()),
              samples.c_str());
  return 0;
}
}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "robotd_bench_pingpong: %s\n", e.what());
    return 1;
  }
}
