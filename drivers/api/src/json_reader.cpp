#include "robotd/driver/json_reader.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace robotd {
namespace {

std::string describe_value(const nlohmann::json& value) {
  std::string text = value.dump();
  constexpr std::size_t kMaxShown = 60;
  if (text.size() > kMaxShown) text = text.substr(0, kMaxShown) + "…";
  return text;
}

std::string range_text(NumberRange range) {
  std::ostringstream out;
  if (std::isfinite(range.min) && std::isfinite(range.max)) {
    out << " in " << range.min << ".." << range.max;
  } else if (std::isfinite(range.min)) {
    out << " >= " << range.min;
  } else if (std::isfinite(range.max)) {
    out << " <= " << range.max;
  }
  return out.str();
}

}  // namespace

JsonReader::JsonReader(const nlohmann::json& value, std::string path, std::vector<std::string>& errors)
    : value_(&value), path_(std::move(path)), errors_(&errors) {
  if (!value.is_object()) {
    errors_->push_back((path_.empty() ? std::string("the document") : path_) + ": expected an object, got " +
                       describe_value(value));
  }
}

std::string JsonReader::path_of(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

void JsonReader::error(std::string_view key, const std::string& message) {
  errors_->push_back(path_of(key) + ": " + message);
}

void JsonReader::expected(std::string_view key, const std::string& what, const nlohmann::json& got) {
  error(key, "expected " + what + ", got " + describe_value(got));
}

bool JsonReader::has(std::string_view key) const {
  return value_->is_object() && value_->find(std::string(key)) != value_->end();
}

const nlohmann::json* JsonReader::find(std::string_view key) {
  consumed_.insert(std::string(key));
  if (!value_->is_object()) return nullptr;
  const auto it = value_->find(std::string(key));
  return it == value_->end() ? nullptr : &*it;
}

void JsonReader::require(std::string_view key, std::string_view what) {
  consumed_.insert(std::string(key));
  if (value_->is_object() && !has(key)) error(key, "missing; expected " + std::string(what));
}

std::optional<double> JsonReader::number(std::string_view key, NumberRange range) {
  const nlohmann::json* value = find(key);
  if (value == nullptr) return std::nullopt;
  if (!value->is_number()) {
    expected(key, "a number" + range_text(range), *value);
    return std::nullopt;
  }
  const double number = value->get<double>();
  if (!(number >= range.min && number <= range.max)) {
    expected(key, "a number" + range_text(range), *value);
    return std::nullopt;
  }
  return number;
}

double JsonReader::number_or(std::string_view key, double fallback, NumberRange range) {
  return number(key, range).value_or(fallback);
}

std::optional<std::int64_t> JsonReader::integer(std::string_view key, std::int64_t min, std::int64_t max) {
  const nlohmann::json* value = find(key);
  if (value == nullptr) return std::nullopt;
  const std::string what = "an integer in " + std::to_string(min) + ".." + std::to_string(max);
  if (!value->is_number_integer()) {
    expected(key, what, *value);
    return std::nullopt;
  }
  const auto number = value->get<std::int64_t>();
  if (number < min || number > max) {
    expected(key, what, *value);
    return std::nullopt;
  }
  return number;
}

std::int64_t JsonReader::integer_or(std::string_view key, std::int64_t fallback, std::int64_t min, std::int64_t max) {
  return integer(key, min, max).value_or(fallback);
}

bool JsonReader::boolean_or(std::string_view key, bool fallback) {
  const nlohmann::json* value = find(key);
  if (value == nullptr) return fallback;
  if (!value->is_boolean()) {
    expected(key, "true or false", *value);
    return fallback;
  }
  return value->get<bool>();
}

std::optional<std::string> JsonReader::string(std::string_view key, const std::vector<std::string>& choices) {
  const nlohmann::json* value = find(key);
  if (value == nullptr) return std::nullopt;
  std::string what = "a string";
  if (!choices.empty()) {
    what = "one of ";
    for (std::size_t i = 0; i < choices.size(); ++i) what += (i > 0 ? ", \"" : "\"") + choices[i] + "\"";
  }
  if (!value->is_string()) {
    expected(key, what, *value);
    return std::nullopt;
  }
  auto text = value->get<std::string>();
  if (!choices.empty() && std::find(choices.begin(), choices.end(), text) == choices.end()) {
    expected(key, what, *value);
    return std::nullopt;
  }
  return text;
}

std::string JsonReader::string_or(std::string_view key, std::string fallback, const std::vector<std::string>& choices) {
  return string(key, choices).value_or(std::move(fallback));
}

std::optional<std::vector<std::string>> JsonReader::string_array(std::string_view key) {
  const nlohmann::json* value = find(key);
  if (value == nullptr) return std::nullopt;
  if (!value->is_array()) {
    expected(key, "an array of strings", *value);
    return std::nullopt;
  }
  std::vector<std::string> out;
  for (std::size_t i = 0; i < value->size(); ++i) {
    const auto& element = (*value)[i];
    if (!element.is_string()) {
      errors_->push_back(path_of(key) + "[" + std::to_string(i) + "]: expected a string, got " +
                         describe_value(element));
      return std::nullopt;
    }
    out.push_back(element.get<std::string>());
  }
  return out;
}

std::optional<std::vector<double>> JsonReader::number_array(std::string_view key, NumberRange range) {
  const nlohmann::json* value = find(key);
  if (value == nullptr) return std::nullopt;
  if (!value->is_array()) {
    expected(key, "an array of numbers", *value);
    return std::nullopt;
  }
  std::vector<double> out;
  for (std::size_t i = 0; i < value->size(); ++i) {
    const auto& element = (*value)[i];
    if (!element.is_number() || !(element.get<double>() >= range.min && element.get<double>() <= range.max)) {
      errors_->push_back(path_of(key) + "[" + std::to_string(i) + "]: expected a number" + range_text(range) +
                         ", got " + describe_value(element));
      return std::nullopt;
    }
    out.push_back(element.get<double>());
  }
  return out;
}

std::optional<nlohmann::json> JsonReader::raw(std::string_view key) {
  const nlohmann::json* value = find(key);
  if (value == nullptr) return std::nullopt;
  return *value;
}

std::optional<JsonReader> JsonReader::object(std::string_view key) {
  const nlohmann::json* value = find(key);
  if (value == nullptr) return std::nullopt;
  if (!value->is_object()) {
    expected(key, "an object", *value);
    return std::nullopt;
  }
  return JsonReader(*value, path_of(key), *errors_);
}

std::vector<JsonReader> JsonReader::object_array(std::string_view key) {
  std::vector<JsonReader> out;
  const nlohmann::json* value = find(key);
  if (value == nullptr) return out;
  if (!value->is_array()) {
    expected(key, "an array of objects", *value);
    return out;
  }
  for (std::size_t i = 0; i < value->size(); ++i) {
    out.emplace_back((*value)[i], path_of(key) + "[" + std::to_string(i) + "]", *errors_);
  }
  return out;
}

std::vector<std::pair<std::string, JsonReader>> JsonReader::object_map(std::string_view key) {
  std::vector<std::pair<std::string, JsonReader>> out;
  const nlohmann::json* value = find(key);
  if (value == nullptr) return out;
  if (!value->is_object()) {
    expected(key, "an object", *value);
    return out;
  }
  for (const auto& [name, element] : value->items()) {
    out.emplace_back(name, JsonReader(element, path_of(key) + "." + name, *errors_));
  }
  return out;
}

void JsonReader::finish() {
  if (!value_->is_object()) return;
  std::string known;
  for (const auto& name : consumed_) known += (known.empty() ? "" : ", ") + name;
  for (const auto& [key, element] : value_->items()) {
    if (consumed_.find(key) != consumed_.end()) continue;
    error(key,
          known.empty() ? "unknown key (this object takes no keys)" : "unknown key (expected one of: " + known + ")");
  }
}

std::optional<nlohmann::json> parse_json_with_comments(std::string_view text, std::string_view origin,
                                                       std::vector<std::string>& errors) {
  try {
    return nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/true, /*ignore_comments=*/true);
  } catch (const nlohmann::json::exception& e) {  // parse_error, and out_of_range for a number beyond a double
    errors.push_back(std::string(origin) + ": invalid JSON: " + e.what());
    return std::nullopt;
  }
}

std::string join_errors(const std::vector<std::string>& errors) {
  std::string out;
  for (const auto& e : errors) out += (out.empty() ? "" : "; ") + e;
  return out;
}

}  // namespace robotd
