// Reading a control-channel request: the fields an op takes, checked, with error replies that
// say what was wrong and what is expected. A handler throws RequestError; the simulator's
// dispatcher turns it into {"ok": false, "error": what()}.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace robotd::sim_control {

/// A request that names a field wrongly: the message says which and what is expected.
class RequestError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// {"ok": false, "error": message}
nlohmann::json error_reply(const std::string& message);

/// The request's "op" string; throws naming `ops` (the list of valid ops) when it is missing.
std::string op_of(const nlohmann::json& request, const char* ops);
/// Throws for any field other than "op" and `fields`.
void expect_fields(const nlohmann::json& request, const std::string& op, std::initializer_list<const char*> fields);
/// A required integer field within [min, max].
std::int64_t integer_field(const nlohmann::json& request, const std::string& op, const char* name, std::int64_t min,
                           std::int64_t max);
/// A required number field.
double number_field(const nlohmann::json& request, const std::string& op, const char* name);
/// A required array of exactly `count` numbers, in `unit` (named in the error).
std::vector<double> numbers_field(const nlohmann::json& request, const std::string& op, const char* name,
                                  std::size_t count, const char* unit);
/// A required true/false field.
bool boolean_field(const nlohmann::json& request, const std::string& op, const char* name);

}  // namespace robotd::sim_control
