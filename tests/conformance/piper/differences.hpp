#pragma once

// The documented departures from the SDK (differences.json, listed with their reasons in
// docs/drivers/piper.md "Conformance"): deliberate differences pinned to robotd's own value, and
// what robotd does not implement.

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "conformance_report.hpp"

namespace robotd::piper::conformance {

/// How one vector ends: the SDK's result against robotd's, both as JSON. `key` names the vector
/// (call and arguments, or id and data). Passed when they are equal; a deliberate difference
/// when differences.json lists the key under `group` with exactly robotd's result; not
/// implemented when it lists the key (or the call alone) as not implemented; failed otherwise, with a GoogleTest
/// failure naming the vector.
robotd::conformance::Outcome judge(std::string_view group, const nlohmann::json& key, const nlohmann::json& sdk,
                                   const nlohmann::json& robotd);

}  // namespace robotd::piper::conformance
