// The arms of §7 with their device type codes and joint limits (the SDK's, in degrees there),
// looked up by robotd's name or by what the controller reports.
#include <algorithm>
#include <array>
#include <cstddef>
#include <numbers>
#include <optional>
#include <span>
#include <string_view>

#include "xarm_codec.hpp"

namespace robotd::xarm {
namespace {

using Degrees = std::array<double, kMaxDof>;

constexpr double kXarmTcpSpeed = 1.0;   // m/s
constexpr double kLite6TcpSpeed = 0.5;  // m/s

constexpr int kLite6Type = 9;
constexpr int kUf850Type = 12;

/// UFACTORY publishes one D-H table per family: xArm 5, xArm 6 (every 6-joint type but Lite 6 and
/// 850), xArm 7, Lite 6, UFACTORY 850.
constexpr std::string_view kinematic_model_of(std::size_t dof, int type_code) {
  if (dof == 5) return "xarm5";
  if (dof == 7) return "xarm7";
  if (type_code == kLite6Type) return "lite6";
  if (type_code == kUf850Type) return "uf850";
  return "xarm6";
}

constexpr ArmModel model(std::string_view name, std::string_view display, std::size_t dof, int type_code,
                         const Degrees& min_deg, const Degrees& max_deg, double max_tcp_speed_m_s = kXarmTcpSpeed) {
  ArmModel arm{.name = name,
               .display = display,
               .dof = dof,
               .type_code = type_code,
               .min_rad = {},
               .max_rad = {},
               .max_tcp_speed_m_s = max_tcp_speed_m_s,
               .kinematic_model = kinematic_model_of(dof, type_code)};
  for (std::size_t j = 0; j < dof; ++j) {
    arm.min_rad[j] = min_deg[j] * std::numbers::pi / 180.0;
    arm.max_rad[j] = max_deg[j] * std::numbers::pi / 180.0;
  }
  return arm;
}

// §7's table, in its order.
constexpr auto kModels = std::to_array<ArmModel>({
    model("xarm5", "xArm 5", 5, 5, {-360, -118, -225, -97, -360}, {360, 120, 11, 180, 360}),
    model("xarm5-1305", "xArm 5 (1305)", 5, 51305, {-360, -117, -219, -97, -360}, {360, 116, 10, 180, 360}),
    model("xarm6", "xArm 6", 6, 6, {-360, -118, -225, -360, -97, -360}, {360, 120, 11, 360, 180, 360}),
    model("xarm6-1305", "xArm 6 (1305)", 6, 61305, {-360, -117, -219, -360, -97, -360}, {360, 116, 10, 360, 180, 360}),
    model("xarm6-x8", "xArm 6 (X8)", 6, 8, {-360, -118, -11, -360, -97, -360}, {360, 120, 225, 360, 180, 360}),
    model("lite6", "Lite 6", 6, 9, {-360, -150, -3.5, -360, -124, -360}, {360, 150, 300, 360, 124, 360},
          kLite6TcpSpeed),
    model("xarm6-x11", "xArm 6 (X11)", 6, 11, {-360, -360, -360, -360, -97, -360}, {360, 360, 360, 360, 180, 360}),
    model("uf850", "UFACTORY 850", 6, 12, {-360, -132, -242, -360, -124, -360}, {360, 132, 3.5, 360, 124, 360}),
    model("xarm7-x3", "xArm 7 (X3)", 7, 3, {-360, -118, -360, -225, -360, -97, -360},
          {360, 120, 360, 11, 360, 180, 360}),
    model("xarm7", "xArm 7", 7, 7, {-360, -118, -360, -11, -360, -97, -360}, {360, 120, 360, 225, 360, 180, 360}),
    model("xarm7-1305", "xArm 7 (1305)", 7, 71305, {-360, -117, -360, -6, -360, -97, -360},
          {360, 116, 360, 225, 360, 180, 360}),
    model("xarm7-x13", "xArm 7 (X13)", 7, 13, {-360, -120, -360, -225, -360, -180, -360},
          {360, 118, 360, 11, 360, 97, 360}),
});

// Type codes 5, 6 and 7 are the X4 generation of each axis count.
constexpr int kFirstX4Type = 5;
constexpr int kLastX4Type = 7;

constexpr char lower(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; }

bool same_name(std::string_view a, std::string_view b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](char x, char y) { return lower(x) == lower(y); });
}

template <class Predicate>
std::optional<ArmModel> first_model(Predicate matches) {
  const auto found = std::find_if(kModels.begin(), kModels.end(), matches);
  if (found == kModels.end()) return std::nullopt;
  return *found;
}

}  // namespace

std::optional<ArmModel> find_model(std::string_view name) {
  return first_model([name](const ArmModel& arm) { return same_name(arm.name, name); });
}

std::optional<ArmModel> model_for_type(int axes, int type_code) {
  if (type_code >= kFirstX4Type && type_code <= kLastX4Type) type_code = axes;
  return first_model([axes, type_code](const ArmModel& arm) {
    return arm.dof == static_cast<std::size_t>(axes) && arm.type_code == type_code;
  });
}

std::span<const ArmModel> known_models() { return kModels; }

}  // namespace robotd::xarm
