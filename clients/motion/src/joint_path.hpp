// Sampling one s(t) onto a straight joint-space line.
#pragma once

#include <cstddef>
#include <string>

#include "robotd/motion/path_profile.hpp"
#include "robotd/motion/trajectory.hpp"

namespace robotd::motion::detail {

/// from + (to − from)·s(k·dt) and its velocity for k = 0 … count (the last sample exactly `to`,
/// at rest), `profile` lasting count·dt.
Trajectory sample_joint_path(const Joints& from, const Joints& to, const PathProfile& profile, std::size_t count,
                             double dt_s, std::string how);

}  // namespace robotd::motion::detail
