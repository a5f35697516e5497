// The non-throwing field reads behind every reply parser: nlohmann's accessors are only called
// after the type has been checked.
#include "field_reader.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace robotd::realman {
namespace {

constexpr std::size_t kExcerptBytes = 60;

/// The start of `text` as printable ASCII: a message may be anything a socket delivered.
std::string excerpt(std::string_view text) {
  constexpr std::string_view kHexDigits = "0123456789ABCDEF";
  std::string out;
  for (const char c : text.substr(0, kExcerptBytes)) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x20 && byte < 0x7F) {
      out += c;
    } else {
      out += "\\x";
      out += kHexDigits[byte >> 4];
      out += kHexDigits[byte & 0x0F];
    }
  }
  if (text.size() > kExcerptBytes) out += "...";
  return out;
}

std::optional<std::int64_t> as_integer(const nlohmann::json& value) {
  if (value.is_number_unsigned()) {
    const auto unsigned_value = value.get<std::uint64_t>();
    if (unsigned_value > static_cast<std::uint64_t>(FieldReader::kAnyMax)) return std::nullopt;
    return static_cast<std::int64_t>(unsigned_value);
  }
  if (value.is_number_integer()) return value.get<std::int64_t>();
  return std::nullopt;
}

std::optional<bool> as_flag(const nlohmann::json& value) {
  if (value.is_boolean()) return value.get<bool>();
  const auto number = as_integer(value);
  if (!number || *number < 0 || *number > 1) return std::nullopt;
  return *number == 1;
}

std::string range_text(std::int64_t min, std::int64_t max) {
  if (min == FieldReader::kAnyMin && max == FieldReader::kAnyMax) return "";
  return " in " + std::to_string(min) + ".." + std::to_string(max);
}

std::string count_text(std::size_t min_count, std::size_t max_count) {
  if (min_count == max_count) return std::to_string(min_count);
  if (max_count == FieldReader::kAnyCount) return "at least " + std::to_string(min_count);
  return std::to_string(min_count) + ".." + std::to_string(max_count);
}

/// A value as it appeared, shortened; replaces bytes that are not UTF-8 instead of throwing.
std::string shown(const nlohmann::json& value) {
  return excerpt(value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
}

/// "a string", "an array", "null": what was found instead.
std::string kind_of(const nlohmann::json& value) {
  std::string name = value.type_name();
  if (value.is_null()) return name;
  return (name.find_first_of("aeiou") == 0 ? "an " : "a ") + name;
}

}  // namespace

Result<nlohmann::json> parse_object(std::string_view text) {
  nlohmann::json parsed = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (parsed.is_discarded()) return make_error(ErrorCode::kInvalidArgument, "not JSON: " + excerpt(text));
  if (!parsed.is_object()) {
    return make_error(ErrorCode::kInvalidArgument, "JSON but not an object: " + excerpt(text));
  }
  return parsed;
}

FieldReader::FieldReader(const nlohmann::json& object, std::string path, std::string& problem)
    : FieldReader(&object, std::move(path), &problem) {}

FieldReader::FieldReader(const nlohmann::json* object, std::string path, std::string* problem)
    : object_(object), path_(std::move(path)), problem_(problem) {
  if (object_ != nullptr && !object_->is_object()) {
    report("", "expected an object, got " + kind_of(*object_));
    object_ = nullptr;
  }
}

bool FieldReader::has(std::string_view name) const {
  return object_ != nullptr && object_->find(name) != object_->end();
}

const nlohmann::json* FieldReader::find(std::string_view name) {
  if (object_ == nullptr) return nullptr;  // already reported
  const auto found = object_->find(name);
  if (found == object_->end()) {
    report(name, "missing");
    return nullptr;
  }
  return &*found;
}

void FieldReader::report(std::string_view name, const std::string& message) {
  if (!problem_->empty()) return;
  std::string where = path_;
  if (!name.empty()) where += (where.empty() ? "" : ".") + std::string(name);
  *problem_ = (where.empty() ? "the message" : "\"" + where + "\"") + ": " + message;
}

std::int64_t FieldReader::integer(std::string_view name, std::int64_t min, std::int64_t max) {
  const nlohmann::json* value = find(name);
  if (value == nullptr) return 0;
  const auto number = as_integer(*value);
  if (!number || *number < min || *number > max) {
    report(name, "expected an integer" + range_text(min, max) + ", got " + shown(*value));
    return 0;
  }
  return *number;
}

bool FieldReader::flag(std::string_view name) {
  const nlohmann::json* value = find(name);
  if (value == nullptr) return false;
  const auto parsed = as_flag(*value);
  if (!parsed) report(name, "expected a bool (or 0/1), got " + shown(*value));
  return parsed.value_or(false);
}

std::string FieldReader::text(std::string_view name) {
  const nlohmann::json* value = find(name);
  if (value == nullptr) return "";
  if (!value->is_string()) {
    report(name, "expected a string, got " + kind_of(*value));
    return "";
  }
  return value->get<std::string>();
}

std::vector<std::int64_t> FieldReader::integers(std::string_view name, std::size_t min_count, std::size_t max_count,
                                                std::int64_t min, std::int64_t max) {
  const nlohmann::json* value = find(name);
  if (value == nullptr) return {};
  if (!value->is_array() || value->size() < min_count || value->size() > max_count) {
    const std::string got = value->is_array() ? std::to_string(value->size()) + " entries" : kind_of(*value);
    report(name, "expected an array of " + count_text(min_count, max_count) + " integers, got " + got);
    return {};
  }
  std::vector<std::int64_t> numbers;
  numbers.reserve(value->size());
  for (std::size_t i = 0; i < value->size(); ++i) {
    const auto number = as_integer((*value)[i]);
    if (!number || *number < min || *number > max) {
      report(name, "entry " + std::to_string(i) + ": expected an integer" + range_text(min, max) + ", got " +
                       shown((*value)[i]));
      return {};
    }
    numbers.push_back(*number);
  }
  return numbers;
}

std::vector<bool> FieldReader::flags(std::string_view name, std::size_t min_count, std::size_t max_count) {
  const nlohmann::json* value = find(name);
  if (value == nullptr) return {};
  if (!value->is_array() || value->size() < min_count || value->size() > max_count) {
    const std::string got = value->is_array() ? std::to_string(value->size()) + " entries" : kind_of(*value);
    report(name, "expected an array of " + count_text(min_count, max_count) + " flags, got " + got);
    return {};
  }
  std::vector<bool> out;
  out.reserve(value->size());
  for (std::size_t i = 0; i < value->size(); ++i) {
    const auto parsed = as_flag((*value)[i]);
    if (!parsed) {
      report(name, "entry " + std::to_string(i) + ": expected a bool (or 0/1), got " + shown((*value)[i]));
      return {};
    }
    out.push_back(*parsed);
  }
  return out;
}

FieldReader FieldReader::object(std::string_view name) {
  const std::string child_path = path_.empty() ? std::string(name) : path_ + "." + std::string(name);
  return FieldReader(find(name), child_path, problem_);
}

std::vector<std::uint16_t> FieldReader::error_codes() {
  if (object_ == nullptr) return {};
  const auto values = error_values(*object_);
  if (values.empty()) report("", "no error field (\"err\", or \"arm_err\" and \"sys_err\")");
  std::vector<std::uint16_t> codes;
  for (const auto& [field, value] : values) {
    const auto code = as_integer(*value);
    if (!code || *code < 0 || *code > 0xFFFF) {
      report(field, "expected error codes 0..65535, got " + shown(*value));
      return {};
    }
    const auto code16 = static_cast<std::uint16_t>(*code);
    if (code16 != 0 && std::find(codes.begin(), codes.end(), code16) == codes.end()) codes.push_back(code16);
  }
  return codes;
}

}  // namespace robotd::realman
