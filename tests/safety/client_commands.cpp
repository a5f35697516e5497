#include "client_commands.hpp"

#include <cmath>
#include <limits>
#include <random>

namespace robotd::safety {
namespace {

// A client's trajectory for joint j: a slow sine inside the limits, its own per label.
double trajectory(int label, std::size_t j, const DeviceSpec& device, double t_s) {
  const double centre = 0.5 * (device.position_min + device.position_max);
  const double amplitude = 0.45 * (device.position_max - device.position_min);
  const double frequency_hz = 0.05 + 0.1 * static_cast<double>((label * 7 + static_cast<int>(j) * 3) % 5);
  const double phase = static_cast<double>(label) + 1.3 * static_cast<double>(j);
  return centre + amplitude * std::sin(2 * M_PI * frequency_hz * t_s + phase);
}

}  // namespace

ControlCommand client_command(const ClientSession& session, std::uint32_t seed, const DeviceSpec& device,
                              std::int64_t now_ns) {
  std::mt19937 engine(seed);
  const auto real = [&engine](double low, double high) {
    return std::uniform_real_distribution<double>(low, high)(engine);
  };
  const auto chance = [&real](double p) { return real(0, 1) < p; };
  const double t_s = static_cast<double>(now_ns) * 1e-9;

  ControlCommand command;
  command.uuid = session.uuid;
  command.sent_steady_ns = chance(0.7) ? now_ns - 200'000 : 0;
  for (std::size_t j = 0; j < device.joints; ++j) {
    if ((session.motors >> j & 1U) != 0 && (chance(0.85) || command.motor_ids.empty())) {
      command.motor_ids.push_back(static_cast<std::int32_t>(j));
    }
  }
  const bool torque = session.mode != ControlMode::kPosition;
  const bool gains = session.mode == ControlMode::kMixed || chance(0.3);
  const bool velocities = chance(0.3);
  const bool far = chance(0.05);
  for (const auto id : command.motor_ids) {
    const auto j = static_cast<std::size_t>(id);
    const double position =
        far ? real(device.position_min, device.position_max) : trajectory(session.label, j, device, t_s);
    command.positions.push_back(static_cast<float>(position));
    if (velocities) command.velocities.push_back(static_cast<float>(real(-device.velocity_max, device.velocity_max)));
    if (gains) {
      command.kp.push_back(static_cast<float>(real(0, device.kp_max)));
      command.kd.push_back(static_cast<float>(real(0, device.kd_max)));
    }
    if (torque) command.torques.push_back(static_cast<float>(real(-device.effort_max, device.effort_max)));
  }

  // One command in five is wrong in some way.
  const double shape = real(0, 1);
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  constexpr float kInf = std::numeric_limits<float>::infinity();
  if (shape < 0.05 && !command.positions.empty()) {
    command.positions[0] = static_cast<float>(device.position_max + real(0.1, 5.0));  // beyond the limit
  } else if (shape < 0.07 && !command.torques.empty()) {
    command.torques[0] = static_cast<float>(device.effort_max * real(1.1, 10.0));
  } else if (shape < 0.09 && !command.kp.empty()) {
    command.kp[0] = static_cast<float>(device.kp_max * real(1.1, 3.0));
  } else if (shape < 0.11 && !command.positions.empty()) {
    command.positions[0] = chance(0.5) ? kNaN : -kInf;
  } else if (shape < 0.12 && !command.torques.empty()) {
    command.torques[0] = kNaN;
  } else if (shape < 0.14) {
    command.positions.push_back(0.0F);  // one value too many
  } else if (shape < 0.16) {
    command.motor_ids.push_back(static_cast<std::int32_t>(device.joints + 3));  // no such motor
    command.positions.push_back(0.0F);
  } else if (shape < 0.18) {
    for (std::size_t j = 0; j < device.joints; ++j) {  // a motor the session does not hold, if any
      if ((session.motors >> j & 1U) == 0) {
        command.motor_ids.push_back(static_cast<std::int32_t>(j));
        command.positions.push_back(0.0F);
        break;
      }
    }
  } else if (shape < 0.19) {
    command.device = "another";
  } else if (shape < 0.20) {
    command = ControlCommand{};  // a keepalive
    command.uuid = session.uuid;
  }
  return command;
}

std::uint64_t answered_tick(const Event& command, std::uint64_t newest) {
  if (command.kind != Event::Kind::kCommand || !command.answers) return 0;
  const auto tick = static_cast<std::int64_t>(newest) + command.answer_offset;
  return tick > 0 ? static_cast<std::uint64_t>(tick) : 0;
}

}  // namespace robotd::safety
