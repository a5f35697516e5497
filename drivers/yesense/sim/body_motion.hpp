// The body the emulated IMU is strapped to: it holds a base orientation and, unless told to
// hold still, sways gently about it. README.md states the motion.
#pragma once

#include <cstdint>

#include "robotd/imu/imu_reading.hpp"

namespace robotd::imu::sim {

inline constexpr double kGravity = 9.80665;  // m/s²

class BodyMotion {
 public:
  /// Swaying about level, yaw 0, from `now_ns`.
  explicit BodyMotion(std::int64_t now_ns) : sway_start_ns_(now_ns) {}

  /// Holds still at `base` (the sway stops).
  void hold(const EulerRad& base) noexcept;
  /// Sways about the orientation of `now_ns`, from there on.
  void sway(std::int64_t now_ns) noexcept;
  bool swaying() const noexcept { return swaying_; }

  /// The orientation at `now_ns`.
  EulerRad orientation(std::int64_t now_ns) const noexcept;
  /// What an ideal IMU at the body's centre of rotation reads at `now_ns`: orientation (also as
  /// Euler angles), body rates, and specific force (+g along the body's up axis when level).
  ImuReading sample(std::int64_t now_ns) const noexcept;

 private:
  EulerRad base_{};
  bool swaying_ = true;
  std::int64_t sway_start_ns_;
};

}  // namespace robotd::imu::sim
