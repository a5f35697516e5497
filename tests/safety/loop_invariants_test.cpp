// The safety invariants (docs/safety.md) on random scenarios, in two layers: the ControlLoop
// with the service side played by the rig (loop_rig), and the same scenarios through robotd's
// real services (service_rig). Every regression scenario in tests/safety/regressions runs
// through both. A failure prints the seed, the broken invariant and a shrunk scenario that
// reproduces it, and writes that scenario to <build>/tests/safety-failures/ so it can be
// replayed and kept.
//
//   ROBOTD_SAFETY_SEED            first seed (default: drawn at random, printed)
//   ROBOTD_SAFETY_TICKS           ticks over all scenarios, loop layer (default 1 000 000)
//   ROBOTD_SAFETY_SERVICE_TICKS   ticks over all scenarios, service layer (default 200 000)
//   ROBOTD_SAFETY_REPLAY          run just this scenario file (ROBOTD_SAFETY_TRACE=1: print every
//                                 tick; ROBOTD_SAFETY_LAYER=services: through the services)
//   ROBOTD_SAFETY_SURVEY=1        do not stop at the first failure: one line per failing seed
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

#include "client_commands.hpp"
#include "loop_rig.hpp"
#include "scenario_generator.hpp"
#include "service_rig.hpp"
#include "shrink.hpp"

namespace robotd::safety {
namespace {

constexpr std::size_t kTicksPerScenario = 5000;

std::uint64_t env_number(const char* name, std::uint64_t fallback) {
  const char* text = std::getenv(name);  // NOLINT(concurrency-mt-unsafe): read before any thread starts
  return text == nullptr ? fallback : std::stoull(text);
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string report(const Scenario& scenario, const RunResult& result) {
  std::ostringstream out;
  out << result.violation->invariant << " at tick " << result.violation->tick << ": " << result.violation->detail
      << "\n--- scenario (" << scenario.events.size() << " events, " << scenario.tick_count() << " ticks) ---\n"
      << to_text(scenario);
  return out.str();
}

struct Layer {
  const char* name;
  Runner run;
};
constexpr Layer kLoop{"loop", &run_scenario};
constexpr Layer kServices{"services", &run_scenario_through_services};

// Shrinks a failure, saves it and returns the text to print.
std::string shrink_and_save(const Layer& layer, const Scenario& scenario, const RunResult& result, std::uint64_t seed) {
  const ShrinkResult shrunk = shrink(scenario, result, layer.run);
  const std::filesystem::path directory = std::filesystem::path(ROBOTD_BINARY_DIR) / "tests" / "safety-failures";
  std::filesystem::create_directories(directory);
  const std::filesystem::path file =
      directory / (std::string(layer.name) + "-seed-" + std::to_string(seed) + ".scenario");
  std::ofstream(file) << "# " << layer.name << " layer, seed " << seed << ": " << shrunk.result.violation->invariant
                      << "\n# " << shrunk.result.violation->detail << "\n"
                      << to_text(shrunk.scenario);
  return std::string(layer.name) + " layer, seed " + std::to_string(seed) + " (shrunk in " +
         std::to_string(shrunk.replays) + " replays, saved as " + file.string() + "):\n" +
         report(shrunk.scenario, shrunk.result);
}

void run_random_scenarios(const Layer& layer, std::uint64_t total_ticks) {
  const std::uint64_t first_seed = env_number("ROBOTD_SAFETY_SEED", std::random_device{}());
  std::printf("%s layer: first seed %llu (ROBOTD_SAFETY_SEED=%llu reproduces this run), %llu ticks\n", layer.name,
              static_cast<unsigned long long>(first_seed), static_cast<unsigned long long>(first_seed),
              static_cast<unsigned long long>(total_ticks));
  const bool survey = env_number("ROBOTD_SAFETY_SURVEY", 0) != 0;
  const auto began = std::chrono::steady_clock::now();
  RunResult sum;
  std::uint64_t scenarios = 0;
  std::uint64_t failures = 0;
  for (std::uint64_t seed = first_seed; sum.ticks < total_ticks; ++seed) {
    const Scenario scenario = generate_scenario(seed, kTicksPerScenario);
    const RunResult result = layer.run(scenario, nullptr);
    ++scenarios;
    sum.ticks += result.ticks;
    sum.commands_accepted += result.commands_accepted;
    sum.commands_rejected += result.commands_rejected;
    sum.commands_unknown_session += result.commands_unknown_session;
    sum.sessions_granted += result.sessions_granted;
    sum.sessions_ended_for_rate += result.sessions_ended_for_rate;
    sum.rate_warnings += result.rate_warnings;
    for (std::size_t i = 0; i < sum.ticks_in_state.size(); ++i) sum.ticks_in_state[i] += result.ticks_in_state[i];
    if (result.violation && survey) {
      ++failures;
      std::printf("seed %llu: %s at tick %llu: %s\n", static_cast<unsigned long long>(seed),
                  result.violation->invariant.c_str(), static_cast<unsigned long long>(result.violation->tick),
                  result.violation->detail.substr(0, 160).c_str());
    } else if (result.violation) {
      FAIL() << shrink_and_save(layer, scenario, result, seed);
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  std::printf(
      "%llu scenarios, %llu ticks in %.1f s: %llu sessions granted, %llu commands accepted, %llu rejected (%llu "
      "without a live session); %llu sessions ended for their success rate, %llu warned of it\nticks by state:",
      static_cast<unsigned long long>(scenarios), static_cast<unsigned long long>(sum.ticks), seconds,
      static_cast<unsigned long long>(sum.sessions_granted), static_cast<unsigned long long>(sum.commands_accepted),
      static_cast<unsigned long long>(sum.commands_rejected),
      static_cast<unsigned long long>(sum.commands_unknown_session),
      static_cast<unsigned long long>(sum.sessions_ended_for_rate), static_cast<unsigned long long>(sum.rate_warnings));
  for (std::size_t i = 0; i < sum.ticks_in_state.size(); ++i) {
    if (sum.ticks_in_state[i] == 0) continue;
    std::printf(" %s %.1f%%", std::string(to_string(static_cast<DeviceState>(i))).c_str(),
                100.0 * static_cast<double>(sum.ticks_in_state[i]) / static_cast<double>(sum.ticks));
  }
  std::printf("\n");
  EXPECT_EQ(failures, 0U);
  // The generator must exercise what it claims to: sessions, commands both good and bad,
  // closed-loop sessions falling below their minimum (ended, or warned), and every state.
  EXPECT_GT(sum.sessions_granted, scenarios);
  EXPECT_GT(sum.sessions_ended_for_rate + sum.rate_warnings, scenarios / 10);  // each about one a scenario
  EXPECT_GT(sum.commands_accepted, sum.ticks / 10);
  EXPECT_GT(sum.commands_rejected, sum.ticks / 100);
  for (const DeviceState state :
       {DeviceState::kRunning, DeviceState::kFault, DeviceState::kEstop, DeviceState::kMaintenance}) {
    EXPECT_GT(sum.ticks_in_state[static_cast<std::size_t>(state)], sum.ticks / 100) << to_string(state);
  }
}

TEST(SafetyInvariants, HoldOnEveryTickOfRandomScenarios) {
  if (const char* replay = std::getenv("ROBOTD_SAFETY_REPLAY")) {  // NOLINT(concurrency-mt-unsafe)
    std::string error;
    const auto scenario = parse_scenario(read_file(replay), error);
    ASSERT_TRUE(scenario) << replay << ": " << error;
    const char* layer = std::getenv("ROBOTD_SAFETY_LAYER");  // NOLINT(concurrency-mt-unsafe)
    const Runner run = layer != nullptr && std::string(layer) == "services" ? kServices.run : kLoop.run;
    const RunResult result = run(*scenario, env_number("ROBOTD_SAFETY_TRACE", 0) != 0 ? stdout : nullptr);
    EXPECT_FALSE(result.violation) << report(*scenario, result);
    return;
  }
  run_random_scenarios(kLoop, env_number("ROBOTD_SAFETY_TICKS", 1'000'000));
}

TEST(SafetyInvariants, HoldThroughTheServicesOnRandomScenarios) {
  if (std::getenv("ROBOTD_SAFETY_REPLAY") != nullptr) GTEST_SKIP() << "replaying one scenario";  // NOLINT
  spdlog::set_level(spdlog::level::err);  // the services log every grant, refusal and recover
  run_random_scenarios(kServices, env_number("ROBOTD_SAFETY_SERVICE_TICKS", 200'000));
}

std::vector<std::string> regression_files() {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(ROBOTD_SAFETY_REGRESSIONS)) {
    if (entry.path().extension() == ".scenario") files.push_back(entry.path().filename().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

class RegressionScenario : public ::testing::TestWithParam<std::string> {
 protected:
  void replay(const Layer& layer) const {
    spdlog::set_level(spdlog::level::err);
    const std::filesystem::path path = std::filesystem::path(ROBOTD_SAFETY_REGRESSIONS) / GetParam();
    std::string error;
    const auto scenario = parse_scenario(read_file(path), error);
    ASSERT_TRUE(scenario) << path << ": " << error;
    const RunResult result = layer.run(*scenario, nullptr);
    EXPECT_FALSE(result.violation) << layer.name << " layer, " << path << "\n" << report(*scenario, result);
  }
};

TEST_P(RegressionScenario, HoldsInTheLoop) { replay(kLoop); }
TEST_P(RegressionScenario, HoldsThroughTheServices) { replay(kServices); }

std::string test_name(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = std::filesystem::path(info.param).stem().string();
  for (char& c : name) {
    if (std::isalnum(static_cast<unsigned char>(c)) == 0) c = '_';
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(Kept, RegressionScenario, ::testing::ValuesIn(regression_files()), test_name);

TEST(ScenarioText, RoundTrips) {
  const Scenario scenario = generate_scenario(7, 3000);
  std::string error;
  const auto parsed = parse_scenario(to_text(scenario), error);
  ASSERT_TRUE(parsed) << error;
  EXPECT_EQ(to_text(*parsed), to_text(scenario));
}

TEST(ScenarioText, ClosedLoopFieldsRoundTripAndOldLinesKeepTheirDefaults) {
  const std::string device = "device joints=2 safe=damping shutdown=keep policy=clamp\n";
  std::string error;
  const auto old =
      parse_scenario(device + "start s=1 motors=0 mode=position fallback=keep\ncommand s=1 seed=7\n", error);
  ASSERT_TRUE(old) << error;
  EXPECT_EQ(old->events[0].min_rate, 0);
  EXPECT_EQ(old->events[0].on_low, LowRateAction::kWarn);
  EXPECT_FALSE(old->events[1].answers);
  EXPECT_EQ(to_text(old->events[0]), "start s=1 motors=0 mode=position fallback=keep timeout_ms=100");
  EXPECT_EQ(to_text(old->events[1]), "command s=1 seed=7");

  const std::string lines =
      "start s=1 motors=0 mode=position fallback=keep timeout_ms=100 min_rate=0.95 on_low=fallback\n"
      "command s=1 seed=7 answers=newest\ncommand s=1 seed=8 answers=newest-3\ncommand s=1 seed=9 answers=newest+2\n";
  const auto closed = parse_scenario(device + lines, error);
  ASSERT_TRUE(closed) << error;
  EXPECT_EQ(closed->events[0].min_rate, 0.95);
  EXPECT_EQ(closed->events[0].on_low, LowRateAction::kFallback);
  EXPECT_EQ(closed->events[2].answer_offset, -3);
  EXPECT_EQ(answered_tick(closed->events[3], 10), 12U);
  EXPECT_EQ(answered_tick(closed->events[2], 2), 0U);  // before the first tick: none
  std::string printed;
  for (const Event& event : closed->events) printed += to_text(event) + "\n";
  EXPECT_EQ(printed, lines);
}

TEST(ScenarioText, BadClosedLoopFieldsSayWhatWasExpected) {
  const std::string device = "device joints=2 safe=damping shutdown=keep policy=clamp\n";
  std::string error;
  EXPECT_FALSE(parse_scenario(device + "start s=1 motors=0 mode=position fallback=keep on_low=panic\n", error));
  EXPECT_NE(error.find("line 2: on_low='panic' is not warn or fallback"), std::string::npos) << error;
  EXPECT_FALSE(parse_scenario(device + "command s=1 seed=7 answers=latest\n", error));
  EXPECT_NE(error.find("line 2: answers=latest is not newest, newest-N or newest+N"), std::string::npos) << error;
  EXPECT_FALSE(parse_scenario(device + "command s=1 seed=7 answers=newest+-1\n", error));
  EXPECT_NE(error.find("answers=newest+-1 is not"), std::string::npos) << error;
}

TEST(ScenarioText, ABadLineSaysWhichAndWhatWasExpected) {
  std::string error;
  EXPECT_FALSE(parse_scenario("device joints=2 safe=damping shutdown=keep policy=clamp\ntick n=1\nwobble\n", error));
  EXPECT_NE(error.find("line 3: unknown event 'wobble'"), std::string::npos) << error;
}

}  // namespace
}  // namespace robotd::safety
