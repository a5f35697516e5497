// robotd_bench_tick: the cost of one tick of a device's loop (ControlLoop::tick): mailbox,
// session check, safety and rate limiting, and the sim driver's read and write, for a
// 6-joint and a 23-joint device with a session streaming a new target every tick. The sim
// plugin is loaded through robotd's own plugin loader and configured like a real device.
//
//   robotd_bench_tick [Google Benchmark flags]     wall time per tick
//   robotd_bench_tick --callgrind-ticks N --joints J
//       under `valgrind --tool=callgrind --collect-atstart=no`: collects exactly N ticks,
//       so instructions per tick = callgrind's total / N (repeatable on a noisy machine)
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <valgrind/callgrind.h>

#include <benchmark/benchmark.h>

#include "config/config.hpp"
#include "device/control_loop.hpp"
#include "device/device.hpp"
#include "plugin/plugin_loader.hpp"
#include "rt/monotonic_clock.hpp"

namespace {

using robotd::device::ControlEvent;

/// A configured sim device with a session on every joint and a loop to tick by hand.
class TickBench {
 public:
  explicit TickBench(int joints) {
    robotd::config::DeviceConfig config;
    config.path = "devices[0]";
    config.name = "bench";
    config.driver = "sim";
    config.params = {{"joint_count", joints}};
    auto plugin = robotd::plugin::load_driver_file(ROBOTD_SIM_PLUGIN, "sim");
    if (!plugin) fail(plugin.error().message);
    device_ = std::make_unique<robotd::device::Device>(config, std::move(plugin.value()));
    if (auto configured = device_->configure(); !configured) fail(configured.error().message);
    if (auto connected = device_->driver().connect(); !connected) fail(connected.error().message);
    loop_ = std::make_unique<robotd::device::ControlLoop>(device_->driver(), device_->model(), device_->channel(),
                                                          robotd::device::LoopSettings{});
    ControlEvent start;
    start.type = ControlEvent::Type::kSessionStart;
    start.generation = 1;
    start.timeout_ns = 60 * robotd::rt::kNsPerSecond;
    start.granted_ns = robotd::rt::monotonic_now_ns();
    start.default_kp.fill(robotd::device::kNoGain);
    start.default_kd.fill(robotd::device::kNoGain);
    for (int j = 0; j < joints; ++j) start.motors.set(static_cast<std::size_t>(j));
    device_->channel().post(start);
    for (int i = 0; i < 100; ++i) tick();  // first feedback, session started, caches warm
  }

  /// What the command intake does when a command arrives: new targets for every joint.
  void new_command() {
    const std::int64_t now = robotd::rt::monotonic_now_ns();
    auto& snapshot = device_->channel().commands.write_buffer();
    ++sequence_;
    const auto position = static_cast<float>(0.3 * std::sin(static_cast<double>(sequence_) * 1e-3));
    for (std::size_t j = 0; j < device_->model().joint_count(); ++j) {
      auto& target = snapshot.joints[j];
      target.generation = 1;
      target.sequence = sequence_;
      target.received_ns = now;
      target.sent_ns = now;
      target.update.joint = static_cast<std::uint8_t>(j);
      target.update.fields = robotd::control::kHasPosition;
      target.update.position = position;
    }
    snapshot.slots[0] = robotd::device::SlotActivity{1, now};
    device_->channel().commands.publish();
  }

  void tick() {
    const std::int64_t now = robotd::rt::monotonic_now_ns();
    loop_->tick(now, now);
    drain();
  }

 private:
  // The state publisher's part: keep the rings from filling up.
  void drain() {
    auto& channel = device_->channel();
    while (channel.timings.pop()) {
    }
    while (channel.loop_events.pop()) {
    }
    (void)channel.state.take();
  }

  [[noreturn]] static void fail(const std::string& message) { throw std::runtime_error(message); }

  std::unique_ptr<robotd::device::Device> device_;
  std::unique_ptr<robotd::device::ControlLoop> loop_;
  std::uint64_t sequence_ = 0;
};

void tick_with_new_command(benchmark::State& state) {
  TickBench bench(static_cast<int>(state.range(0)));
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): Google Benchmark's loop idiom
    state.PauseTiming();
    bench.new_command();
    state.ResumeTiming();
    bench.tick();
  }
}
BENCHMARK(tick_with_new_command)->Arg(6)->Arg(23)->UseRealTime();

int callgrind_ticks(int ticks, int joints) {
  TickBench bench(joints);
  for (int i = 0; i < ticks; ++i) {
    bench.new_command();
    CALLGRIND_TOGGLE_COLLECT;
    bench.tick();
    CALLGRIND_TOGGLE_COLLECT;
  }
  std::printf("{\"ticks\": %d, \"joints\": %d}\n", ticks, joints);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    for (int i = 1; i + 3 < argc; ++i) {
      if (std::strcmp(argv[i], "--callgrind-ticks") == 0 && std::strcmp(argv[i + 2], "--joints") == 0) {
        return callgrind_ticks(std::stoi(argv[i + 1]), std::stoi(argv[i + 3]));
      }
    }
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "robotd_bench_tick: %s\n", e.what());
    return 1;
  }
}
