// record: write joint states, commands, session and device status to a robotd recording
// (docs/recording.md) as they arrive, until --seconds have passed or Ctrl-C; then say what was
// written. (One topic as JSON lines: robotctl echo TOPIC --json > FILE.)
#include <algorithm>
#include <chrono>
#include <ctime>
#include <iostream>
#include <memory>
#include <vector>

#include "device_lookup.hpp"
#include "exit_status.hpp"
#include "recording/recording_format.hpp"
#include "recording/recording_writer.hpp"
#include "recording_sink.hpp"
#include "text_format.hpp"
#include "verbs/verbs.hpp"

namespace robotctl {
namespace {

using Clock = std::chrono::steady_clock;

// How often buffered records are handed to the kernel: what robotctl being killed can lose.
constexpr auto kFlushPeriod = std::chrono::milliseconds(250);

struct RecordOptions {
  std::string path;
  std::vector<std::string> topics = recording::recordable_topics();
  std::string device;  // "" = every device
  double seconds = 0;  // 0 = until Ctrl-C
};

bool wants(const RecordOptions& options, const std::string& topic) {
  return std::find(options.topics.begin(), options.topics.end(), topic) != options.topics.end();
}

std::int64_t realtime_ns() {
  timespec now{};
  clock_gettime(CLOCK_REALTIME, &now);
  return static_cast<std::int64_t>(now.tv_sec) * 1'000'000'000 + now.tv_nsec;
}

recording::Description describe(const RecordOptions& options, const std::vector<robotd::DeviceInfo>& devices,
                                std::int32_t domain_id) {
  recording::Description description{ROBOTD_VERSION, realtime_ns(), domain_id, {}, {}};
  // In the order of recordable_topics(), whatever the order on the command line.
  for (const auto& topic : recording::recordable_topics()) {
    if (wants(options, topic)) description.topics.push_back(topic);
  }
  for (const auto& device : devices) {
    if (options.device.empty() || device.name == options.device) {
      description.devices.push_back(recording::recorded_device(device));
    }
  }
  return description;
}

std::string summary_text(const RecordingSink::Summary& summary, const std::string& path) {
  const auto& topics = recording::recordable_topics();
  std::string text =
      "recorded " + fixed(summary.duration_s, 2) + " s to " + path + " (" + std::to_string(summary.bytes) + " bytes):";
  for (std::size_t i = 0; i < topics.size(); ++i) {
    text += (i == 0 ? " " : ", ") + topics[i] + " " + std::to_string(summary.records.at(i));
  }
  if (summary.unrecordable > 0) {
    text += "; " + std::to_string(summary.unrecordable) + " samples left out (arrays over 65535 values)";
  }
  return text;
}

// Waits for `end` or a stop signal, flushing every kFlushPeriod; fails when a write does.
robotd::Result<void> record_until_stopped(StopSignals& stop, RecordingSink& sink, Clock::time_point end) {
  while (true) {
    const StopSignals::Wake wake = stop.wait_until(std::min(Clock::now() + kFlushPeriod, end));
    if (auto flushed = sink.flush(); !flushed) return flushed;
    if (wake == StopSignals::Wake::kStopSignal || Clock::now() >= end) return {};
  }
}

int record(VerbContext& context, const RecordOptions& options) {
  const robotd::ClientOptions& client_options = context.client.options();
  auto devices = list_devices_including(context.client, options.device);
  if (!devices) return report_failure(devices.error(), client_options);
  const recording::Description description = describe(options, devices.value(), client_options.domain_id);
  auto writer = recording::RecordingWriter::create(options.path, description);
  if (!writer) return report_failure(writer.error().message);
  RecordingSink sink(std::move(writer.value()), description, options.device.empty(),
                     devices.value().size() == 1 ? devices.value().front().name : "");

  robotd::Client& client = context.client;
  std::vector<std::pair<std::string, robotd::Subscription>> subscriptions;
  if (wants(options, "session_status")) {
    subscriptions.emplace_back(
        "session_status", client.on_session_status([&sink](const robotd::SessionStatus& status) { sink.add(status); }));
  }
  if (wants(options, "joint_states")) {
    subscriptions.emplace_back("joint_states",
                               client.on_joint_states([&sink](const robotd::JointState& state) { sink.add(state); }));
  }
  if (wants(options, "control_command")) {
    subscriptions.emplace_back(
        "control_command",
        client.on_control_commands([&sink](const robotd::ControlCommand& command) { sink.add(command); }));
  }
  if (wants(options, "device_status")) {
    subscriptions.emplace_back(
        "device_status", client.on_device_status([&sink](const robotd::DeviceStatus& status) { sink.add(status); }));
  }
  for (const auto& [topic, subscription] : subscriptions) {
    if (!subscription.active()) {
      return report_failure("cannot subscribe to /" + topic +
                            " (with DDS Security, this identity's permissions must allow reading it)");
    }
  }

  std::cerr << "recording " << join(description.topics, ", ") << " of "
            << (options.device.empty() ? "every device" : "'" + options.device + "'") << " to " << options.path
            << (options.seconds > 0 ? " for " + fixed(options.seconds, 1) + " s" : "") << "; Ctrl-C stops" << std::endl;
  const auto end =
      options.seconds > 0
          ? Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(options.seconds))
          : Clock::time_point::max();
  const robotd::Result<void> recorded = record_until_stopped(context.stop, sink, end);
  subscriptions.clear();  // no callback writes after this
  if (!recorded) return report_failure(recorded.error().message);
  if (auto finished = sink.finish(); !finished) return report_failure(finished.error().message);
  std::cout << summary_text(sink.summary(), options.path) << std::endl;
  return kExitSuccess;
}

}  // namespace

Verb add_record_verb(CLI::App& app) {
  auto options = std::make_shared<RecordOptions>();
  CLI::App* command =
      app.add_subcommand("record", "Record joint states, commands, sessions and device status to a file, for replay");
  command->add_option("FILE", options->path, "The recording to write (replaced if it exists)")->required();
  command->add_option("--topics", options->topics, "Topics to record, comma-separated (a leading '/' is accepted)")
      ->delimiter(',')
      ->allow_extra_args(false)
      ->transform([](const std::string& topic) { return topic.starts_with('/') ? topic.substr(1) : topic; })
      ->check(CLI::IsMember(recording::recordable_topics()))
      ->default_str(join(recording::recordable_topics(), ","));
  command->add_option("--device", options->device, "Only this device's joint states, commands and status");
  command->add_option("--seconds", options->seconds, "Stop after this many seconds (default: at Ctrl-C)")
      ->check(CLI::PositiveNumber);
  command->footer(
      "Writes each sample as it arrives, in the compact binary format of docs/recording.md, and flushes it to the "
      "file every 250 ms; at the end prints the duration, the size and the records per topic. A recording cut off "
      "(robotctl killed) still reads up to its last complete record.\n\n"
      "Example:\n  robotctl record run.rdrec --device arm --seconds 30\n"
      "  robotctl record run.rdrec --topics joint_states,control_command\n"
      "  robotctl replay run.rdrec --device arm --dry-run\n"
      "  python3 -m robotd.plot run.rdrec -o run.png");
  return Verb{command, true, [options](VerbContext& context) { return record(context, *options); }};
}

}  // namespace robotctl
