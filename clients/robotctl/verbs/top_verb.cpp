// top: a live view of every device's loop health and the sessions, redrawn in place.
#include <array>
#include <chrono>
#include <ctime>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <unistd.h>
#include <vector>

#include "exit_status.hpp"
#include "message_text.hpp"
#include "text_format.hpp"
#include "text_table.hpp"
#include "verbs/verbs.hpp"

namespace robotctl {
namespace {

using Clock = std::chrono::steady_clock;

// A status older than this is shown as stale: robotd (or the device's publisher) has gone quiet.
constexpr auto kStaleAfter = std::chrono::seconds(2);

struct TopOptions {
  int interval_ms = 500;
  bool once = false;
};

// The latest /device_status of each device and the latest /session_status, as they arrive.
class LiveState {
 public:
  void update(const robotd::DeviceStatus& status) {
    const std::lock_guard lock(mutex_);
    devices_[status.device] = Received{status, Clock::now()};
  }
  void update(const robotd::SessionStatus& status) {
    const std::lock_guard lock(mutex_);
    sessions_ = status;
  }
  /// Whether every device in `devices` has reported, and the sessions too.
  bool complete(const std::vector<robotd::DeviceInfo>& devices) const {
    const std::lock_guard lock(mutex_);
    for (const auto& device : devices) {
      if (devices_.count(device.name) == 0) return false;
    }
    return sessions_.has_value();
  }
  std::string frame(const std::vector<robotd::DeviceInfo>& devices) const;

 private:
  struct Received {
    robotd::DeviceStatus status;
    Clock::time_point at;
  };
  mutable std::mutex mutex_;
  std::map<std::string, Received> devices_;
  std::optional<robotd::SessionStatus> sessions_;
};

std::string LiveState::frame(const std::vector<robotd::DeviceInfo>& devices) const {
  const std::lock_guard lock(mutex_);
  TextTable table(
      {"DEVICE", "STATE", "WAKE p50/p99/max µs", "EXEC p99 µs", "OVERRUNS", "TICKS", "COMMANDS ok/rejected"});
  for (const auto& device : devices) {
    const auto found = devices_.find(device.name);
    if (found == devices_.end()) {
      table.add_row({device.name, "waiting for /device_status"});
      continue;
    }
    const robotd::DeviceStatus& status = found->second.status;
    const robotd::LoopStatistics& loop = status.loop;
    const auto age = Clock::now() - found->second.at;
    std::string state = state_text(status);
    if (age > kStaleAfter) {
      state += " (stale: last status " + std::to_string(std::chrono::duration_cast<std::chrono::seconds>(age).count()) +
               " s ago)";
    }
    table.add_row({device.name, state,
                   fixed(loop.wake_latency_p50_us, 1) + "/" + fixed(loop.wake_latency_p99_us, 1) + "/" +
                       fixed(loop.wake_latency_max_us, 1),
                   fixed(loop.execution_p99_us, 1), std::to_string(loop.overruns), std::to_string(loop.ticks),
                   std::to_string(status.commands.accepted) + "/" + std::to_string(status.commands.rejected_total())});
  }
  std::string text = table.render() + "\n";
  text += sessions_ ? session_table(*sessions_) : "waiting for /session_status\n";
  return text;
}

std::string clock_text() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  std::array<char, 16> text{};
  std::strftime(text.data(), text.size(), "%H:%M:%S", &local);
  return text.data();
}

// Redraws over the previous frame: home, each line cleared to its end, the rest of the screen cleared.
std::string in_place(const std::string& frame) {
  std::string text = "\x1b[H";
  for (std::size_t begin = 0; begin < frame.size();) {
    const std::size_t end = frame.find('\n', begin);
    text += frame.substr(begin, end - begin) + "\x1b[K\n";
    begin = end == std::string::npos ? frame.size() : end + 1;
  }
  return text + "\x1b[J";
}

// Whether every device and the sessions reported before `deadline` (or a stop signal).
bool wait_until_complete(StopSignals& stop, const LiveState& live, const std::vector<robotd::DeviceInfo>& devices,
                         Clock::time_point deadline) {
  while (!live.complete(devices)) {
    if (stop.wait_until(deadline) != StopSignals::Wake::kWoken) return live.complete(devices);
  }
  return true;
}

int print_once(VerbContext& context, const LiveState& live, const std::vector<robotd::DeviceInfo>& devices) {
  const bool complete =
      wait_until_complete(context.stop, live, devices, Clock::now() + context.client.options().service_timeout);
  std::cout << live.frame(devices) << std::flush;
  if (!complete) {
    return report_failure("not every device reported within " +
                          std::to_string(context.client.options().service_timeout.count()) + " ms");
  }
  return kExitSuccess;
}

int top(VerbContext& context, const TopOptions& options) {
  auto devices = context.client.list_devices();
  if (!devices) return report_failure(devices.error(), context.client.options());
  LiveState live;
  StopSignals& stop = context.stop;
  const robotd::Subscription device_statuses = context.client.on_device_status([&](const robotd::DeviceStatus& status) {
    live.update(status);
    stop.wake();
  });
  const robotd::Subscription session_statuses =
      context.client.on_session_status([&](const robotd::SessionStatus& status) {
        live.update(status);
        stop.wake();
      });
  if (options.once) return print_once(context, live, devices.value());

  const bool terminal = isatty(STDOUT_FILENO) == 1;
  if (terminal) std::cout << "\x1b[2J";
  const auto interval = std::chrono::milliseconds(options.interval_ms);
  // The first frame waits (up to one interval) for every device, so it does not open half empty.
  wait_until_complete(stop, live, devices.value(), Clock::now() + interval);
  auto next_frame = Clock::now();
  while (true) {
    const std::string frame = "robotd on DDS domain " + std::to_string(context.client.options().domain_id) + "  " +
                              clock_text() + "  (every " + std::to_string(options.interval_ms) +
                              " ms, Ctrl-C quits)\n\n" + live.frame(devices.value());
    std::cout << (terminal ? in_place(frame) : frame + "\n") << std::flush;
    next_frame += interval;
    StopSignals::Wake wake = StopSignals::Wake::kWoken;
    while (wake == StopSignals::Wake::kWoken) wake = stop.wait_until(next_frame);
    if (wake == StopSignals::Wake::kStopSignal) return kExitSuccess;
  }
}

}  // namespace

Verb add_top_verb(CLI::App& app) {
  auto options = std::make_shared<TopOptions>();
  CLI::App* command = app.add_subcommand("top", "A live view of every device's loop health and the sessions");
  command->add_option("--interval-ms", options->interval_ms, "Redraw period in ms")
      ->check(CLI::Range(50, 60'000))
      ->capture_default_str();
  command->add_flag("--once", options->once, "Print one frame (once every device has reported) and exit");
  command->footer(
      "Redrawn in place every --interval-ms: per device the state, loop wake latency p50/p99/max, execution p99, "
      "overruns, ticks and commands accepted/rejected; then the sessions with their time left. Ctrl-C quits.\n\n"
      "Example:\n  robotctl top\n  robotctl top --once");
  return Verb{command, true, [options](VerbContext& context) { return top(context, *options); }};
}

}  // namespace robotctl
