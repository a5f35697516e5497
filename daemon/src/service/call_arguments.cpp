#include "service/call_arguments.hpp"

#include <string>

namespace robotd::service {

Result<nlohmann::json> parse_call_arguments(std::string_view args_json) {
  if (args_json.empty()) return nlohmann::json::object();
  nlohmann::json args;
  try {
    args = nlohmann::json::parse(args_json);
  } catch (const nlohmann::json::exception& e) {  // parse_error, and out_of_range for a number beyond a double
    return make_error(ErrorCode::kInvalidArgument,
                      "args_json is not valid JSON (" + std::string(e.what()) + "); expected an object");
  }
  if (!args.is_object()) {
    return make_error(ErrorCode::kInvalidArgument, "args_json must be a JSON object, got " + args.dump());
  }
  return args;
}

}  // namespace robotd::service
