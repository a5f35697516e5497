// Orientation conversions the arm drivers share.
#pragma once

#include <array>

namespace robotd::kinematics {

/// Roll, pitch, yaw about fixed axes x, y, z (R = Rz(yaw)·Ry(pitch)·Rx(roll)) as a unit
/// quaternion (x, y, z, w). No allocation.
std::array<double, 4> quaternion_xyzw_from_rpy(const std::array<double, 3>& rpy_rad) noexcept;

}  // namespace robotd::kinematics
