// The interface a robotd driver plugin implements, and the one symbol it exports.
//
// Threads (see docs/design.md):
//   configure, describe, connect, disconnect, recover, reset_zero — called by robotd's main or
//     maintenance thread, never while the RT loop is calling read/write on this driver.
//   read, write — called only by the device's RT thread at rate_hz. They must not allocate,
//     lock a mutex another thread holds, log, or block beyond a short bounded time.
//   call, diagnostics — called from non-RT threads while the RT loop runs; the driver makes
//     them safe against read/write (atomics, lock-free queues).
//   describe — also after every successful recover/reset_zero and call(), on that non-RT
//     thread while the RT loop runs: safe against the other methods. Narrower limits it then
//     reports narrow the running device's (never wider: docs/safety.md).
//   abort_maintenance — any thread, including the RT loop, at any time.
// Errors cross this boundary as values; no exception may escape a driver method.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "robotd/driver/types.hpp"
#include "robotd/result.hpp"

namespace robotd::driver {

/// Bump when anything in this header or types.hpp changes layout or meaning.
inline constexpr std::uint32_t kAbiVersion = 7;

struct JointLimits {
  double position_min_rad = -3.14;
  double position_max_rad = 3.14;
  double velocity_max_rad_s = 1.0;
  double acceleration_max_rad_s2 = 5.0;
  double effort_max_nm = 10.0;
  double kp_max = 200.0;
  double kd_max = 20.0;
};

struct JointDescription {
  std::string name;
  JointLimits limits;
  double default_kp = 0;  // used when a command carries no gains
  double default_kd = 0;  // also the damping gain for the DAMPING behaviour
  /// Where the joint reads right after reset_zero: 0 unless the driver maps motor angles to
  /// joint angles with an offset (the motor's zero seen through that map).
  double zero_position_rad = 0;
};

struct OpDescription {
  std::string name;
  std::string help;  // one line: what it does, its JSON arguments with units
  /// The op powers, enables, disables, brakes, reboots, zeroes, moves or changes the mode of joints
  /// robotd drives: robotd refuses it while a session holds any motor of the device, and grants no
  /// session while it runs (docs/writing-a-driver.md, "Ops that act on the joints").
  bool needs_free_motors = false;
};

/// For a driver's op table: {"name", "help", kNeedsFreeMotors}.
inline constexpr bool kNeedsFreeMotors = true;

struct DeviceDescription {
  std::string model;
  // The arm model the client-side motion layer plans with (robotd::kinematics::find_arm_model:
  // "parol6", "piper", "xarm6" …); "" when none.
  std::string kinematic_model;
  double native_rate_hz = 1000;
  std::vector<JointDescription> joints;
  bool supports_torque = false;       // kImpedance commands: TORQUE and MIXED sessions
  bool supports_damping = false;      // can hold joints with kp = 0, kd > 0
  bool supports_zero_torque = false;  // can let joints go (kp = kd = torque = 0)
  bool has_imu = false;
  bool has_end_pose = false;  // Feedback carries the end effector's pose
  std::vector<OpDescription> ops;
  // Non-empty: the device only reports (e.g. a leader arm a person moves by hand); robotd grants
  // no control of it and refuses a request with this text, which says why.
  std::string read_only_reason;
};

using Diagnostics = std::vector<std::pair<std::string, std::string>>;

class Driver {
 public:
  virtual ~Driver() = default;

  /// Validates and applies the device's "params" object. Errors name the offending key path
  /// relative to params (robotd prefixes the device's path).
  virtual Result<void> configure(const nlohmann::json& params) = 0;
  virtual DeviceDescription describe() const = 0;

  /// Opens the link. ErrorCode::kNotAvailable means "not reachable now, may be later": robotd
  /// then starts the device as a lost link and retries through recover().
  virtual Result<void> connect() = 0;
  /// Safe to call whether or not connect() succeeded.
  virtual void disconnect() noexcept = 0;
  /// Clears a latched fault and re-establishes the link if needed.
  virtual Result<void> recover() = 0;
  virtual Result<void> reset_zero(std::span<const int> joints) = 0;
  /// Makes a recover() or reset_zero() that runs on another thread give up and return an
  /// error as soon as it can: an e-stop or a shutdown must not wait for maintenance. robotd's
  /// RT loop calls it on every tick while an e-stop or a shutdown waits for maintenance, so it
  /// must only store to an atomic and return: no lock, no allocation, no I/O, no logging.
  /// recover() and reset_zero() clear the request when they start.
  virtual void abort_maintenance() noexcept = 0;

  /// Before a successful connect() or recover(), read and write return kDisconnected.
  /// write returns kDisconnected only when the frame could not be handed to the device; a
  /// device that reports a fault still takes the frame (its e-stop above all), and write then
  /// returns kFault. robotd counts an e-stop frame as having reached the device unless write
  /// returned kDisconnected, so a driver that decimates to a slower native rate sends an e-stop
  /// frame on the tick it first arrives.
  virtual IoResult read(Feedback& out, FaultInfo& fault) noexcept = 0;
  virtual IoResult write(const CommandFrame& command, FaultInfo& fault) noexcept = 0;

  /// Vendor operations (gripper, I/O, queries, fault injection). `args` is a JSON object.
  virtual Result<nlohmann::json> call(const std::string& op, const nlohmann::json& args) = 0;
  virtual Diagnostics diagnostics() const = 0;
};

/// What a plugin's entry symbol returns. robotd refuses a plugin whose abi_version, or whose
/// view of the RT structs' sizes, differs from its own.
struct PluginInfo {
  std::uint32_t abi_version;
  std::uint32_t command_frame_size;
  std::uint32_t feedback_size;
  const char* name;
  const char* version;
  Driver* (*create)() noexcept;
  void (*destroy)(Driver*) noexcept;
};

inline constexpr const char* kPluginEntrySymbol = "robotd_driver_plugin";
using PluginEntry = const PluginInfo* (*)();

}  // namespace robotd::driver

/// Exports a driver class as a robotd plugin: ROBOTD_DRIVER_PLUGIN(SimDriver, "sim", "1.0.0")
#define ROBOTD_DRIVER_PLUGIN(DriverClass, plugin_name, plugin_version)                                             \
  extern "C" __attribute__((visibility("default"))) const robotd::driver::PluginInfo* robotd_driver_plugin() {     \
    static const robotd::driver::PluginInfo info{robotd::driver::kAbiVersion,                                      \
                                                 static_cast<std::uint32_t>(sizeof(robotd::driver::CommandFrame)), \
                                                 static_cast<std::uint32_t>(sizeof(robotd::driver::Feedback)),     \
                                                 plugin_name,                                                      \
                                                 plugin_version,                                                   \
                                                 []() noexcept -> robotd::driver::Driver* {                        \
                                                   try {                                                           \
                                                     return new DriverClass();                                     \
                                                   } catch (...) {                                                 \
                                                     return nullptr;                                               \
                                                   }                                                               \
                                                 },                                                                \
                                                 [](robotd::driver::Driver* driver) noexcept { delete driver; }};  \
    return &info;                                                                                                  \
  }
