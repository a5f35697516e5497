// echo: print the samples of one of robotd's topics as they arrive.
#include <iostream>
#include <memory>

#include "exit_status.hpp"
#include "topic_feed.hpp"
#include "verbs/verbs.hpp"

namespace robotctl {

Verb add_echo_verb(CLI::App& app) {
  auto options = std::make_shared<FeedOptions>();
  CLI::App* command = app.add_subcommand("echo", "Print the samples of a robotd topic as they arrive");
  add_feed_options(*command, *options, "The topic");
  command->add_option("--count", options->count, "Stop after this many samples (default: until Ctrl-C)")
      ->check(CLI::PositiveNumber);
  command->add_flag("--json", options->json, "One JSON object per line instead of a readable block");
  command->footer(
      "Prints one readable block per sample, or with --json one JSON object per line, until --count samples "
      "have been printed or Ctrl-C.\n\n"
      "Example:\n  robotctl echo /joint_states --device arm --count 1\n"
      "  robotctl echo device_status --json | jq .loop.wake_latency_p99_us\n"
      "  robotctl echo joy          (robotd's joystick, config key \"joystick\")\n"
      "  robotctl echo policy_data  (what policies publish; robotd need not run)\n"
      "  robotctl echo policy_data --json > run.jsonl   (keep a topic as JSON lines; robotctl record keeps "
      "joint states, commands and status for replay)");
  return Verb{command, true, [options](VerbContext& context) {
                int failure = kExitFailure;
                return run_feed(context, *options, std::cout, failure) ? kExitSuccess : failure;
              }};
}

}  // namespace robotctl
