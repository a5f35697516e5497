#pragma once

// Judging one recorded vector: robotd's result (as JSON, with the vendor's field names) against
// what one vendor codebase produced, with the deliberate differences of differences.json.

#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "conformance_report.hpp"

namespace robotd::parol6::conformance {

using robotd::conformance::Outcome;

/// One documented difference (differences.json): where robotd differs from `vendor` in `field`
/// of the vectors of `group`, why, and what robotd gives instead: either the value at the JSON
/// pointer `robotd_follows` in the same vector (e.g. "/api/position_steps": the other vendor's
/// recorded value), or an explicit value per vector name (`robotd`).
struct Difference {
  std::string id;
  std::string group;
  std::vector<std::string> vendors;
  std::string field;  // a JSON pointer into the vendor's result, e.g. "/gripper/object_detection"
  std::string robotd_follows;
  nlohmann::json robotd;  // vector name → robotd's value
};

class Differences {
 public:
  /// differences.json of this vendor's data directory; throws on a malformed entry.
  static Differences load();
  const std::vector<Difference>& all() const { return differences_; }

  /// robotd's documented value for `field` of `vector` against `vendor`, or null if none.
  nlohmann::json documented(std::string_view group, std::string_view vendor, std::string_view field,
                            const nlohmann::json& vector) const;

 private:
  std::vector<Difference> differences_;
};

struct Verdict {
  Outcome outcome = Outcome::passed;
  std::string detail;  // for a failure: each field, the vendor's value, robotd's, the documented one
};

/// Compares every field robotd offers (the keys of `robotd`, recursively; arrays element by element)
/// with the vendor's. Numbers that are not integers agree within `relative_tolerance`.
Verdict judge(const Differences& differences, std::string_view group, std::string_view vendor,
              const nlohmann::json& vendor_result, const nlohmann::json& robotd, const nlohmann::json& vector,
              double relative_tolerance = 0.0);

}  // namespace robotd::parol6::conformance
