// record: write the samples of one of robotd's topics to a file, one JSON object per line.
#include <chrono>
#include <fstream>
#include <iostream>
#include <memory>

#include "exit_status.hpp"
#include "topic_feed.hpp"
#include "verbs/verbs.hpp"

namespace robotctl {
namespace {

struct RecordOptions {
  FeedOptions feed;
  std::string output;
  double duration_s = 0;
};

int record(VerbContext& context, RecordOptions& options) {
  std::ofstream file(options.output, std::ios::trunc);
  if (!file) return report_failure("record: cannot write " + options.output);
  options.feed.json = true;
  if (options.duration_s > 0) {
    options.feed.duration = std::chrono::milliseconds(static_cast<std::int64_t>(options.duration_s * 1000.0));
  }
  int failure = kExitFailure;
  const auto written = run_feed(context, options.feed, file, failure);
  if (!written) return failure;
  if (!file) return report_failure("record: writing " + options.output + " failed");
  std::cerr << "recorded " << *written << " samples of /" << options.feed.topic << " to " << options.output << "\n";
  return kExitSuccess;
}

}  // namespace

Verb add_record_verb(CLI::App& app) {
  auto options = std::make_shared<RecordOptions>();
  CLI::App* command = app.add_subcommand("record", "Record the samples of a robotd topic to a file as JSON lines");
  add_feed_options(*command, options->feed, "The topic");
  command->add_option("--output,-o", options->output, "The file to write (replaced), one JSON object per line")
      ->required();
  auto* duration = command->add_option("--duration", options->duration_s, "Stop after this many seconds")
                       ->check(CLI::PositiveNumber);
  command->add_option("--count", options->feed.count, "Stop after this many samples")
      ->check(CLI::PositiveNumber)
      ->excludes(duration);
  command->footer(
      "Writes each sample as `robotctl echo --json` prints it, until --count samples, --duration seconds or "
      "Ctrl-C; then says how many it wrote.\n\n"
      "Example:\n  robotctl record policy_data --output run1.jsonl --duration 30\n"
      "  robotctl record joint_states --device arm --count 1000 -o arm.jsonl");
  return Verb{command, true, [options](VerbContext& context) { return record(context, *options); }};
}

}  // namespace robotctl
