#pragma once

// The per-vendor tally the suite reports: vectors, passed, deliberate differences (each one
// documented with its reason in docs/drivers/<vendor>.md and pinned to robotd's own value),
// not implemented, failed. It is printed when the test program ends and written to
// <build>/conformance/<vendor>.json for tests/conformance/report.py.

#include <string_view>

namespace robotd::conformance {

enum class Outcome {
  passed,                 // robotd agrees with the vendor's code
  deliberate_difference,  // robotd differs on purpose, as documented, and gave the documented value
  not_implemented,        // robotd does not offer what the vector exercises (documented)
  failed,                 // robotd disagrees without a documented reason: the GoogleTest fails too
};

// Counts one vector of `group` (a short name such as "scaling" or "block frames").
void record(std::string_view group, Outcome outcome);

}  // namespace robotd::conformance
