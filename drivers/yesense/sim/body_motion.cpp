#include "body_motion.hpp"

#include <cmath>
#include <numbers>

#include "robotd/kinematics/rotation.hpp"

namespace robotd::imu::sim {
namespace {

/// One axis of the sway: amplitude · sin(2π · frequency · t).
struct Sway {
  double amplitude_rad;
  double frequency_hz;

  double angle(double t) const noexcept { return amplitude_rad * std::sin(omega() * t); }
  double rate(double t) const noexcept { return amplitude_rad * omega() * std::cos(omega() * t); }
  double omega() const noexcept { return 2 * std::numbers::pi * frequency_hz; }
};

constexpr Sway kRoll{.amplitude_rad = 0.05, .frequency_hz = 0.5};
constexpr Sway kPitch{.amplitude_rad = 0.03, .frequency_hz = 0.3};
constexpr Sway kYaw{.amplitude_rad = 0.02, .frequency_hz = 0.1};

double seconds_since(std::int64_t start_ns, std::int64_t now_ns) noexcept {
  return static_cast<double>(now_ns - start_ns) * 1e-9;
}

}  // namespace

void BodyMotion::hold(const EulerRad& base) noexcept {
  base_ = base;
  swaying_ = false;
}

void BodyMotion::sway(std::int64_t now_ns) noexcept {
  if (swaying_) return;
  sway_start_ns_ = now_ns;  // every sway term is 0 at its start: no jump
  swaying_ = true;
}

EulerRad BodyMotion::orientation(std::int64_t now_ns) const noexcept {
  if (!swaying_) return base_;
  const double t = seconds_since(sway_start_ns_, now_ns);
  return {
      .roll = base_.roll + kRoll.angle(t), .pitch = base_.pitch + kPitch.angle(t), .yaw = base_.yaw + kYaw.angle(t)};
}

ImuReading BodyMotion::sample(std::int64_t now_ns) const noexcept {
  const EulerRad euler = orientation(now_ns);
  double roll_rate = 0;
  double pitch_rate = 0;
  double yaw_rate = 0;
  if (swaying_) {
    const double t = seconds_since(sway_start_ns_, now_ns);
    roll_rate = kRoll.rate(t);
    pitch_rate = kPitch.rate(t);
    yaw_rate = kYaw.rate(t);
  }
  const double sr = std::sin(euler.roll);
  const double cr = std::cos(euler.roll);
  const double sp = std::sin(euler.pitch);
  const double cp = std::cos(euler.pitch);

  ImuReading reading;
  reading.has_orientation = true;
  reading.has_euler = true;
  reading.has_angular_velocity = true;
  reading.has_linear_acceleration = true;
  reading.euler_rad = euler;
  reading.orientation_xyzw = kinematics::quaternion_xyzw_from_rpy({euler.roll, euler.pitch, euler.yaw});
  // Body rates from Z-Y-X Euler rates.
  reading.angular_velocity_rad_s = {roll_rate - yaw_rate * sp, pitch_rate * cr + yaw_rate * sr * cp,
                                    -pitch_rate * sr + yaw_rate * cr * cp};
  // Specific force at the centre of rotation: the world's (0, 0, g) in body axes (Rᵀ·ẑ·g).
  reading.linear_acceleration_m_s2 = {-kGravity * sp, kGravity * sr * cp, kGravity * cr * cp};
  return reading;
}

}  // namespace robotd::imu::sim
