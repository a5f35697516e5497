#include "plant_driver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace robotd::safety {
namespace {

constexpr double kInertia = 0.05;        // kg·m²
constexpr double kGravityTorque = 1.0;   // N·m, pulling every joint toward negative angles
constexpr double kFriction = 0.05;       // N·m·s/rad
constexpr double kSpeedLimit = 5.0;      // rad/s: the mechanism's own end stop on speed
constexpr double kServoFollowing = 0.3;  // a position servo closes this share of its error a tick

}  // namespace

PlantDriver::PlantDriver(const DeviceSpec& spec) : spec_(spec), joint_count_(spec.joints) {}

driver::DeviceDescription PlantDriver::describe() const {
  const control::DeviceModel model = spec_.model();
  driver::DeviceDescription description;
  description.model = "plant";
  description.supports_torque = spec_.torque;
  description.supports_damping = spec_.damping;
  description.supports_zero_torque = spec_.zero_torque;
  const std::lock_guard lock(mutex_);
  for (std::size_t j = 0; j < joint_count_; ++j) {
    driver::JointLimits limits = model.limits[j];
    if (described_range_[j] > 0) {
      limits.position_min_rad = std::fmax(limits.position_min_rad, -described_range_[j]);
      limits.position_max_rad = std::fmin(limits.position_max_rad, described_range_[j]);
    }
    description.joints.push_back(
        driver::JointDescription{model.joint_names[j], limits, model.default_kp[j], model.default_kd[j], 0.0});
  }
  return description;
}

void PlantDriver::narrow(std::size_t joint, double range) {
  const std::lock_guard lock(mutex_);
  described_range_[joint] = described_range_[joint] > 0 ? std::fmin(described_range_[joint], range) : range;
}

void PlantDriver::next_maintenance(int ticks, bool fail) noexcept {
  const std::lock_guard lock(mutex_);
  maintenance_ticks_ = ticks;
  maintenance_fails_ = fail;
}

bool PlantDriver::wait_for_maintenance() {
  abort_requested.store(false);  // recover() and reset_zero() clear the request when they start
  std::unique_lock lock(mutex_);
  until_ = ticks_ + static_cast<std::uint64_t>(std::max(maintenance_ticks_, 0));
  in_work_.store(true);
  ticked_.wait(lock, [&] { return ticks_ >= until_ || abort_requested.load(); });
  in_work_.store(false);
  return !abort_requested.load() && !maintenance_fails_;
}

bool PlantDriver::maintenance_released() {
  const std::lock_guard lock(mutex_);
  return in_work_.load() && (ticks_ >= until_ || abort_requested.load());
}

Result<void> PlantDriver::recover() {
  if (!wait_for_maintenance()) return make_error(ErrorCode::kRefused, "aborted or failed");
  if (!link_up) return make_error(ErrorCode::kNotAvailable, "link down");
  fault_code = 0;
  return {};
}

Result<void> PlantDriver::reset_zero(std::span<const int> joints) {
  if (!wait_for_maintenance()) return make_error(ErrorCode::kRefused, "aborted or failed");
  const std::lock_guard lock(mutex_);  // the test thread keeps advancing the plant meanwhile
  for (const int joint : joints) {
    if (joint >= 0 && static_cast<std::size_t>(joint) < joint_count_)
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
  const std::lock_guard lock(mutex_);
  ++ticks_;
  ticked_.notify_all();
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
