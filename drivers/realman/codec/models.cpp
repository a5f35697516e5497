// The arms of §8 with the joint ranges of the doc's "working space" text (degrees). ECO65 uses
// the doc's ranges; its URDF disagrees and is not trusted here.
#include <algorithm>
#include <array>
#include <cstddef>
#include <numbers>
#include <optional>
#include <span>
#include <string_view>

#include "realman_codec.hpp"

namespace robotd::realman {
namespace {

using Degrees = std::array<double, kMaxDof>;

constexpr ArmModel model(std::string_view name, std::size_t dof, const Degrees& min_deg, const Degrees& max_deg,
                         std::string_view kinematic_model, std::string_view force_kinematic_model) {
  ArmModel arm{name, dof, {}, {}, kinematic_model, force_kinematic_model};
  for (std::size_t j = 0; j < dof; ++j) {
    arm.min_rad[j] = min_deg[j] * std::numbers::pi / 180.0;
    arm.max_rad[j] = max_deg[j] * std::numbers::pi / 180.0;
  }
  return arm;
}

constexpr auto kModels = std::to_array<ArmModel>({
    model("RM65", 6, {-178, -130, -135, -178, -128, -360}, {178, 130, 135, 178, 128, 360}, "rm65", "rm65_6f"),
    model("RM75", 7, {-178, -130, -178, -135, -178, -128, -360}, {178, 130, 178, 135, 178, 128, 360}, "rm75",
          "rm75_6f"),
    model("RML63", 6, {-178, -178, -178, -178, -178, -360}, {178, 178, 145, 178, 178, 360}, "rml63", "rml63_6f"),
    model("ECO65", 6, {-178, -178, -160, -178, -178, -360}, {178, 135, 145, 178, 178, 360}, "", ""),
    // The GEN72's force version has a flange as long as the standard one.
    model("GEN72", 7, {-172, -105, -172, -170, -172, -90, -172}, {172, 105, 172, 55, 172, 120, 172}, "gen72", "gen72"),
});

}  // namespace

std::optional<ArmModel> find_model(std::string_view product_version) {
  const std::string_view name = product_version.substr(0, product_version.find('-'));
  const auto found =
      std::find_if(kModels.begin(), kModels.end(), [name](const ArmModel& arm) { return arm.name == name; });
  if (found == kModels.end()) return std::nullopt;
  return *found;
}

std::string_view kinematic_model_of(std::string_view product_version) {
  const auto model = find_model(product_version);
  if (!model) return {};
  const bool force = product_version.find("-6F") != std::string_view::npos;
  return force ? model->force_kinematic_model : model->kinematic_model;
}

std::span<const ArmModel> known_models() { return kModels; }

}  // namespace robotd::realman
