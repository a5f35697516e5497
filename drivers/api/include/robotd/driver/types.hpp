// Data exchanged between robotd's real-time loop and a driver, once per tick. Fixed-size,
// trivially copyable, no heap: these cross the RT boundary.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace robotd::driver {

/// Upper bound on joints per device (the PI Plus humanoid has 23).
inline constexpr std::size_t kMaxJoints = 64;

enum class JointCommandKind : std::uint8_t {
  kNone,       // never commanded since connect: the driver leaves the joint in its own idle state
  kPosition,   // follow position_rad with velocity_rad_s feed-forward; kp/kd are servo gains if
               // the driver has gains, else ignored
  kImpedance,  // torque = kp·(position − q) + kd·(velocity − dq) + torque_nm (MIT law); this
               // also expresses pure torque (kp = kd = 0), damping (kp = 0) and zero torque
};

struct JointCommand {
  JointCommandKind kind = JointCommandKind::kNone;
  bool owned = false;  // a session holds this joint (drivers may enable motors on this edge)
  double position_rad = 0;
  double velocity_rad_s = 0;
  double kp = 0;  // N·m/rad
  double kd = 0;  // N·m·s/rad
  double torque_nm = 0;

  /// Whether the motor works for robotd: a position to hold or track, or an impedance command
  /// with any gain or torque (DAMPING included). False for kNone and for the all-zero impedance
  /// command (ZERO_TORQUE), which let the joint go. An op that would let go of a joint (disable,
  /// reboot) waits for this to be false: robotd holds such a joint after a session's KEEP or
  /// DAMPING fallback, with nobody owning it.
  bool holds() const noexcept {
    switch (kind) {
      case JointCommandKind::kNone:
        return false;
      case JointCommandKind::kPosition:
        return true;
      case JointCommandKind::kImpedance:
        return kp != 0 || kd != 0 || torque_nm != 0;
    }
    return true;
  }
};

/// What robotd asks of the device for one tick.
struct CommandFrame {
  std::uint64_t tick = 0;
  std::int64_t tick_deadline_ns = 0;        // CLOCK_MONOTONIC time this tick was due
  bool estop = false;                       // robotd's e-stop is latched: trigger the vendor e-stop
  std::int64_t newest_command_sent_ns = 0;  // client send time of the newest command applied
                                            // this tick (CLOCK_MONOTONIC), 0 if none
  std::size_t joint_count = 0;
  std::array<JointCommand, kMaxJoints> joints{};
};

struct JointFeedback {
  double position_rad = 0;
  double velocity_rad_s = 0;
  double effort_nm = 0;
};

struct ImuSample {
  std::array<double, 4> orientation_xyzw{0, 0, 0, 1};
  std::array<double, 3> angular_velocity_rad_s{};
  std::array<double, 3> linear_acceleration_m_s2{};
};

/// A pose in the device's base frame.
struct Pose {
  std::array<double, 3> position_m{};
  std::array<double, 4> orientation_xyzw{0, 0, 0, 1};
};

struct Feedback {
  std::size_t joint_count = 0;
  std::array<JointFeedback, kMaxJoints> joints{};
  bool has_imu = false;
  ImuSample imu{};
  bool has_end_pose = false;  // the end effector's pose (e.g. forward kinematics of the joints)
  Pose end_pose{};
  /// The device's own e-stop input (a button wired to the controller) is pressed: robotd
  /// engages its e-stop on the device, and refuses to reset it while the input stays pressed.
  bool estop_input = false;
};

/// A device fault as the driver reports it: a vendor code and a short human-readable text.
struct FaultInfo {
  std::int32_t code = 0;
  std::array<char, 160> text{};

  void set(std::int32_t fault_code, const char* message) noexcept {
    code = fault_code;
    std::strncpy(text.data(), message, text.size() - 1);
    text.back() = '\0';
  }
  void clear() noexcept {
    code = 0;
    text[0] = '\0';
  }
};

enum class IoResult : std::uint8_t {
  kOk,            // read: fresh feedback in `out`; write: command handed to the device
  kNoNewData,     // read only: nothing new since the last read (not an error by itself)
  kFault,         // the device reports a fault, described in FaultInfo (write: the command still went out)
  kDisconnected,  // the link is gone, described in FaultInfo
};

}  // namespace robotd::driver
