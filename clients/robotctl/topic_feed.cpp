#include "topic_feed.hpp"

#include <functional>
#include <utility>

#include "device_lookup.hpp"
#include "exit_status.hpp"
#include "message_json.hpp"
#include "message_text.hpp"
#include "text_format.hpp"

namespace robotctl {
namespace {

// Samples formatted on the subscription's thread, written by the main thread.
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

// Topics whose samples carry no device: --device does not apply to them.
bool has_device(const std::string& topic) {
  return topic != "session_status" && topic != "joy" && topic != "policy_data";
}

robotd::Subscription subscribe(robotd::Client& client, const FeedOptions& options, SampleQueue& queue,
                               StopSignals& stop) {
  const auto wanted = [device = options.device](const std::string& sample_device) {
    return device.empty() || sample_device == device;
  };
  const auto emit = [&queue, &stop](std::string text) {
    queue.push(std::move(text));
    stop.wake();
  };
  const bool json = options.json;
  const std::string& topic = options.topic;
  if (topic == "joint_states") {
    return client.on_joint_states([=](const robotd::JointState& state) {
      if (wanted(state.header.frame_id)) emit(sample_text(state, json, &joint_state_text));
    });
  }
  if (topic == "device_status") {
    return client.on_device_status([=](const robotd::DeviceStatus& status) {
      if (wanted(status.device)) emit(sample_text(status, json, &device_status_text));
    });
  }
  if (topic == "imu") {
    return client.on_imu([=](const robotd::Imu& imu) {
      if (wanted(imu.header.frame_id)) emit(sample_text(imu, json, &imu_text));
    });
  }
  if (topic == "end_pose") {
    return client.on_end_pose([=](const robotd::PoseStamped& pose) {
      if (wanted(pose.header.frame_id)) emit(sample_text(pose, json, &end_pose_text));
    });
  }
  if (topic == "joy") {
    return client.on_joy([=](const robotd::Joy& joy) { emit(sample_text(joy, json, &joy_text)); }, options.joy_topic);
  }
  if (topic == "policy_data") {
    return client.on_policy_data(
        [=](const robotd::PolicyData& data) { emit(sample_text(data, json, &policy_data_text)); });
  }
  return client.on_session_status(
      [=](const robotd::SessionStatus& status) { emit(sample_text(status, json, &session_status_text)); });
}

}  // namespace

const std::vector<std::string>& feed_topics() {
  static const std::vector<std::string> topics = {"joint_states", "session_status", "device_status", "imu", "end_pose",
                                                  "joy",          "policy_data"};
  return topics;
}

void add_feed_options(CLI::App& command, FeedOptions& options, const std::string& what) {
  command.add_option("TOPIC", options.topic, what + ": " + join(feed_topics(), ", ") + " (a leading '/' is accepted)")
      ->required()
      ->transform([](const std::string& topic) { return topic.starts_with('/') ? topic.substr(1) : topic; })
      ->check(CLI::IsMember(feed_topics()));
  command.add_option("--device", options.device,
                     "Only samples of this device (joint_states, device_status, imu, end_pose)");
  command.add_option("--joy-topic", options.joy_topic, "robotd's joystick.topic, for TOPIC joy (default: joy)");
}

std::optional<int> run_feed(VerbContext& context, const FeedOptions& options, std::ostream& out, int& failure_status) {
  if (!options.device.empty() && !has_device(options.topic)) {
    failure_status = report_usage_error(options.topic +
                                        " carries no device; --device applies to joint_states, "
                                        "device_status, imu and end_pose");
    return std::nullopt;
  }
  // Only robotd's own topics need robotd: policies publish /policy_data without it.
  if (options.topic != "policy_data") {
    if (auto devices = list_devices_including(context.client, options.device); !devices) {
      failure_status = report_failure(devices.error(), context.client.options());
      return std::nullopt;
    }
  }
  SampleQueue queue;
  const robotd::Subscription subscription = subscribe(context.client, options, queue, context.stop);
  int written = 0;
  while (options.count == 0 || written < options.count) {
    const StopSignals::Wake wake = context.stop.wait_for_wake();
    for (const auto& text : queue.take_all()) {
      if (options.count > 0 && written == options.count) break;
      out << text;
      ++written;
    }
    out.flush();
    if (wake == StopSignals::Wake::kStopSignal) break;
  }
  return written;
}

}  // namespace robotctl
