#include "sim_options.hpp"

namespace robotd::realman::sim {

std::optional<Generation> parse_generation(std::string_view text) {
  if (text == "2") return Generation::k2;
  if (text == "3") return Generation::k3;
  if (text == "4") return Generation::k4;
  return std::nullopt;
}

std::optional<ErrorShape> parse_error_shape(std::string_view text) {
  if (text == "list") return ErrorShape::kList;
  if (text == "legacy") return ErrorShape::kLegacy;
  if (text == "scalar") return ErrorShape::kScalar;
  return std::nullopt;
}

std::string_view error_shape_name(ErrorShape shape) {
  switch (shape) {
    case ErrorShape::kList:
      return "list";
    case ErrorShape::kLegacy:
      return "legacy";
    case ErrorShape::kScalar:
      return "scalar";
  }
  return "list";
}

}  // namespace robotd::realman::sim
