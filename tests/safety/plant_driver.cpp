#include "plant_driver.hpp"

#include <algorithm>
#include <limits>

namespace robotd::safety {
namespace {

constexpr double kInertia = 0.05;          // kg·m²
constexpr double kGravityTorque = 1.0;     // N·m, pulling every joint toward negative angles
constexpr double kFriction = 0.05;         // N·m·s/rad
constexpr double kSpeedLimit = 5.0;        // rad/s: the mechanism's own end stop on speed
constexpr double kServoFollowing = 0.3;    // a position servo closes this share of its error a tick

}  // namespace

PlantDriver::PlantDriver(const DeviceSpec& spec) : joint_count_(spec.joints) {}

Result<void> PlantDriver::recover() {
  if (!link_up) return make_error(ErrorCode::kNotAvailable, "link down");
  fault_code = 0;
  return {};
}

Result<void> PlantDriver::reset_zero(std::span<const int> joints) {
  for (const int joint : joints) {
    joints_[static_cast<std::size_t>(joint)] = Joint{};
  }
  return {};
}

void PlantDriver::teleport(std::size_t joint, double position) noexcept {
  joints_[joint].position = position;
  joints_[joint].velocity = 0;
}

void PlantDriver::begin_tick() noexcept {
  wrote = false;
  read_called = false;
  read_ok = false;
}

driver::IoResult PlantDriver::read(driver::Feedback& out, driver::FaultInfo& fault) noexcept {
  read_called = true;
  read_result = read_unrecorded(out, fault);
  return read_result;
}

driver::IoResult PlantDriver::read_unrecorded(driver::Feedback& out, driver::FaultInfo& fault) noexcept {
  if (!link_up) {
    fault.set(0, "link down");
    return driver::IoResult::kDisconnected;
  }
  if (fault_code != 0) {
    fault.set(fault_code, "injected fault");
    return driver::IoResult::kFault;
  }
  if (silent) return driver::IoResult::kNoNewData;
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  out = driver::Feedback{};
  out.joint_count = joint_count_;
  for (std::size_t j = 0; j < joint_count_; ++j) {
    const auto& bad = non_finite[j];
    out.joints[j].position_rad = bad[0] ? kNaN : joints_[j].position;
    out.joints[j].velocity_rad_s = bad[1] ? std::numeric_limits<double>::infinity() : joints_[j].velocity;
    out.joints[j].effort_nm = bad[2] ? kNaN : joints_[j].effort;
  }
  out.estop_input = estop_input;
  read_ok = true;
  read_feedback = out;
  return driver::IoResult::kOk;
}

driver::IoResult PlantDriver::write(const driver::CommandFrame& command, driver::FaultInfo& fault) noexcept {
  wrote = true;
  frame = command;
  if (!link_up) {
    fault.set(0, "link down");
    return driver::IoResult::kDisconnected;
  }
  last_written_ = command;
  have_written_ = true;
  return driver::IoResult::kOk;
}

void PlantDriver::advance(double dt_s) noexcept {
  for (std::size_t j = 0; j < joint_count_; ++j) {
    Joint& joint = joints_[j];
    const driver::JointCommand* command = have_written_ && link_up ? &last_written_.joints[j] : nullptr;
    const auto kind = command != nullptr ? command->kind : driver::JointCommandKind::kNone;
    switch (kind) {
      case driver::JointCommandKind::kNone:
        joint.velocity = 0;  // an undriven joint rests on its brake
        joint.effort = 0;
        break;
      case driver::JointCommandKind::kPosition: {
        const double next = joint.position + kServoFollowing * (command->position_rad - joint.position);
        joint.velocity = (next - joint.position) / dt_s;
        joint.position = next;
        joint.effort = kGravityTorque;
        break;
      }
      case driver::JointCommandKind::kImpedance: {
        const double torque = command->kp * (command->position_rad - joint.position) +
                              command->kd * (command->velocity_rad_s - joint.velocity) + command->torque_nm;
        joint.effort = torque;
        const double acceleration = (torque - kGravityTorque - kFriction * joint.velocity) / kInertia;
        joint.velocity = std::clamp(joint.velocity + acceleration * dt_s, -kSpeedLimit, kSpeedLimit);
        joint.position += joint.velocity * dt_s;
        break;
      }
    }
  }
}

}  // namespace robotd::safety
