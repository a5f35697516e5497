#include "robotd/kinematics/rotation.hpp"

#include <cmath>

namespace robotd::kinematics {

std::array<double, 4> quaternion_xyzw_from_rpy(const std::array<double, 3>& rpy_rad) noexcept {
  const double cx = std::cos(rpy_rad[0] / 2);
  const double sx = std::sin(rpy_rad[0] / 2);
  const double cy = std::cos(rpy_rad[1] / 2);
  const double sy = std::sin(rpy_rad[1] / 2);
  const double cz = std::cos(rpy_rad[2] / 2);
  const double sz = std::sin(rpy_rad[2] / 2);
  return {sx * cy * cz - cx * sy * sz, cx * sy * cz + sx * cy * sz, cx * cy * sz - sx * sy * cz,
          cx * cy * cz + sx * sy * sz};
}

}  // namespace robotd::kinematics
