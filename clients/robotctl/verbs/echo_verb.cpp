// echo: print the samples of one of robotd's topics as they arrive.
#include <deque>
#include <iostream>
#include <memory>
#include <mutex>
#include <string>
#include <utility>

#include "device_lookup.hpp"
#include "exit_status.hpp"
#include "message_json.hpp"
#include "message_text.hpp"
#include "text_format.hpp"
#include "verbs/verbs.hpp"

namespace robotctl {
namespace {

struct EchoOptions {
  std::string topic;
  std::string device;
  int count = 0;  // 0 = until Ctrl-C
  bool json = false;
};

// Samples formatted on the subscription's thread, printed by the main thread.
class SampleQueue {
 public:
  void push(std::string text) {
    const std::lock_guard lock(mutex_);
    texts_.push_back(std::move(text));
  }
  std::deque<std::string> take_all() {
    const std::lock_guard lock(mutex_);
    return std::exchange(texts_, {});
  }

 private:
  std::mutex mutex_;
  std::deque<std::string> texts_;
};

std::string session_status_text(const robotd::SessionStatus& status) {
  return "session_status  " + status.state + "  stamp " + stamp_text(status.header.stamp) + "\n" +
         session_table(status);
}

// One JSON object per line, or a readable block followed by a blank line.
template <class Message>
std::string sample_text(const Message& message, bool json, std::string (*readable)(const Message&)) {
  return json ? compact_text(to_json(message)) + "\n" : readable(message) + "\n";
}

robotd::Subscription subscribe(robotd::Client& client, const EchoOptions& options, SampleQueue& queue,
                               StopSignals& stop) {
  const auto wanted = [device = options.device](const std::string& sample_device) {
    return device.empty() || sample_device == device;
  };
  const auto emit = [&queue, &stop](std::string text) {
    queue.push(std::move(text));
    stop.wake();
  };
  const bool json = options.json;
  if (options.topic == "joint_states") {
    return client.on_joint_states([=](const robotd::JointState& state) {
      if (wanted(state.header.frame_id)) emit(sample_text(state, json, &joint_state_text));
    });
  }
  if (options.topic == "device_status") {
    return client.on_device_status([=](const robotd::DeviceStatus& status) {
      if (wanted(status.device)) emit(sample_text(status, json, &device_status_text));
    });
  }
  if (options.topic == "imu") {
    return client.on_imu([=](const robotd::Imu& imu) {
      if (wanted(imu.header.frame_id)) emit(sample_text(imu, json, &imu_text));
    });
  }
  if (options.topic == "end_pose") {
    return client.on_end_pose([=](const robotd::PoseStamped& pose) {
      if (wanted(pose.header.frame_id)) emit(sample_text(pose, json, &end_pose_text));
    });
  }
  return client.on_session_status(
      [=](const robotd::SessionStatus& status) { emit(sample_text(status, json, &session_status_text)); });
}

int echo(VerbContext& context, const EchoOptions& options) {
  if (options.topic == "session_status" && !options.device.empty()) {
    return report_usage_error(
        "session_status covers every device; --device applies to joint_states, device_status, "
        "imu and end_pose");
  }
  if (auto devices = list_devices_including(context.client, options.device); !devices) {
    return report_failure(devices.error(), context.client.options());
  }
  SampleQueue queue;
  const robotd::Subscription subscription = subscribe(context.client, options, queue, context.stop);
  int printed = 0;
  while (options.count == 0 || printed < options.count) {
    if (context.stop.wait_for_wake() == StopSignals::Wake::kStopSignal) break;
    for (const auto& text : queue.take_all()) {
      if (options.count > 0 && printed == options.count) break;
      std::cout << text;
      ++printed;
    }
    std::cout.flush();
  }
  return kExitSuccess;
}

}  // namespace

Verb add_echo_verb(CLI::App& app) {
  auto options = std::make_shared<EchoOptions>();
  CLI::App* command = app.add_subcommand("echo", "Print the samples of a robotd topic as they arrive");
  command
      ->add_option("TOPIC", options->topic,
                   "joint_states, session_status, device_status, imu or end_pose (a leading '/' is accepted)")
      ->required()
      ->transform([](const std::string& topic) { return topic.starts_with('/') ? topic.substr(1) : topic; })
      ->check(CLI::IsMember({"joint_states", "session_status", "device_status", "imu", "end_pose"}));
  command->add_option("--device", options->device, "Only samples of this device");
  command->add_option("--count", options->count, "Stop after this many samples (default: until Ctrl-C)")
      ->check(CLI::PositiveNumber);
  command->add_flag("--json", options->json, "One JSON object per line instead of a readable block");
  command->footer(
      "Prints one readable block per sample, or with --json one JSON object per line, until --count samples "
      "have been printed or Ctrl-C.\n\n"
      "Example:\n  robotctl echo /joint_states --device arm --count 1\n"
      "  robotctl echo device_status --json | jq .loop.wake_latency_p99_us");
  return Verb{command, true, [options](VerbContext& context) { return echo(context, *options); }};
}

}  // namespace robotctl
