#include "differences.hpp"

#include <gtest/gtest.h>

#include "vector_file.hpp"

namespace robotd::piper::conformance {
namespace {

using nlohmann::json;
using robotd::conformance::Outcome;

const json& listed() {
  static const json file = robotd::conformance::load_json("differences.json");
  return file;
}

/// The entry of `section` (deliberate_differences or not_implemented) for this vector: listed
/// by its whole key, or (not implemented) by the call alone.
const json* entry(std::string_view section, std::string_view group, const json& key) {
  for (const json& item : listed().at(std::string(section))) {
    if (item.at("group") != group) continue;
    const json& listed_key = item.at("key");
    if (listed_key == key) return &item;
    if (key.contains("call") && listed_key.size() == 1 && listed_key.contains("call") &&
        listed_key.at("call") == key.at("call")) {
      return &item;
    }
  }
  return nullptr;
}

}  // namespace

Outcome judge(std::string_view group, const json& key, const json& sdk, const json& robotd) {
  if (sdk == robotd) return Outcome::passed;
  if (const json* difference = entry("deliberate_differences", group, key)) {
    if (difference->at("robotd") == robotd) return Outcome::deliberate_difference;
    ADD_FAILURE() << group << " " << key.dump() << ": a listed deliberate difference, but robotd gave " << robotd.dump()
                  << " instead of the listed " << difference->at("robotd").dump();
    return Outcome::failed;
  }
  if (entry("not_implemented", group, key) != nullptr) return Outcome::not_implemented;
  ADD_FAILURE() << group << " " << key.dump() << ":\n  SDK:    " << sdk.dump() << "\n  robotd: " << robotd.dump();
  return Outcome::failed;
}

}  // namespace robotd::piper::conformance
