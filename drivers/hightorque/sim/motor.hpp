// One simulated HighTorque motor: what it does with the requests a bus hands it, its built-in
// controllers, faults and command watchdog, and a rigid rotor with viscous friction. Pure: no
// I/O. README.md in this folder lists the constants and why.
//
// Positions here are the motor's own frame (rad, after its stored zero); the rotor itself turns
// in the shaft frame, zero_offset_rad() apart.
#pragma once

#include <cstdint>
#include <utility>

#include "codec/hightorque_codec.hpp"
#include "joint_dynamics.hpp"
#include "sim_options.hpp"

namespace robotd::hightorque::sim {

/// The motor's built-in controllers and electrical stand-ins (README.md, "Physics").
struct MotorConstants {
  static constexpr double kBrakeDampingNmsPerRad = 2.0;  // BRAKE: phases shorted, τ = −2·v
  static constexpr double kPositionKp = 50.0;            // POSITION and the profiled modes, N·m/rad
  static constexpr double kPositionKd = 2.0;             // N·m·s/rad: critically damped at 0.02 kg·m²
  static constexpr double kVelocityKp = 2.0;             // VELOCITY: N·m per rad/s of error
  static constexpr double kVelocityKi = 20.0;            // N·m per rad of accumulated error
  static constexpr double kTorquePerAmp = 0.1;           // CURRENT: τ = 0.1 N·m/A · i_q
  static constexpr double kTorquePerVolt = 0.1;          // VOLTAGE: τ = 0.1 N·m/V · v_q (no back-EMF)
  static constexpr double kAmbientC = 30.0;
  static constexpr double kHeatingCPerNm2S = 0.002;       // dT/dt += 0.002 °C/s per (N·m)²
  static constexpr double kCoolingTimeConstantS = 300.0;  // dT/dt −= (T − 30 °C) / 300 s
  static constexpr double kOverTemperatureC = 90.0;       // fault 0x14 above this …
  static constexpr double kOverTemperatureClearC = 80.0;  // … until it cooled below this
  static constexpr std::uint32_t kMinPushPeriodUs = 100;
};

inline constexpr std::uint8_t kFaultOverTemperature = 0x14;
inline constexpr std::uint8_t kFaultCommunicationTimeout = 0x15;

class SimMotor {
 public:
  SimMotor(int id, const MotorPhysics& physics, std::int64_t now_ns);

  int id() const { return id_; }
  void set_id(int id) { id_ = id; }

  // ---- What the bus hands it (a muted motor is handed nothing) ----
  /// Every request addressed to it: counted, and the command watchdog restarts.
  void heard(std::int64_t now_ns);
  /// A mode command. Fields the request did not carry keep their previous value. Clears the
  /// watchdog's fault 0x15; ignored while a fault that free-wheels the motor is raised.
  void command(const MotorRequest& request);
  /// The current position becomes 0.
  void set_zero();
  /// Back to STOP; keeps its zero; the watchdog and the status push are disarmed.
  void soft_reboot();
  /// 0 disarms; otherwise BRAKE and fault 0x15 when nothing is heard for `timeout_ms`.
  void set_command_timeout(std::uint16_t timeout_ms) { timeout_ms_ = timeout_ms; }
  /// Periodic replies of `query` at `width`; period 0 stops them. False (refused, nothing
  /// changed) for a period under 100 µs.
  bool set_status_push(Query query, Width width, std::uint32_t period_us, std::int64_t now_ns);
  /// Whether a pushed reply is due at `now_ns` (then the next one is scheduled).
  bool push_due(std::int64_t now_ns);
  Query push_query() const { return push_query_; }
  Width push_width() const { return push_width_; }
  std::uint32_t push_period_us() const { return push_period_us_; }

  /// Its reply to `query`, carrying its state now.
  MotorState report(Query query) const;
  BoardMotorState board_report() const;

  /// Advances the rotor by `dt_s` and runs the watchdog and the temperature.
  void step(double dt_s, std::int64_t now_ns);

  // ---- The control channel ----
  void teleport(double position_rad);
  /// Free-wheels (STOP) and reports `code` until clear_fault().
  void inject_fault(std::uint8_t code);
  /// Clears an injected fault and over-temperature (raised again if still too hot).
  void clear_fault();
  void set_temperature(double celsius) { temperature_c_ = celsius; }
  void set_external_torque(double torque_nm) { external_torque_nm_ = torque_nm; }
  void set_muted(bool muted) { muted_ = muted; }

  // ---- What it reports ----
  double position_rad() const { return rotor_.position_rad - zero_offset_rad_; }
  double velocity_rad_s() const { return rotor_.velocity_rad_s; }
  double torque_nm() const { return rotor_.motor_torque_nm; }
  /// The mode it runs in: STOP while a fault free-wheels it, BRAKE after the watchdog fired.
  Mode mode() const { return mode_; }
  /// CLOCK_MONOTONIC of the request that put it in that mode; 0 when it went there by itself.
  std::int64_t mode_commanded_ns() const { return mode_commanded_ns_; }
  std::uint8_t fault() const;
  const MotorCommand& stored() const { return stored_; }
  std::uint16_t timeout_ms() const { return timeout_ms_; }
  double temperature_c() const { return temperature_c_; }
  std::uint64_t requests() const { return requests_; }
  std::uint64_t reboots() const { return reboots_; }
  double zero_offset_rad() const { return zero_offset_rad_; }
  double external_torque_nm() const { return external_torque_nm_; }
  bool muted() const { return muted_; }
  /// Set when the motor stopped on its own (watchdog, fault); cleared by taking it.
  bool take_event() { return std::exchange(event_, false); }

 private:
  /// Moves the profile's reference toward `target` at ≤ v_max and ≤ accel (≤ 0 or not finite:
  /// no limit) over `dt_s`.
  void advance_profile(double target, double v_max, double accel, double dt_s);
  ::robotd::sim::MotorLaw law(double dt_s, double& effort_max_nm);
  bool free_wheeling() const { return injected_fault_ != 0 || over_temperature_; }
  void reset_references();
  void enter_mode(Mode mode, std::int64_t commanded_ns);

  int id_;
  MotorPhysics physics_;
  ::robotd::sim::JointState rotor_;
  double zero_offset_rad_ = 0;
  Mode mode_ = Mode::kStop;
  std::int64_t mode_commanded_ns_ = 0;
  MotorCommand stored_;                // the last value of every field, in the motor frame
  double reference_position_rad_ = 0;  // profiled modes
  double reference_velocity_rad_s_ = 0;
  double velocity_integral_nm_ = 0;  // VELOCITY's I term
  std::uint16_t timeout_ms_ = 0;
  std::int64_t last_heard_ns_;
  bool timed_out_ = false;
  std::uint8_t injected_fault_ = 0;
  bool over_temperature_ = false;
  double temperature_c_ = MotorConstants::kAmbientC;
  double external_torque_nm_ = 0;
  bool muted_ = false;
  std::uint64_t requests_ = 0;
  std::uint64_t reboots_ = 0;  // soft reboots, for tests
  Query push_query_ = Query::kNone;
  Width push_width_ = Width::kInt16;
  std::uint32_t push_period_us_ = 0;
  std::int64_t next_push_ns_ = 0;
  bool event_ = false;
};

}  // namespace robotd::hightorque::sim
