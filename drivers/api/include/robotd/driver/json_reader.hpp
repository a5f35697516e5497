// Reads one JSON object against what the reader expects and records every problem with the
// key path that caused it ("devices[1].rate_hz: expected an integer in 1..10000, got 0").
// finish() reports keys nobody asked for, so a typo is an error, not a silent default.
// Used for robotd's config and for every driver's "params".
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace robotd {

struct NumberRange {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
};

class JsonReader {
 public:
  /// `path` names `value` in messages ("" for the document root).
  JsonReader(const nlohmann::json& value, std::string path, std::vector<std::string>& errors);

  bool has(std::string_view key) const;

  std::optional<double> number(std::string_view key, NumberRange range = {});
  double number_or(std::string_view key, double fallback, NumberRange range = {});
  std::optional<std::int64_t> integer(std::string_view key, std::int64_t min, std::int64_t max);
  std::int64_t integer_or(std::string_view key, std::int64_t fallback, std::int64_t min, std::int64_t max);
  bool boolean_or(std::string_view key, bool fallback);
  /// `choices` empty = any string.
  std::optional<std::string> string(std::string_view key, const std::vector<std::string>& choices = {});
  std::string string_or(std::string_view key, std::string fallback, const std::vector<std::string>& choices = {});
  std::optional<std::vector<std::string>> string_array(std::string_view key);
  std::optional<std::vector<double>> number_array(std::string_view key, NumberRange range = {});

  /// A reader for the object at `key`, or nullopt (with an error if it is not an object).
  std::optional<JsonReader> object(std::string_view key);
  /// Readers for each element of the array of objects at `key`.
  std::vector<JsonReader> object_array(std::string_view key);
  /// Each key/value of the object at `key`, for maps keyed by name (e.g. joint overrides).
  std::vector<std::pair<std::string, JsonReader>> object_map(std::string_view key);

  /// The value at `key` as is, for a part validated elsewhere (a driver's params).
  std::optional<nlohmann::json> raw(std::string_view key);

  /// Records an error for a key that is required but missing.
  void require(std::string_view key, std::string_view what);
  void error(std::string_view key, const std::string& message);
  std::string path_of(std::string_view key) const;
  const std::string& path() const { return path_; }

  /// Reports every key present in the object that no accessor asked for.
  void finish();

 private:
  const nlohmann::json* find(std::string_view key);
  void expected(std::string_view key, const std::string& what, const nlohmann::json& got);

  const nlohmann::json* value_;
  std::string path_;
  std::vector<std::string>* errors_;
  std::set<std::string, std::less<>> consumed_;
};

/// Parses JSON text that may contain // and /* */ comments. On failure returns nullopt and
/// appends "<origin>: <parser message>" to errors.
std::optional<nlohmann::json> parse_json_with_comments(std::string_view text, std::string_view origin,
                                                       std::vector<std::string>& errors);

/// "a; b; c" — how robotd joins a list of problems into one message.
std::string join_errors(const std::vector<std::string>& errors);

}  // namespace robotd
