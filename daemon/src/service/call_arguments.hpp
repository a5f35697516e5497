// The arguments of a device_call request as its op receives them.
#pragma once

#include <string_view>

#include <nlohmann/json.hpp>

#include "robotd/result.hpp"

namespace robotd::service {

/// `args_json` as a JSON object: "" is {}; text that is not JSON, or JSON that is not an object,
/// is refused (kInvalidArgument) with a message that says why.
Result<nlohmann::json> parse_call_arguments(std::string_view args_json);

}  // namespace robotd::service
