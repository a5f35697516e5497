// The one rule for changing a running device's limits: they may only narrow. Applied to what a
// driver describes once connected, again after every reconnect and after every device op
// (docs/safety.md "Limits narrow at run time, never widen"). Pure: the caller owns the limits.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "robotd/driver/driver.hpp"
#include "robotd/result.hpp"

namespace robotd::control {

struct LimitChange {
  std::size_t joint = 0;
  const char* key = "";  // "position_min_rad", …
  double from = 0;
  double to = 0;
};

/// `current` tightened by `reported` joint by joint: position_min up, position_max down,
/// velocity, acceleration and effort maxima down; a wider reported value leaves the current
/// one as it is. Returns what changed. If a joint would be left with no position range the
/// whole change is refused (error naming the joint and both ranges) and `current` is untouched.
Result<std::vector<LimitChange>> narrow_limits(std::vector<driver::JointLimits>& current,
                                               std::span<const driver::JointLimits> reported,
                                               std::span<const std::string> joint_names);

}  // namespace robotd::control
