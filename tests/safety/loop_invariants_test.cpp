// The loop's safety invariants (docs/safety.md) on random scenarios and on every regression
// scenario kept in tests/safety/regressions. A failure prints the seed, the broken invariant
// and a shrunk scenario that reproduces it, and writes that scenario to
// <build>/tests/safety-failures/ so it can be replayed (ROBOTD_SAFETY_REPLAY=<file>) and kept.
//
//   ROBOTD_SAFETY_SEED      first seed (default: drawn at random, printed)
//   ROBOTD_SAFETY_TICKS     total ticks over all scenarios (default 1 000 000)
//   ROBOTD_SAFETY_REPLAY    run just this scenario file (ROBOTD_SAFETY_TRACE=1: print every tick)
//   ROBOTD_SAFETY_SURVEY=1  do not stop at the first failure: one line per failing seed
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include <gtest/gtest.h>

#include "loop_rig.hpp"
#include "scenario_generator.hpp"
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

// Shrinks a failure, saves it and returns the text to print.
std::string shrink_and_save(const Scenario& scenario, const RunResult& result, std::uint64_t seed) {
  const ShrinkResult shrunk = shrink(scenario, result);
  const std::filesystem::path directory = std::filesystem::path(ROBOTD_BINARY_DIR) / "tests" / "safety-failures";
  std::filesystem::create_directories(directory);
  const std::filesystem::path file = directory / ("seed-" + std::to_string(seed) + ".scenario");
  std::ofstream(file) << "# seed " << seed << ": " << shrunk.result.violation->invariant << "\n# "
                      << shrunk.result.violation->detail << "\n"
                      << to_text(shrunk.scenario);
  return "seed " + std::to_string(seed) + " (shrunk in " + std::to_string(shrunk.replays) + " replays, saved as " +
         file.string() + "):\n" + report(shrunk.scenario, shrunk.result);
}

TEST(SafetyInvariants, HoldOnEveryTickOfRandomScenarios) {
  if (const char* replay = std::getenv("ROBOTD_SAFETY_REPLAY")) {  // NOLINT(concurrency-mt-unsafe)
    std::string error;
    const auto scenario = parse_scenario(read_file(replay), error);
    ASSERT_TRUE(scenario) << replay << ": " << error;
    const bool trace = env_number("ROBOTD_SAFETY_TRACE", 0) != 0;
    const RunResult result = run_scenario(*scenario, trace ? stdout : nullptr);
    EXPECT_FALSE(result.violation) << report(*scenario, result);
    return;
  }
  const std::uint64_t first_seed = env_number("ROBOTD_SAFETY_SEED", std::random_device{}());
  const std::uint64_t total_ticks = env_number("ROBOTD_SAFETY_TICKS", 1'000'000);
  std::printf("safety scenarios: first seed %llu (ROBOTD_SAFETY_SEED=%llu reproduces this run), %llu ticks\n",
              static_cast<unsigned long long>(first_seed), static_cast<unsigned long long>(first_seed),
              static_cast<unsigned long long>(total_ticks));
  const auto began = std::chrono::steady_clock::now();
  std::uint64_t ticks = 0;
  std::uint64_t accepted = 0;
  std::uint64_t rejected = 0;
  std::uint64_t unknown = 0;
  std::uint64_t granted = 0;
  std::uint64_t scenarios = 0;
  std::array<std::uint64_t, 7> in_state{};
  std::uint64_t failures = 0;
  const bool survey = env_number("ROBOTD_SAFETY_SURVEY", 0) != 0;
  for (std::uint64_t seed = first_seed; ticks < total_ticks; ++seed) {
    const Scenario scenario = generate_scenario(seed, kTicksPerScenario);
    const RunResult result = run_scenario(scenario);
    ++scenarios;
    ticks += result.ticks;
    accepted += result.commands_accepted;
    rejected += result.commands_rejected;
    unknown += result.commands_unknown_session;
    granted += result.sessions_granted;
    for (std::size_t i = 0; i < in_state.size(); ++i) in_state[i] += result.ticks_in_state[i];
    if (result.violation && survey) {
      ++failures;
      std::printf("seed %llu: %s at tick %llu: %s\n", static_cast<unsigned long long>(seed),
                  result.violation->invariant.c_str(), static_cast<unsigned long long>(result.violation->tick),
                  result.violation->detail.substr(0, 160).c_str());
    } else if (result.violation) {
      FAIL() << shrink_and_save(scenario, result, seed);
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  std::printf(
      "%llu scenarios, %llu ticks in %.1f s: %llu sessions granted, %llu commands accepted, %llu rejected (%llu "
      "without a live session)\n",
      static_cast<unsigned long long>(scenarios), static_cast<unsigned long long>(ticks), seconds,
      static_cast<unsigned long long>(granted), static_cast<unsigned long long>(accepted),
      static_cast<unsigned long long>(rejected), static_cast<unsigned long long>(unknown));
  std::printf("ticks by state:");
  for (std::size_t i = 0; i < in_state.size(); ++i) {
    if (in_state[i] != 0) {
      std::printf(" %s %.1f%%", std::string(to_string(static_cast<DeviceState>(i))).c_str(),
                  100.0 * static_cast<double>(in_state[i]) / static_cast<double>(ticks));
    }
  }
  std::printf("\n");
  EXPECT_EQ(failures, 0U);
  // The generator must exercise what it claims to: sessions, and commands both good and bad.
  EXPECT_GT(granted, scenarios);
  EXPECT_GT(accepted, ticks / 4);
  EXPECT_GT(rejected, ticks / 100);
}

class RegressionScenario : public ::testing::TestWithParam<std::string> {};

TEST_P(RegressionScenario, StillHolds) {
  const std::filesystem::path path = std::filesystem::path(ROBOTD_SAFETY_REGRESSIONS) / GetParam();
  std::string error;
  const auto scenario = parse_scenario(read_file(path), error);
  ASSERT_TRUE(scenario) << path << ": " << error;
  const RunResult result = run_scenario(*scenario);
  EXPECT_FALSE(result.violation) << path << "\n" << report(*scenario, result);
}

std::vector<std::string> regression_files() {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(ROBOTD_SAFETY_REGRESSIONS)) {
    if (entry.path().extension() == ".scenario") files.push_back(entry.path().filename().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

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

TEST(ScenarioText, ABadLineSaysWhichAndWhatWasExpected) {
  std::string error;
  EXPECT_FALSE(parse_scenario("device joints=2 safe=damping shutdown=keep policy=clamp\ntick n=1\nwobble\n", error));
  EXPECT_NE(error.find("line 3: unknown event 'wobble'"), std::string::npos) << error;
}

}  // namespace
}  // namespace robotd::safety
