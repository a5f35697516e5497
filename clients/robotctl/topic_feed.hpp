// What echo does: subscribing to one of robotd's topics and handing each sample, formatted,
// from the subscription's thread to the main thread, which writes it out.
#pragma once

#include <deque>
#include <mutex>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "verbs/verbs.hpp"

namespace robotctl {

/// The topics echo knows, by ROS name without the leading '/'.
const std::vector<std::string>& feed_topics();

struct FeedOptions {
  std::string topic;
  std::string device;             // only samples of this device ("" = all)
  std::string joy_topic = "joy";  // robotd's joystick.topic
  bool json = false;              // one JSON object per line instead of a readable block
  int count = 0;                  // stop after this many samples; 0 = no limit
};

/// The TOPIC argument and --device / --joy-topic.
void add_feed_options(CLI::App& command, FeedOptions& options, const std::string& what);

/// Writes the samples of `options.topic` to `out` until the count or a stop signal.
/// Returns how many were written, or nullopt after reporting a failure (robotd not reachable,
/// --device unknown); `failure_status` is then the exit status.
std::optional<int> run_feed(VerbContext& context, const FeedOptions& options, std::ostream& out, int& failure_status);

}  // namespace robotctl
