#include "robotd/sim_control/control_request.hpp"

#include <algorithm>

namespace robotd::sim_control {

using nlohmann::json;

json error_reply(const std::string& message) { return {{"ok", false}, {"error", message}}; }

std::string op_of(const json& request, const char* ops) {
  const auto op = request.find("op");
  if (op == request.end() || !op->is_string()) {
    throw RequestError(std::string("the request needs \"op\": a string, one of ") + ops);
  }
  return op->get<std::string>();
}

void expect_fields(const json& request, const std::string& op, std::initializer_list<const char*> fields) {
  for (const auto& item : request.items()) {
    const std::string& key = item.key();
    if (key == "op") continue;
    if (std::none_of(fields.begin(), fields.end(), [&key](const char* field) { return key == field; })) {
      std::string expected;
      for (const char* field : fields) {
        expected += expected.empty() ? "\"" : ", \"";
        expected += field;
        expected += '"';
      }
      std::string message = "op \"" + op + "\" does not take \"";
      message += key;
      message += expected.empty() ? "\": it takes no fields" : "\"; its fields: ";
      message += expected;
      throw RequestError(message);
    }
  }
}

std::int64_t integer_field(const json& request, const std::string& op, const char* name, std::int64_t min,
                           std::int64_t max) {
  const std::string range = std::to_string(min) + " … " + std::to_string(max);
  const auto field = request.find(name);
  if (field == request.end()) throw RequestError("op \"" + op + "\" needs \"" + name + "\": an integer " + range);
  bool valid = false;
  if (field->is_number_unsigned()) {  // non-negative literals parse as unsigned: no wrap past INT64_MAX
    const auto value = field->get<std::uint64_t>();
    valid = max >= 0 && value <= static_cast<std::uint64_t>(max) && static_cast<std::int64_t>(value) >= min;
  } else if (field->is_number_integer()) {
    const auto value = field->get<std::int64_t>();
    valid = value >= min && value <= max;
  }
  if (!valid) {
    throw RequestError("op \"" + op + "\": \"" + name + "\" must be an integer " + range + ", not " + field->dump());
  }
  return field->get<std::int64_t>();
}

std::vector<double> numbers_field(const json& request, const std::string& op, const char* name, std::size_t count,
                                  const char* unit) {
  const auto field = request.find(name);
  const std::string expected =
      "op \"" + op + "\" needs \"" + name + "\": " + std::to_string(count) + " numbers (" + unit + ")";
  if (field == request.end() || !field->is_array() || field->size() != count) throw RequestError(expected);
  std::vector<double> numbers;
  numbers.reserve(count);
  for (const json& value : *field) {
    if (!value.is_number()) throw RequestError(expected);
    numbers.push_back(value.get<double>());
  }
  return numbers;
}

double number_field(const json& request, const std::string& op, const char* name) {
  const auto field = request.find(name);
  if (field == request.end() || !field->is_number()) {
    throw RequestError("op \"" + op + "\" needs \"" + name + "\": a number" +
                       (field == request.end() ? std::string() : ", not " + field->dump()));
  }
  return field->get<double>();
}

bool boolean_field(const json& request, const std::string& op, const char* name) {
  const auto field = request.find(name);
  if (field == request.end() || !field->is_boolean()) {
    throw RequestError("op \"" + op + "\" needs \"" + name + "\": true or false" +
                       (field == request.end() ? std::string() : ", not " + field->dump()));
  }
  return field->get<bool>();
}

}  // namespace robotd::sim_control
