// robotd_bench_pingpong: the DDS baseline for the command-latency and closed-loop benches. The
// same message types and sizes, the same QoS as the client's and robotd's writers and readers,
// the same loopback configuration. "pong" answers every ping; "ping" sends at --rate Hz for
// --seconds and measures each round trip on CLOCK_MONOTONIC.
//   --shape command      (default) ping and pong are a client's ControlCommand of --joints
//                        positions, with the command writer's and robotd's command reader's QoS:
//                        the command latency's baseline (one way = round trip / 2).
//   --shape closed_loop  ping is robotd's TickState of --joints joints (position, velocity,
//                        effort) with its tick_state QoS, pong a ControlCommand of --joints
//                        torques answering it: the DDS part of a closed-loop tick's round trip.
// ping prints one JSON line: {"sent": N, "lost": N, "round_trip_ns": [...], "oneway_ns": [round trip / 2, ...]}.
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

constexpr int kCommandWriterDepth = 8;   // the client library's command writer
constexpr int kCommandReaderDepth = 64;  // robotd's command reader
constexpr int kTickStateDepth = 1;       // robotd's tick_state writer and the client's reader

std::int64_t now_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

std::vector<std::int32_t> motor_ids(int joints) {
  std::vector<std::int32_t> ids(static_cast<std::size_t>(joints));
  for (int j = 0; j < joints; ++j) ids[static_cast<std::size_t>(j)] = j;
  return ids;
}

robotd::ControlCommand command_like_a_client(int joints, bool torques) {
  robotd::ControlCommand command;
  command.uuid = "00000000-0000-0000-0000-000000000000";
  command.device = "arm";
  command.motor_ids = motor_ids(joints);
  (torques ? command.torques : command.positions).assign(static_cast<std::size_t>(joints), 0.1F);
  return command;
}

robotd::TickState tick_state_like_robotd(int joints) {
  robotd::TickState state;
  state.header.frame_id = "arm";
  state.state = robotd::DeviceState::kRunning;
  state.period_ns = 1'000'000;
  state.position.assign(static_cast<std::size_t>(joints), 0.1);
  state.velocity.assign(static_cast<std::size_t>(joints), 0.2);
  state.effort.assign(static_cast<std::size_t>(joints), 0.3);
  return state;
}

// Where each message type carries the ping's send time, and how a pong answers it.
std::int64_t sent_ns(const robotd::ControlCommand& command) { return command.sent_steady_ns; }
std::int64_t sent_ns(const robotd::TickState& state) { return state.published_steady_ns; }
void stamp(robotd::ControlCommand& command, std::int64_t ns) { command.sent_steady_ns = ns; }
void stamp(robotd::TickState& state, std::int64_t ns) { state.published_steady_ns = ns; }

template <class T>
T must(robotd::Result<T> result) {
  if (!result) throw std::runtime_error(result.error().message);
  return std::move(result.value());
}

struct Settings {
  int domain = 0;
  bool ping = false;
  double rate_hz = 1000;
  double seconds = 10;
};

// History depths of the four endpoints, as the messages' real writers and readers have them.
struct QueueDepths {
  int ping_writer;
  int ping_reader;
  int pong_writer;
  int pong_reader;
};

// Ping is the type the ping side writes, Pong the one the pong side answers with.
template <class Ping, class Pong>
int run(const Settings& settings, const Ping& ping_message, Pong pong_message, QueueDepths depths) {
  robotd::wire::DdsSettings dds;
  dds.domain_id = settings.domain;
  auto participant = must(robotd::wire::Participant::create(dds));
  const auto ping_writer_qos = robotd::wire::reliable_qos(depths.ping_writer);
  const auto ping_reader_qos = robotd::wire::reliable_qos(depths.ping_reader);
  const auto pong_writer_qos = robotd::wire::reliable_qos(depths.pong_writer);
  const auto pong_reader_qos = robotd::wire::reliable_qos(depths.pong_reader);

  if (!settings.ping) {  // answer until killed, the ping's send time copied into the pong
    auto reader = must(robotd::wire::TopicReader<Ping>::create(participant, "rt/bench_ping", ping_reader_qos.get()));
    auto writer = must(robotd::wire::TopicWriter<Pong>::create(participant, "rt/bench_pong", pong_writer_qos.get()));
    robotd::wire::Entity waitset(dds_create_waitset(participant.handle()));
    dds_waitset_attach(waitset.get(), dds_create_readcondition(reader.handle(), DDS_ANY_STATE), 0);
    while (true) {
      dds_waitset_wait(waitset.get(), nullptr, 0, DDS_SECS(1));
      reader.take_each([&](Ping&& sample, const dds_sample_info_t&) {
        stamp(pong_message, sent_ns(sample));
        (void)writer.write(pong_message);
      });
    }
  }

  auto writer = must(robotd::wire::TopicWriter<Ping>::create(participant, "rt/bench_ping", ping_writer_qos.get()));
  auto reader = must(robotd::wire::TopicReader<Pong>::create(participant, "rt/bench_pong", pong_reader_qos.get()));
  robotd::wire::Entity waitset(dds_create_waitset(participant.handle()));
  dds_waitset_attach(waitset.get(), dds_create_readcondition(reader.handle(), DDS_ANY_STATE), 0);
  // Wait until both directions are matched, so no ping is sent into the void.
  const auto match_deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while ((writer.matched_readers() == 0 || reader.matched_writers() == 0) &&
         std::chrono::steady_clock::now() < match_deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  std::mutex mutex;
  std::vector<std::int64_t> round_trip_ns;
  std::atomic<bool> receiving{true};
  std::thread receiver([&] {
    while (receiving.load()) {
      dds_waitset_wait(waitset.get(), nullptr, 0, DDS_MSECS(100));
      reader.take_each([&](Pong&& sample, const dds_sample_info_t&) {
        const std::int64_t round_trip = now_ns() - sent_ns(sample);
        const std::lock_guard lock(mutex);
        round_trip_ns.push_back(round_trip);
      });
    }
  });

  Ping message = ping_message;
  const auto period = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(1.0 / settings.rate_hz));
  const auto start = std::chrono::steady_clock::now();
  const auto end = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                               std::chrono::duration<double>(settings.seconds));
  long sent = 0;
  for (auto next = start; next < end; next += period) {
    std::this_thread::sleep_until(next);
    stamp(message, now_ns());
    if (writer.write(message)) ++sent;
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the last pongs
  receiving.store(false);
  receiver.join();

  const std::lock_guard lock(mutex);
  std::string round_trips;
  std::string oneways;
  for (const auto value : round_trip_ns) {
    round_trips += (round_trips.empty() ? "" : ",") + std::to_string(value);
    oneways += (oneways.empty() ? "" : ",") + std::to_string(value / 2);
  }
  std::printf("{\"sent\": %ld, \"lost\": %ld, \"round_trip_ns\": [%s], \"oneway_ns\": [%s]}\n", sent,
              sent - static_cast<long>(round_trip_ns.size()), round_trips.c_str(), oneways.c_str());
  return 0;
}

int run(int argc, char** argv) {
  CLI::App app{"DDS ping-pong with robotd's message types and QoS (bench tool)"};
  Settings settings;
  std::string role;
  std::string shape = "command";
  int joints = 6;
  app.add_option("--domain", settings.domain)->required();
  app.add_option("--role", role)->required()->check(CLI::IsMember({"ping", "pong"}));
  app.add_option("--shape", shape, "command: ControlCommand both ways; closed_loop: TickState, ControlCommand back")
      ->check(CLI::IsMember({"command", "closed_loop"}));
  app.add_option("--joints", joints, "joints per message")->check(CLI::Range(1, 64));
  app.add_option("--rate", settings.rate_hz)->check(CLI::Range(1.0, 10000.0));
  app.add_option("--seconds", settings.seconds)->check(CLI::Range(0.1, 3600.0));
  CLI11_PARSE(app, argc, argv);
  settings.ping = role == "ping";

  if (shape == "command") {
    return run(settings, command_like_a_client(joints, false), command_like_a_client(joints, false),
               {kCommandWriterDepth, kCommandReaderDepth, kCommandWriterDepth, kCommandReaderDepth});
  }
  return run(settings, tick_state_like_robotd(joints), command_like_a_client(joints, true),
             {kTickStateDepth, kTickStateDepth, kCommandWriterDepth, kCommandReaderDepth});
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
