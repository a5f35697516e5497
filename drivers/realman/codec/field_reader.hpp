// Inside the codec only: reading the fields of a controller message without throwing. A
// FieldReader remembers the first problem with the path of the field that caused it
// ("joint_status.joint_current: expected at least 6 entries (one per joint), got 5"), so a parser
// reads every field, checks once, and only then uses the values.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "robotd/result.hpp"

namespace robotd::realman {

/// Parses text that must hold one JSON object; kInvalidArgument quoting the start of the text.
Result<nlohmann::json> parse_object(std::string_view text);

/// Every value of an error field of `object` ("err" entries or scalar, "arm_err", "sys_err"),
/// with the name of its field; empty for a non-object.
std::vector<std::pair<std::string_view, const nlohmann::json*>> error_values(const nlohmann::json& object);

class FieldReader {
 public:
  static constexpr std::int64_t kAnyMin = std::numeric_limits<std::int64_t>::min();
  static constexpr std::int64_t kAnyMax = std::numeric_limits<std::int64_t>::max();
  static constexpr std::size_t kAnyCount = std::numeric_limits<std::size_t>::max();  // no upper bound

  /// `path` names `object` in problems ("" for the message itself); `problem` keeps the first.
  FieldReader(const nlohmann::json& object, std::string path, std::string& problem);

  bool has(std::string_view name) const;
  std::int64_t integer(std::string_view name, std::int64_t min = kAnyMin, std::int64_t max = kAnyMax);
  /// A bool, or the integers 0 and 1.
  bool flag(std::string_view name);
  std::string text(std::string_view name);
  /// An array of min_count..max_count integers, each min..max.
  std::vector<std::int64_t> integers(std::string_view name, std::size_t min_count, std::size_t max_count,
                                     std::int64_t min = kAnyMin, std::int64_t max = kAnyMax);
  /// An array of min_count..max_count flags (bools or 0/1).
  std::vector<bool> flags(std::string_view name, std::size_t min_count, std::size_t max_count);
  /// A reader for the object `name` (a problem if it is missing or not an object).
  FieldReader object(std::string_view name);
  /// The controller's error codes in every shape of §4.1; at least one error field must exist.
  std::vector<std::uint16_t> error_codes();

 private:
  FieldReader(const nlohmann::json* object, std::string path, std::string* problem);  // nullptr: already reported
  const nlohmann::json* find(std::string_view name);                                  // a problem when missing
  void report(std::string_view name, const std::string& message);

  const nlohmann::json* object_;
  std::string path_;
  std::string* problem_;
};

}  // namespace robotd::realman
