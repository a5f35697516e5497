#include "control/limit_narrowing.hpp"

#include <algorithm>
#include <sstream>

namespace robotd::control {

Result<std::vector<LimitChange>> narrow_limits(std::vector<driver::JointLimits>& current,
                                               std::span<const driver::JointLimits> reported,
                                               std::span<const std::string> joint_names) {
  std::vector<driver::JointLimits> next = current;
  std::vector<LimitChange> changes;
  const std::size_t count = std::min(next.size(), reported.size());
  for (std::size_t j = 0; j < count; ++j) {
    driver::JointLimits& limits = next[j];
    const driver::JointLimits& device = reported[j];
    const auto tighten = [&](double& limit, double value, bool upper, const char* key) {
      if (!(upper ? value < limit : value > limit)) return;  // wider, equal or not a number: kept
      changes.push_back(LimitChange{j, key, limit, value});
      limit = value;
    };
    tighten(limits.position_min_rad, device.position_min_rad, false, "position_min_rad");
    tighten(limits.position_max_rad, device.position_max_rad, true, "position_max_rad");
    if (limits.position_min_rad >= limits.position_max_rad) {
      std::ostringstream text;
      text << "joint '" << joint_names[j] << "': narrowing " << current[j].position_min_rad << ".."
           << current[j].position_max_rad << " rad by " << device.position_min_rad << ".." << device.position_max_rad
           << " rad leaves no position range (the minimum must stay below the maximum); limits unchanged";
      return make_error(ErrorCode::kInvalidArgument, text.str());
    }
    tighten(limits.velocity_max_rad_s, device.velocity_max_rad_s, true, "velocity_max_rad_s");
    tighten(limits.acceleration_max_rad_s2, device.acceleration_max_rad_s2, true, "acceleration_max_rad_s2");
    tighten(limits.effort_max_nm, device.effort_max_nm, true, "effort_max_nm");
  }
  current = std::move(next);
  return changes;
}

}  // namespace robotd::control
