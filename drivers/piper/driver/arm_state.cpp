#include "driver/arm_state.hpp"

#include <algorithm>
#include <cstdio>
#include <type_traits>
#include <variant>

namespace robotd::piper {
namespace {

constexpr std::uint8_t kAllPairs = 0b111;
constexpr std::uint8_t kDriverFaultBits = 0xBF;   // all but bit 6, "enabled"
constexpr std::uint8_t kGripperFaultBits = 0x3F;  // bits 0–5

bool is_fault_status(std::uint8_t arm_status, bool own_estop) {
  switch (arm_status) {
    case 0x01:  // emergency stop
      return !own_estop;
    case 0x05:  // joint communication error
    case 0x06:  // joint brake not released
    case 0x07:  // collision
    case 0x08:  // over-speed during drag-teach
    case 0x09:  // joint status abnormal
    case 0x0A:  // other
    case 0x0E:  // main-controller over-temperature
    case 0x0F:  // brake-resistor over-temperature
      return true;
    default:  // normal, teach states, and a refused target (no IK, singularity, beyond a limit)
      return false;
  }
}

/// "over-current, driver error" from a status byte, into `out` (no allocation).
using FaultText = std::array<char, 144>;  // shorter than FaultInfo::text, so it always fits

void append_bits(std::array<char, 100>& out, std::size_t& used, std::uint8_t bits, const char* (*name)(int)) {
  for (int bit = 0; bit < 8; ++bit) {
    if ((bits & (1U << static_cast<unsigned>(bit))) == 0) continue;
    const int written = std::snprintf(out.data() + used, out.size() - used, "%s%s", used == 0 ? "" : ", ", name(bit));
    if (written > 0) used = std::min(out.size() - 1, used + static_cast<std::size_t>(written));
  }
}

driver::FaultInfo bits_fault(std::int32_t code, const char* subject, std::uint8_t bits, const char* (*name)(int)) {
  std::array<char, 100> names{};
  std::size_t used = 0;
  append_bits(names, used, bits, name);
  FaultText text{};
  std::snprintf(text.data(), text.size(), "%s: %s (status 0x%02X)", subject, names.data(), bits);
  driver::FaultInfo fault;
  fault.set(code, text.data());
  return fault;
}

}  // namespace

bool ArmState::all_enabled() const {
  return std::all_of(joints.begin(), joints.end(), [](const JointReport& joint) { return joint.enabled(); });
}

bool apply_frame(ArmState& state, const Frame& frame, std::int64_t now_ns) noexcept {
  if (!plausible(frame)) {
    ++state.implausible_frames;
    return false;
  }
  bool joints_complete = false;
  std::visit(
      [&](const auto& value) {
        using T = std::decay_t<decltype(value)>;
        if constexpr (std::is_same_v<T, ArmStatus>) {
          state.status = value;
          state.status_seen = true;
          state.last_status_ns = now_ns;
        } else if constexpr (std::is_same_v<T, JointFeedbackPair>) {
          const std::size_t first = 2 * static_cast<std::size_t>(value.pair);
          state.joints[first].position_rad = value.first_rad;
          state.joints[first + 1].position_rad = value.second_rad;
          state.joint_pairs_seen |= static_cast<std::uint8_t>(1U << static_cast<unsigned>(value.pair));
          state.last_joints_ns = now_ns;
          // A set is complete when the last of the three frames arrives (the arm sends them in
          // order); a lost frame leaves the older value for that pair, at most 5 ms old.
          if (value.pair == 2 && (state.joint_pairs_seen == kAllPairs || state.joints_seen)) {
            state.joints_seen = true;
            state.joint_pairs_seen = 0;
            joints_complete = true;
          }
        } else if constexpr (std::is_same_v<T, EndPoseFeedbackPart>) {
          CartesianPose& pose = state.end_pose;
          if (value.part == 0) {
            pose.x_m = value.first;
            pose.y_m = value.second;
          } else if (value.part == 1) {
            pose.z_m = value.first;
            pose.rx_rad = value.second;
          } else {
            pose.ry_rad = value.first;
            pose.rz_rad = value.second;
          }
        } else if constexpr (std::is_same_v<T, GripperFeedback>) {
          state.gripper = value;
          state.gripper_seen = true;
        } else if constexpr (std::is_same_v<T, HighSpeedInfo>) {
          JointReport& joint = state.joints[static_cast<std::size_t>(value.joint - 1)];
          joint.speed_rad_s = value.speed_rad_s;
          joint.current_a = value.current_a;
          joint.motor_position_rad = value.position_rad;
        } else if constexpr (std::is_same_v<T, ModeControl>) {
          state.master_mode = value;
          state.master_seen = true;
        } else if constexpr (std::is_same_v<T, JointTargetPair>) {
          const std::size_t first = 2 * static_cast<std::size_t>(value.pair);
          state.master_joints_rad[first] = value.first_rad;
          state.master_joints_rad[first + 1] = value.second_rad;
          state.master_seen = true;
          state.master_pairs_seen |= static_cast<std::uint8_t>(1U << static_cast<unsigned>(value.pair));
          state.last_master_joints_ns = now_ns;
          // Complete as the arm's own joint feedback is: when the last of the three arrives.
          if (value.pair == 2 && (state.master_pairs_seen == kAllPairs || state.master_joints_seen)) {
            state.master_joints_seen = true;
            state.master_pairs_seen = 0;
            ++state.master_joint_sets;
          }
        } else if constexpr (std::is_same_v<T, GripperControl>) {
          state.master_gripper = value;
          state.master_seen = true;
          state.master_gripper_seen = true;
        } else if constexpr (std::is_same_v<T, LowSpeedInfo>) {
          JointReport& joint = state.joints[static_cast<std::size_t>(value.joint - 1)];
          joint.voltage_v = value.voltage_v;
          joint.driver_temperature_c = value.driver_temperature_c;
          joint.motor_temperature_c = value.motor_temperature_c;
          joint.driver_status = value.status_bits;
          joint.bus_current_a = value.bus_current_a;
          joint.low_speed_seen = true;
        }
      },
      frame);
  ++state.frames;
  return joints_complete;
}

driver::FaultInfo arm_fault(const ArmState& state, bool own_estop, bool with_gripper) noexcept {
  driver::FaultInfo fault;
  if (state.status_seen && is_fault_status(state.status.arm_status, own_estop)) {
    FaultText text{};
    std::snprintf(text.data(), text.size(), "arm reports %s (0x2A1 status 0x%02X)",
                  arm_status_text(state.status.arm_status), state.status.arm_status);
    fault.set(state.status.arm_status, text.data());
    return fault;
  }
  for (int j = 0; j < kArmJoints; ++j) {
    if ((state.status.comm_error_bits & (1U << static_cast<unsigned>(j))) != 0) {
      FaultText text{};
      std::snprintf(text.data(), text.size(),
                    "joint %d: communication error between the arm's controller and its driver", j + 1);
      fault.set(kJointCommFaultBase + j + 1, text.data());
      return fault;
    }
  }
  for (int j = 0; j < kArmJoints; ++j) {
    const std::uint8_t bits = state.joints[static_cast<std::size_t>(j)].driver_status & kDriverFaultBits;
    if (bits == 0) continue;
    std::array<char, 24> subject{};
    std::snprintf(subject.data(), subject.size(), "joint %d driver", j + 1);
    return bits_fault(kDriverFaultBase + j + 1, subject.data(),
                      state.joints[static_cast<std::size_t>(j)].driver_status & kDriverFaultBits,
                      driver_status_bit_text);
  }
  if (with_gripper && state.gripper_seen && (state.gripper.status_bits & kGripperFaultBits) != 0) {
    return bits_fault(kGripperFault, "gripper", state.gripper.status_bits & kGripperFaultBits, gripper_status_bit_text);
  }
  return fault;
}

}  // namespace robotd::piper
