// The controller's error codes in the three shapes of §4.1: "err" as a list (newer), "err" as a
// scalar (one English page), "arm_err" and "sys_err" (older).
#include <algorithm>
#include <cstdint>
#include <string_view>
#include <utility>
#include <vector>

#include "field_reader.hpp"
#include "realman_codec.hpp"

namespace robotd::realman {

std::vector<std::pair<std::string_view, const nlohmann::json*>> error_values(const nlohmann::json& object) {
  std::vector<std::pair<std::string_view, const nlohmann::json*>> values;
  if (!object.is_object()) return values;
  for (const std::string_view field : {"err", "arm_err", "sys_err"}) {
    const auto found = object.find(field);
    if (found == object.end()) continue;
    if (found->is_array()) {
      for (const nlohmann::json& entry : *found) values.emplace_back(field, &entry);
    } else {
      values.emplace_back(field, &*found);
    }
  }
  return values;
}

std::vector<std::uint16_t> collect_errors(const nlohmann::json& object) {
  std::vector<std::uint16_t> codes;
  for (const auto& [field, value] : error_values(object)) {
    // Without a way to report here, an entry that is no error code is skipped; the reply
    // parsers reject such messages outright.
    if (!value->is_number_integer()) continue;
    const auto code = value->get<std::int64_t>();
    if (code <= 0 || code > 0xFFFF) continue;
    const auto code16 = static_cast<std::uint16_t>(code);
    if (std::find(codes.begin(), codes.end(), code16) == codes.end()) codes.push_back(code16);
  }
  return codes;
}

}  // namespace robotd::realman
