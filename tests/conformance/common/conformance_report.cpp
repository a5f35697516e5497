#include "conformance_report.hpp"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#ifndef ROBOTD_CONFORMANCE_VENDOR
#error "ROBOTD_CONFORMANCE_VENDOR names the vendor (robotd_add_conformance)"
#endif

namespace robotd::conformance {
namespace {

struct Counts {
  int passed = 0;
  int deliberate_differences = 0;
  int not_implemented = 0;
  int failed = 0;

  [[nodiscard]] int vectors() const { return passed + deliberate_differences + not_implemented + failed; }
};

std::map<std::string, Counts, std::less<>>& tally() {
  static std::map<std::string, Counts, std::less<>> counts;
  return counts;
}

nlohmann::json to_json(const Counts& counts) {
  return {{"vectors", counts.vectors()},
          {"passed", counts.passed},
          {"deliberate_differences", counts.deliberate_differences},
          {"not_implemented", counts.not_implemented},
          {"failed", counts.failed}};
}

// Prints the tally when the program ends and, when ROBOTD_CONFORMANCE_REPORT names a file
// (tests/conformance/report.py sets it), writes it there as JSON.
class ReportEnvironment : public ::testing::Environment {
 public:
  void TearDown() override {
    Counts total;
    nlohmann::json groups = nlohmann::json::object();
    for (const auto& [group, counts] : tally()) {
      groups[group] = to_json(counts);
      total.passed += counts.passed;
      total.deliberate_differences += counts.deliberate_differences;
      total.not_implemented += counts.not_implemented;
      total.failed += counts.failed;
    }
    std::printf(
        "conformance %s: %d vectors, %d passed, %d deliberate differences, "
        "%d not implemented, %d failed\n",
        ROBOTD_CONFORMANCE_VENDOR, total.vectors(), total.passed, total.deliberate_differences, total.not_implemented,
        total.failed);
    if (const char* path = std::getenv("ROBOTD_CONFORMANCE_REPORT")) {
      nlohmann::json report = to_json(total);
      report["vendor"] = ROBOTD_CONFORMANCE_VENDOR;
      report["groups"] = std::move(groups);
      std::ofstream(path) << report.dump(2) << '\n';
    }
  }
};

// Registered before main(), the one way with GoogleTest's own main; GoogleTest owns it.
// NOLINTNEXTLINE(cert-err58-cpp,bugprone-throwing-static-initialization,cppcoreguidelines-owning-memory)
[[maybe_unused]] const ::testing::Environment* const kReport =
    ::testing::AddGlobalTestEnvironment(new ReportEnvironment);

}  // namespace

void record(std::string_view group, Outcome outcome) {
  auto it = tally().find(group);
  if (it == tally().end()) {
    it = tally().emplace(std::string(group), Counts{}).first;
  }
  switch (outcome) {
    case Outcome::passed:
      ++it->second.passed;
      break;
    case Outcome::deliberate_difference:
      ++it->second.deliberate_differences;
      break;
    case Outcome::not_implemented:
      ++it->second.not_implemented;
      break;
    case Outcome::failed:
      ++it->second.failed;
      break;
  }
}

}  // namespace robotd::conformance
