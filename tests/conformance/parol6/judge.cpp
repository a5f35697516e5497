#include "judge.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "vector_file.hpp"

namespace robotd::parol6::conformance {
namespace {

using nlohmann::json;

bool same(const json& vendor, const json& robotd, double relative_tolerance) {
  if (vendor.is_number_float() || robotd.is_number_float()) {
    if (!vendor.is_number() || !robotd.is_number()) return false;
    const double a = vendor.get<double>();
    const double b = robotd.get<double>();
    return a == b || std::abs(a - b) <= relative_tolerance * std::max(std::abs(a), std::abs(b));
  }
  return vendor == robotd;
}

/// The JSON pointers of the fields robotd offers where the vendor's value differs. Objects are
/// compared on robotd's keys; arrays of different sizes differ as a whole.
void mismatches(const json& vendor, const json& robotd, const std::string& path, double tolerance,
                std::vector<std::string>& out) {
  if (robotd.is_object() && vendor.is_object()) {
    for (const auto& [key, value] : robotd.items()) {
      std::string field = path;
      field += '/';
      field += key;
      if (vendor.contains(key)) {
        mismatches(vendor.at(key), value, field, tolerance, out);
      } else {
        out.push_back(std::move(field));
      }
    }
    return;
  }
  if (robotd.is_array() && vendor.is_array() && robotd.size() == vendor.size()) {
    std::vector<std::string> inner;
    for (std::size_t i = 0; i < robotd.size(); ++i) mismatches(vendor[i], robotd[i], path, tolerance, inner);
    if (!inner.empty()) out.push_back(path);  // a list differs as a whole (one documented field)
    return;
  }
  if (!same(vendor, robotd, tolerance)) out.push_back(path);
}

std::string vector_name(const json& vector) { return vector.value("name", std::string{}); }

}  // namespace

Differences Differences::load() {
  Differences differences;
  const json file = robotd::conformance::load_json("differences.json");
  for (const json& entry : file.at("differences")) {
    Difference d{.id = entry.at("id").get<std::string>(),
                 .group = entry.at("group").get<std::string>(),
                 .vendors = entry.at("vendors").get<std::vector<std::string>>(),
                 .field = entry.at("field").get<std::string>(),
                 .robotd_follows = entry.value("robotd_follows", std::string{}),
                 .robotd = entry.value("robotd", json::object())};
    if (!entry.contains("reason") || entry.at("reason").get<std::string>().empty()) {
      throw std::runtime_error("differences.json: difference " + d.id + " gives no reason");
    }
    if (d.robotd_follows.empty() == d.robotd.empty()) {
      throw std::runtime_error("differences.json: difference " + d.id +
                               " needs exactly one of robotd_follows (a JSON pointer) and robotd (values per vector)");
    }
    differences.differences_.push_back(std::move(d));
  }
  return differences;
}

json Differences::documented(std::string_view group, std::string_view vendor, std::string_view field,
                             const json& vector) const {
  for (const Difference& d : differences_) {
    if (d.group != group || d.field != field ||
        std::find(d.vendors.begin(), d.vendors.end(), vendor) == d.vendors.end()) {
      continue;
    }
    if (!d.robotd_follows.empty()) return vector.at(json::json_pointer(d.robotd_follows));
    if (const auto it = d.robotd.find(vector_name(vector)); it != d.robotd.end()) return *it;
  }
  return nullptr;
}

Verdict judge(const Differences& differences, std::string_view group, std::string_view vendor,
              const json& vendor_result, const json& robotd, const json& vector, double relative_tolerance) {
  std::vector<std::string> fields;
  mismatches(vendor_result, robotd, "", relative_tolerance, fields);
  Verdict verdict;
  for (const std::string& field : fields) {
    const json::json_pointer pointer(field);
    const json theirs = vendor_result.contains(pointer) ? vendor_result.at(pointer) : json();
    const json& ours = robotd.at(pointer);
    const json documented = differences.documented(group, vendor, field, vector);
    if (!documented.is_null() && same(documented, ours, relative_tolerance)) {
      verdict.outcome = verdict.outcome == Outcome::failed ? Outcome::failed : Outcome::deliberate_difference;
      continue;
    }
    verdict.outcome = Outcome::failed;
    verdict.detail +=
        "\n  " + std::string(vendor) + " " + field + ": vendor " + theirs.dump() + ", robotd " + ours.dump() +
        (documented.is_null() ? ", no documented difference" : ", documented robotd value " + documented.dump());
  }
  return verdict;
}

}  // namespace robotd::parol6::conformance
