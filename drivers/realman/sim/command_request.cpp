#include "command_request.hpp"

namespace robotd::realman::sim {
namespace {

std::string range(std::int64_t min, std::int64_t max) { return std::to_string(min) + " … " + std::to_string(max); }

/// The value as an int64 if it is an integer that fits.
std::optional<std::int64_t> as_integer(const nlohmann::json& value) {
  if (value.is_number_integer()) return value.get<std::int64_t>();
  if (value.is_number_unsigned() && value.get<std::uint64_t>() <= INT64_MAX) {
    return static_cast<std::int64_t>(value.get<std::uint64_t>());
  }
  return std::nullopt;
}

}  // namespace

const nlohmann::json& CommandRequest::field(const char* key, const std::string& expected) const {
  const auto found = body_.find(key);
  if (found == body_.end()) throw Refusal(std::string("missing \"") + key + "\" (" + expected + ")");
  return *found;
}

std::int64_t CommandRequest::integer(const char* key, std::int64_t min, std::int64_t max) const {
  const std::string expected = "an integer " + range(min, max);
  const nlohmann::json& value = field(key, expected);
  const auto number = as_integer(value);
  if (!number || *number < min || *number > max) {
    throw Refusal(std::string("\"") + key + "\" must be " + expected + ", got " + value.dump());
  }
  return *number;
}

std::optional<std::int64_t> CommandRequest::optional_integer(const char* key, std::int64_t min,
                                                             std::int64_t max) const {
  if (!has(key)) return std::nullopt;
  return integer(key, min, max);
}

bool CommandRequest::boolean(const char* key) const {
  const nlohmann::json& value = field(key, "true or false");
  if (value.is_boolean()) return value.get<bool>();
  if (const auto number = as_integer(value); number && (*number == 0 || *number == 1)) return *number == 1;
  throw Refusal(std::string("\"") + key + "\" must be true or false, got " + value.dump());
}

std::optional<bool> CommandRequest::optional_boolean(const char* key) const {
  if (!has(key)) return std::nullopt;
  return boolean(key);
}

std::vector<std::int64_t> CommandRequest::integers(const char* key, std::size_t count, std::int64_t min,
                                                   std::int64_t max, const char* unit) const {
  const std::string expected = std::to_string(count) + " integers (" + unit + ")";
  const nlohmann::json& value = field(key, expected);
  if (!value.is_array() || value.size() != count) {
    throw Refusal(std::string("\"") + key + "\" must be " + expected + ", got " + value.dump());
  }
  std::vector<std::int64_t> numbers;
  numbers.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const auto number = as_integer(value[i]);
    if (!number || *number < min || *number > max) {
      throw Refusal(std::string("\"") + key + "\"[" + std::to_string(i) + "] must be an integer " + range(min, max) +
                    " (" + unit + "), got " + value[i].dump());
    }
    numbers.push_back(*number);
  }
  return numbers;
}

std::string CommandRequest::string(const char* key) const {
  const nlohmann::json& value = field(key, "a string");
  if (!value.is_string()) throw Refusal(std::string("\"") + key + "\" must be a string, got " + value.dump());
  return value.get<std::string>();
}

const nlohmann::json& CommandRequest::object(const char* key) const {
  const nlohmann::json& value = field(key, "an object");
  if (!value.is_object()) throw Refusal(std::string("\"") + key + "\" must be an object, got " + value.dump());
  return value;
}

}  // namespace robotd::realman::sim
