#include "robotd/driver/op_arguments.hpp"

namespace robotd::driver {

OpArguments::OpArguments(std::string_view op, const nlohmann::json& args, std::string_view usage)
    : op_(op),
      usage_(usage),
      args_(args.is_null() ? nlohmann::json::object() : args),
      reader_(args_, "args", errors_) {}

std::optional<Error> OpArguments::finish() {
  reader_.finish();
  if (errors_.empty()) return std::nullopt;
  return make_error(ErrorCode::kInvalidArgument, op_ + ": " + join_errors(errors_) + " (expects " + usage_ + ")");
}

}  // namespace robotd::driver
