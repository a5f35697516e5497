#include "joint_path.hpp"

#include <utility>

namespace robotd::motion::detail {

Trajectory sample_joint_path(const Joints& from, const Joints& to, const PathProfile& profile, std::size_t count,
                             double dt_s, std::string how) {
  Trajectory trajectory{.dt_s = dt_s,
                        .positions = {},
                        .velocities = {},
                        .shape = profile.shape(),
                        .duration_s = static_cast<double>(count) * dt_s,
                        .how = std::move(how)};
  trajectory.positions.reserve(count + 1);
  trajectory.velocities.reserve(count + 1);
  for (std::size_t k = 0; k < count; ++k) {
    const double t_s = static_cast<double>(k) * dt_s;
    const double s = profile.position(t_s);
    const double rate = profile.rate(t_s);
    Joints position(from.size());
    Joints velocity(from.size());
    for (std::size_t j = 0; j < from.size(); ++j) {
      position[j] = from[j] + (to[j] - from[j]) * s;
      velocity[j] = (to[j] - from[j]) * rate;
    }
    trajectory.positions.push_back(std::move(position));
    trajectory.velocities.push_back(std::move(velocity));
  }
  trajectory.positions.push_back(to);
  trajectory.velocities.emplace_back(to.size(), 0.0);
  return trajectory;
}

}  // namespace robotd::motion::detail
