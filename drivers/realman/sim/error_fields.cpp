#include "error_fields.hpp"

#include <algorithm>

namespace robotd::realman::sim {
namespace {

constexpr std::uint16_t kControllerErrors = 0x5000;  // 0x5xxx: the controller itself (§7.1)

}  // namespace

std::uint16_t first_error(const std::vector<std::uint16_t>& errors) { return errors.empty() ? 0 : errors.front(); }

void add_error_fields(nlohmann::json& object, ErrorShape shape, const std::vector<std::uint16_t>& errors) {
  switch (shape) {
    case ErrorShape::kList:
      object["err"] = errors.empty() ? std::vector<std::uint16_t>{0} : errors;
      return;
    case ErrorShape::kScalar:
      object["err"] = first_error(errors);
      return;
    case ErrorShape::kLegacy: {
      const auto is_controller = [](std::uint16_t code) { return (code & 0xF000) == kControllerErrors; };
      const auto arm = std::find_if_not(errors.begin(), errors.end(), is_controller);
      const auto controller = std::find_if(errors.begin(), errors.end(), is_controller);
      object["arm_err"] = arm == errors.end() ? 0 : *arm;
      object["sys_err"] = controller == errors.end() ? 0 : *controller;
      return;
    }
  }
}

}  // namespace robotd::realman::sim
