#include "motor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace robotd::hightorque::sim {
namespace {

using C = MotorConstants;
constexpr double kNoStop = 1e9;  // the rotor turns freely: no hard stops

bool limited(double limit) { return std::isfinite(limit) && limit > 0; }

/// `value` if the request carried it as a finite number, else `previous`.
double carried(bool has, double value, double previous) { return has && std::isfinite(value) ? value : previous; }

}  // namespace

SimMotor::SimMotor(int id, const MotorPhysics& physics, std::int64_t now_ns)
    : id_(id), physics_(physics), last_heard_ns_(now_ns) {}

void SimMotor::heard(std::int64_t now_ns) {
  ++requests_;
  last_heard_ns_ = now_ns;
}

void SimMotor::command(const MotorRequest& request) {
  timed_out_ = false;
  if (free_wheeling()) return;
  const MotorCommand& in = request.command;
  stored_.position_rad = carried(request.has_position, in.position_rad, stored_.position_rad);
  stored_.velocity_rad_s = carried(request.has_velocity, in.velocity_rad_s, stored_.velocity_rad_s);
  stored_.torque_nm = carried(request.has_torque, in.torque_nm, stored_.torque_nm);
  stored_.kp = carried(request.has_kp, in.kp, stored_.kp);
  stored_.kd = carried(request.has_kd, in.kd, stored_.kd);
  stored_.acceleration_rad_s2 = carried(true, in.acceleration_rad_s2, stored_.acceleration_rad_s2);
  stored_.voltage_q_v = carried(true, in.voltage_q_v, stored_.voltage_q_v);
  stored_.current_q_a = carried(true, in.current_q_a, stored_.current_q_a);
  stored_.mode = in.mode;
  if (in.mode != mode_) {
    enter_mode(in.mode, last_heard_ns_);
    reset_references();
  }
}

void SimMotor::enter_mode(Mode mode, std::int64_t commanded_ns) {
  mode_ = mode;
  mode_commanded_ns_ = commanded_ns;
}

void SimMotor::reset_references() {
  reference_position_rad_ = position_rad();
  reference_velocity_rad_s_ = velocity_rad_s();
  velocity_integral_nm_ = 0;
}

void SimMotor::set_zero() {
  zero_offset_rad_ = rotor_.position_rad;
  reset_references();
}

void SimMotor::soft_reboot() {
  ++reboots_;
  enter_mode(Mode::kStop, 0);
  stored_ = MotorCommand{};
  timeout_ms_ = 0;
  timed_out_ = false;
  push_period_us_ = 0;
  push_query_ = Query::kNone;
  reset_references();
}

bool SimMotor::set_status_push(Query query, Width width, std::uint32_t period_us, std::int64_t now_ns) {
  if (period_us != 0 && period_us < C::kMinPushPeriodUs) return false;
  push_period_us_ = period_us;
  push_query_ = query;
  push_width_ = width;
  next_push_ns_ = now_ns + static_cast<std::int64_t>(period_us) * 1000;
  return true;
}

bool SimMotor::push_due(std::int64_t now_ns) {
  if (push_period_us_ == 0 || push_query_ == Query::kNone || now_ns < next_push_ns_) return false;
  const std::int64_t period_ns = static_cast<std::int64_t>(push_period_us_) * 1000;
  next_push_ns_ += period_ns;
  if (next_push_ns_ <= now_ns) next_push_ns_ = now_ns + period_ns;  // at most one per pass: no bursts
  return true;
}

std::uint8_t SimMotor::fault() const {
  if (injected_fault_ != 0) return injected_fault_;
  if (over_temperature_) return kFaultOverTemperature;
  if (timed_out_) return kFaultCommunicationTimeout;
  return 0;
}

MotorState SimMotor::report(Query query) const {
  MotorState state;
  state.motor = id_;
  state.query = query;
  state.mode = static_cast<std::uint8_t>(mode_);
  state.fault = fault();
  state.position_rad = position_rad();
  state.velocity_rad_s = velocity_rad_s();
  state.torque_nm = torque_nm();
  if (query == Query::kStateTemperature) state.temperature_c = temperature_c_;
  if (query == Query::kCounter) state.counter = static_cast<std::uint16_t>(requests_ & 0xFFFFU);
  return state;
}

BoardMotorState SimMotor::board_report() const {
  return BoardMotorState{.motor = id_,
                         .mode = static_cast<std::uint8_t>(mode_),
                         .fault = fault(),
                         .position_rad = position_rad(),
                         .velocity_rad_s = velocity_rad_s(),
                         .torque_nm = torque_nm()};
}

void SimMotor::teleport(double position_rad) {
  rotor_ = ::robotd::sim::JointState{
      .position_rad = position_rad + zero_offset_rad_, .velocity_rad_s = 0, .motor_torque_nm = 0};
  reset_references();
}

void SimMotor::inject_fault(std::uint8_t code) {
  injected_fault_ = code;
  enter_mode(Mode::kStop, 0);
  reset_references();
}

void SimMotor::clear_fault() {
  injected_fault_ = 0;
  over_temperature_ = false;
}

void SimMotor::advance_profile(double target, double v_max, double accel, double dt_s) {
  const double distance = target - reference_position_rad_;
  double wanted = distance / dt_s;  // straight there if nothing limits it
  if (limited(accel)) {
    wanted = std::copysign(std::sqrt(2 * accel * std::abs(distance)), distance);  // brake in time
  }
  if (limited(v_max)) wanted = std::clamp(wanted, -v_max, v_max);
  if (limited(accel)) {
    const double change = accel * dt_s;
    reference_velocity_rad_s_ =
        std::clamp(wanted, reference_velocity_rad_s_ - change, reference_velocity_rad_s_ + change);
  } else {
    reference_velocity_rad_s_ = wanted;
  }
  reference_position_rad_ += reference_velocity_rad_s_ * dt_s;
  if ((target - reference_position_rad_) * distance <= 0) {  // arrived (or went past): settle there
    reference_position_rad_ = target;
    reference_velocity_rad_s_ = 0;
  }
}

::robotd::sim::MotorLaw SimMotor::law(double dt_s, double& effort_max_nm) {
  ::robotd::sim::MotorLaw law;
  const double offset = zero_offset_rad_;
  const auto velocity_loop = [&](double target_rad_s) {
    velocity_integral_nm_ += C::kVelocityKi * (target_rad_s - velocity_rad_s()) * dt_s;
    velocity_integral_nm_ = std::clamp(velocity_integral_nm_, -physics_.torque_max_nm, physics_.torque_max_nm);
    law.kd = C::kVelocityKp;
    law.velocity_rad_s = target_rad_s;
    law.torque_nm = velocity_integral_nm_;
  };
  const auto track_reference = [&] {
    law.kp = C::kPositionKp;
    law.kd = C::kPositionKd;
    law.position_rad = reference_position_rad_ + offset;
    law.velocity_rad_s = reference_velocity_rad_s_;
  };
  switch (mode_) {
    case Mode::kStop:
      break;
    case Mode::kBrake:
      law.kd = C::kBrakeDampingNmsPerRad;
      break;
    case Mode::kVoltage:
      law.torque_nm = C::kTorquePerVolt * stored_.voltage_q_v;
      break;
    case Mode::kCurrent:
      law.torque_nm = C::kTorquePerAmp * stored_.current_q_a;
      break;
    case Mode::kTorque:
      law.torque_nm = stored_.torque_nm;
      break;
    case Mode::kVelocity:
      velocity_loop(stored_.velocity_rad_s);
      break;
    case Mode::kVelocityAcceleration: {
      const double change = limited(stored_.acceleration_rad_s2) ? stored_.acceleration_rad_s2 * dt_s
                                                                 : std::numeric_limits<double>::infinity();
      reference_velocity_rad_s_ =
          std::clamp(stored_.velocity_rad_s, reference_velocity_rad_s_ - change, reference_velocity_rad_s_ + change);
      velocity_loop(reference_velocity_rad_s_);
      break;
    }
    case Mode::kPosition:
      law.kp = C::kPositionKp;
      law.kd = C::kPositionKd;
      law.position_rad = stored_.position_rad + offset;
      break;
    case Mode::kPositionVelocityTorque:
      advance_profile(stored_.position_rad, stored_.velocity_rad_s, 0, dt_s);
      track_reference();
      if (limited(stored_.torque_nm)) effort_max_nm = std::min(effort_max_nm, stored_.torque_nm);
      break;
    case Mode::kPositionVelocityAcceleration:
      advance_profile(stored_.position_rad, stored_.velocity_rad_s, stored_.acceleration_rad_s2, dt_s);
      track_reference();
      break;
    case Mode::kMit:
      law.kp = stored_.kp;
      law.kd = stored_.kd;
      law.position_rad = stored_.position_rad + offset;
      law.velocity_rad_s = stored_.velocity_rad_s;
      law.torque_nm = stored_.torque_nm;
      break;
  }
  return law;
}

void SimMotor::step(double dt_s, std::int64_t now_ns) {
  if (timeout_ms_ != 0 && !timed_out_ &&
      now_ns - last_heard_ns_ >= static_cast<std::int64_t>(timeout_ms_) * 1'000'000) {
    timed_out_ = true;
    event_ = true;
    if (!free_wheeling()) {
      enter_mode(Mode::kBrake, 0);
      reset_references();
    }
  }
  double effort_max_nm = physics_.torque_max_nm;
  const ::robotd::sim::MotorLaw motor_law = law(dt_s, effort_max_nm);
  const ::robotd::sim::JointPhysics rotor{.inertia_kg_m2 = physics_.inertia_kg_m2,
                                          .damping_nm_s_rad = physics_.friction_nm_s_rad,
                                          .position_min_rad = -kNoStop,
                                          .position_max_rad = kNoStop,
                                          .effort_max_nm = effort_max_nm};
  ::robotd::sim::step_joint(rotor, motor_law, external_torque_nm_, dt_s, rotor_);

  const double torque = rotor_.motor_torque_nm;
  temperature_c_ +=
      dt_s * (C::kHeatingCPerNm2S * torque * torque - (temperature_c_ - C::kAmbientC) / C::kCoolingTimeConstantS);
  if (!over_temperature_ && temperature_c_ > C::kOverTemperatureC) {
    over_temperature_ = true;
    event_ = true;
    enter_mode(Mode::kStop, 0);
    reset_references();
  } else if (over_temperature_ && temperature_c_ < C::kOverTemperatureClearC) {
    over_temperature_ = false;
    event_ = true;
  }
}

}  // namespace robotd::hightorque::sim
