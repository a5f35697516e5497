// robotd_bench_closed_loop: a closed-loop client. Takes a torque session on every motor of a
// device and runs a PD law (each joint held at where it started plus a slow sine) through
// Session::run_control_loop for --seconds, at whatever rate the device offers its states. Per
// tick it records, all on CLOCK_MONOTONIC (same host as robotd): the tick's deadline, when robotd's
// loop handed the state over and when robotd wrote it (from the TickState), when the law was called
// (the client received it) and when it returned (the client sends the answer). Then robotd's
// SessionInfo for the session (the newest /session_status, published once a second).
// With --rt-priority N the whole process (the law's thread and every DDS thread, created after)
// runs SCHED_FIFO N, as a real controller would.
// Prints one JSON line: {"report": {...}, "info": {...}, "tick": [...], "deadline_ns": [...],
// "ready_ns": [...], "published_ns": [...], "received_ns": [...], "sent_ns": [...]}.
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <sched.h>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "robotd/client.hpp"

namespace {

std::int64_t now_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

// What the client saw of one tick; preallocated for the whole run, so recording allocates nothing.
struct TickRecord {
  std::uint64_t tick = 0;
  std::int64_t deadline_ns = 0;
  std::int64_t ready_ns = 0;
  std::int64_t published_ns = 0;
  std::int64_t received_ns = 0;
  std::int64_t sent_ns = 0;
};

template <class Field>
std::string json_array(const std::vector<TickRecord>& records, Field field) {
  std::string out = "[";
  for (std::size_t i = 0; i < records.size(); ++i) {
    out += (i == 0 ? "" : ",") + std::to_string(records[i].*field);
  }
  return out + "]";
}

std::string report_json(const robotd::ControlLoopReport& report) {
  return "{\"ticks_seen\": " + std::to_string(report.ticks_seen) +
         ", \"ticks_answered\": " + std::to_string(report.ticks_answered) +
         ", \"ticks_skipped\": " + std::to_string(report.ticks_skipped) +
         ", \"first_tick\": " + std::to_string(report.first_tick) +
         ", \"last_tick\": " + std::to_string(report.last_tick) + "}";
}

std::string info_json(const robotd::SessionInfo& info) {
  return "{\"closed_loop\": " + std::string(info.closed_loop ? "true" : "false") +
         ", \"ticks_to_answer\": " + std::to_string(info.ticks_to_answer) +
         ", \"ticks_answered_in_time\": " + std::to_string(info.ticks_answered_in_time) +
         ", \"ticks_answered_late\": " + std::to_string(info.ticks_answered_late) +
         ", \"ticks_unanswered\": " + std::to_string(info.ticks_unanswered) +
         ", \"command_success_rate\": " + std::to_string(info.command_success_rate) + "}";
}

int run(int argc, char** argv) {
  CLI::App app{"closed-loop PD control through robotd, timed per tick (bench tool)"};
  int domain = 0;
  std::string device = "arm";
  double seconds = 10;
  double kp = 20.0;  // N·m/rad
  double kd = 1.0;   // N·m·s/rad
  int rt_priority = 0;
  app.add_option("--domain", domain)->required();
  app.add_option("--device", device);
  app.add_option("--seconds", seconds)->check(CLI::Range(0.1, 3600.0));
  app.add_option("--kp", kp)->check(CLI::Range(0.0, 1000.0));
  app.add_option("--kd", kd)->check(CLI::Range(0.0, 100.0));
  app.add_option("--rt-priority", rt_priority, "SCHED_FIFO priority of the whole process (0 = SCHED_OTHER)")
      ->check(CLI::Range(0, 98));
  CLI11_PARSE(app, argc, argv);

  if (rt_priority > 0) {  // before the client: its DDS threads inherit the policy
    const sched_param param{.sched_priority = rt_priority};
    if (sched_setscheduler(0, SCHED_FIFO, &param) != 0) {
      std::fprintf(stderr, "SCHED_FIFO %d refused: %s (needs root or CAP_SYS_NICE; or leave out --rt-priority)\n",
                   rt_priority, std::strerror(errno));
      return 1;
    }
  }

  robotd::ClientOptions options;
  options.domain_id = domain;
  options.node_name = "bench_closed_loop";
  auto client = robotd::Client::connect(options);
  if (!client) {
    std::fprintf(stderr, "%s\n", client.error().message.c_str());
    return 1;
  }
  robotd::SessionRequest request;
  request.device = device;
  request.mode = robotd::ControlMode::kTorque;
  request.on_timeout = robotd::Behavior::kDamping;
  request.timeout = std::chrono::milliseconds(200);
  request.on_release = robotd::Behavior::kDamping;
  request.closed_loop = true;
  auto session = client.value().request_control(request);
  if (!session) {
    std::fprintf(stderr, "%s\n", session.error().message.c_str());
    return 1;
  }

  // Room for every tick at up to 2 kHz; a faster device's later ticks go unrecorded.
  std::vector<TickRecord> records(static_cast<std::size_t>(seconds * 2000) + 1000);
  std::size_t recorded = 0;
  std::vector<double> start_position;
  robotd::Command command;
  const auto law = [&](const robotd::TickState& state) -> const robotd::Command& {
    const std::int64_t received = now_ns();
    if (start_position.empty()) start_position = state.position;
    const double t = static_cast<double>(state.deadline_steady_ns) * 1e-9;
    command.torques.resize(state.position.size());
    for (std::size_t j = 0; j < state.position.size(); ++j) {
      const double reference = start_position[j] + 0.2 * std::sin(2.0 * M_PI * 0.5 * t);
      command.torques[j] = static_cast<float>(kp * (reference - state.position[j]) - kd * state.velocity[j]);
    }
    if (recorded < records.size()) {
      records[recorded++] = {
          state.tick, state.deadline_steady_ns, state.state_ready_steady_ns, state.published_steady_ns, received,
          now_ns()};
    }
    return command;
  };
  robotd::ControlLoopOptions loop_options;
  loop_options.duration = std::chrono::milliseconds(static_cast<std::int64_t>(seconds * 1000));
  const auto report = session.value().run_control_loop(law, loop_options);
  if (!report) {
    std::fprintf(stderr, "control loop: %s\n", report.error().message.c_str());
    return 1;
  }
  // Right after the loop: the newest /session_status still speaks of the run, not of the ticks
  // after it, which this session no longer answers.
  const auto info = session.value().info(std::chrono::seconds(2));
  if (!info) {
    std::fprintf(stderr, "session info: %s\n", info.error().message.c_str());
    return 1;
  }
  (void)session.value().release(robotd::Behavior::kDamping);
  records.resize(recorded);
  std::printf(
      "{\"device\": \"%s\", \"report\": %s, \"info\": %s, \"tick\": %s, \"deadline_ns\": %s, \"ready_ns\": %s, "
      "\"published_ns\": %s, \"received_ns\": %s, \"sent_ns\": %s}\n",
      device.c_str(), report_json(report.value()).c_str(), info_json(info.value()).c_str(),
      json_array(records, &TickRecord::tick).c_str(), json_array(records, &TickRecord::deadline_ns).c_str(),
      json_array(records, &TickRecord::ready_ns).c_str(), json_array(records, &TickRecord::published_ns).c_str(),
      json_array(records, &TickRecord::received_ns).c_str(), json_array(records, &TickRecord::sent_ns).c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "robotd_bench_closed_loop: %s\n", e.what());
    return 1;
  }
}
