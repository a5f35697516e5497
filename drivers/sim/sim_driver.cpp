#include "sim_driver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <span>
#include <string>
#include <time.h>
#include <utility>

#include "robotd/driver/monotonic_clock.hpp"

namespace robotd::sim {
namespace {

using driver::monotonic_now_ns;

using driver::CommandFrame;
using driver::FaultInfo;
using driver::Feedback;
using driver::IoResult;
using driver::JointCommand;
using driver::JointCommandKind;

bool is_finite(const JointCommand& command) noexcept {
  return std::isfinite(command.position_rad) && std::isfinite(command.velocity_rad_s) && std::isfinite(command.kp) &&
         std::isfinite(command.kd) && std::isfinite(command.torque_nm);
}

/// The motor law a joint command asks for, in the physical frame (targets shifted by the zero offset).
MotorLaw commanded_motor_law(const SimJointParams& joint, const JointCommand& command,
                             double zero_offset_rad) noexcept {
  if (!is_finite(command)) return MotorLaw{};
  const driver::JointLimits& limits = joint.limits;
  switch (command.kind) {
    case JointCommandKind::kNone:
      return MotorLaw{};
    case JointCommandKind::kPosition:
      return MotorLaw{.kp = command.kp > 0 ? std::min(command.kp, limits.kp_max) : joint.default_kp,
                      .kd = command.kd > 0 ? std::min(command.kd, limits.kd_max) : joint.default_kd,
                      .position_rad = command.position_rad + zero_offset_rad,
                      .velocity_rad_s = command.velocity_rad_s};
    case JointCommandKind::kImpedance:
      return MotorLaw{.kp = std::clamp(command.kp, 0.0, limits.kp_max),
                      .kd = std::clamp(command.kd, 0.0, limits.kd_max),
                      .position_rad = command.position_rad + zero_offset_rad,
                      .velocity_rad_s = command.velocity_rad_s,
                      .torque_nm = command.torque_nm};
  }
  return MotorLaw{};
}

}  // namespace

Result<void> SimDriver::configure(const nlohmann::json& params) {
  if (connected_.load()) return make_error(ErrorCode::kRefused, "configure: disconnect first");
  try {
    Result<SimParams> parsed = parse_sim_params(params);
    if (!parsed) return parsed.error();
    params_ = std::move(parsed).value();
  } catch (const std::exception& e) {
    return make_error(ErrorCode::kInvalidArgument, std::string("configure: ") + e.what());
  }
  for (std::size_t i = 0; i < params_.joints.size(); ++i) {
    const SimJointParams& joint = params_.joints[i];
    joints_[i] = JointState{.position_rad = joint.initial_position_rad};
    rt_snapshot_.joints[i] = SimJointSnapshot{.position_rad = joint.initial_position_rad,
                                              .physical_position_rad = joint.initial_position_rad};
    external_torque_nm_[i].store(joint.external_torque_nm);
    zero_offset_rad_[i].store(0);
  }
  rt_snapshot_.joint_count = params_.joints.size();
  rt_snapshot_.estop = false;
  snapshot_.store(rt_snapshot_);
  change_injected_faults([](InjectedFaults& faults) { faults = InjectedFaults{}; });
  // A still base: level, not turning, feeling gravity (until set_imu says otherwise).
  rt_imu_ = driver::ImuSample{};
  rt_imu_.linear_acceleration_m_s2 = {0, 0, kStandardGravity_m_s2};
  {
    const std::lock_guard lock(imu_writer_mutex_);
    imu_.store(rt_imu_);
  }
  configured_ = true;
  return {};
}

Result<void> SimDriver::connect() {
  if (!configured_) return make_error(ErrorCode::kRefused, "connect: the sim driver is not configured");
  motors_enabled_.store(true);
  link_generation_.fetch_add(1);
  connected_.store(true);
  return {};
}

void SimDriver::disconnect() noexcept { connected_.store(false); }

Result<void> SimDriver::recover() {
  abort_.clear();
  if (!configured_) return make_error(ErrorCode::kRefused, "recover: the sim driver is not configured");
  recover_calls_.fetch_add(1);
  if (!wait_as_asked()) return driver::aborted_error("recover (waiting as slow_maintenance asked)");
  const std::int64_t down_for_ns = link_down_until_ns_.load() - monotonic_now_ns();
  if (down_for_ns > 0) {
    return make_error(ErrorCode::kNotAvailable, "simulated link still down for another " +
                                                    std::to_string(down_for_ns / 1'000'000) + " ms (injected)");
  }
  change_injected_faults([](InjectedFaults& faults) { faults = InjectedFaults{}; });
  link_generation_.fetch_add(1);
  connected_.store(true);
  return {};
}

Result<void> SimDriver::reset_zero(std::span<const int> joints) {
  abort_.clear();
  const std::size_t joint_count = params_.joints.size();
  for (const int joint : joints) {
    if (joint < 0 || static_cast<std::size_t>(joint) >= joint_count) {
      return make_error(ErrorCode::kInvalidArgument, "reset_zero: joint index " + std::to_string(joint) +
                                                         " is out of range 0.." + std::to_string(joint_count) +
                                                         " (exclusive)");
    }
  }
  if (!wait_as_asked()) return driver::aborted_error("reset_zero (waiting as slow_maintenance asked)");
  const SimSnapshot snapshot = snapshot_.load_non_rt();
  const auto zero_here = [&](std::size_t joint) {
    zero_offset_rad_[joint].store(snapshot.joints[joint].physical_position_rad);
  };
  if (joints.empty()) {
    for (std::size_t joint = 0; joint < joint_count; ++joint) zero_here(joint);
  }
  for (const int joint : joints) zero_here(static_cast<std::size_t>(joint));
  return {};
}

bool SimDriver::wait_as_asked() {
  const std::int64_t wait_ns = maintenance_wait_ns_.exchange(0);
  return wait_ns <= 0 || abort_.sleep_for(std::chrono::nanoseconds(wait_ns));
}

IoResult SimDriver::read(Feedback& out, FaultInfo& fault) noexcept { return read_at(monotonic_now_ns(), out, fault); }

IoResult SimDriver::read_at(std::int64_t now_ns, Feedback& out, FaultInfo& fault) noexcept {
  if (const std::int64_t stall_ns = stall_ns_.exchange(0, std::memory_order_acq_rel); stall_ns > 0) {
    // Injected on purpose: a driver stuck on its bus, which the RT contract forbids, so that
    // robotd's overrun counting and systemd watchdog can be seen to catch it.
    const timespec pause{static_cast<time_t>(stall_ns / 1'000'000'000), static_cast<long>(stall_ns % 1'000'000'000)};
    nanosleep(&pause, nullptr);
  }
  if (!refresh_link_state(fault)) return IoResult::kDisconnected;
  advance_physics(now_ns);
  if (const IoResult status = injected_link_status(fault); status != IoResult::kOk) return status;
  if (rt_injected_faults_.feedback_stopped) return IoResult::kNoNewData;
  if (params_.imu) imu_.try_load(rt_imu_);  // racing a set_imu: the previous sample, one tick longer
  fill_feedback(out);
  return IoResult::kOk;
}

IoResult SimDriver::write(const CommandFrame& command, FaultInfo& fault) noexcept {
  if (!refresh_link_state(fault)) return IoResult::kDisconnected;
  // A controller in fault still takes frames over its link (the e-stop above all); it reports
  // the fault with them. Only a lost link takes nothing.
  const IoResult status = injected_link_status(fault);
  if (status == IoResult::kDisconnected) return status;
  command_ = command;
  // A motor latches its target where the target was meant when it was written: a zero reset
  // afterwards changes what it reports, not where it holds.
  for (std::size_t i = 0; i < params_.joints.size(); ++i) {
    rt_command_zero_offset_rad_[i] = zero_offset_rad_[i].load(std::memory_order_relaxed);
  }
  const auto joints = std::span(command.joints).first(std::min(command.joint_count, params_.joints.size()));
  // A session taking a joint enables the motors, as the PiPER and xArm drivers do by default.
  if (std::any_of(joints.begin(), joints.end(), [](const JointCommand& joint) { return joint.owned; })) {
    motors_enabled_.store(true, std::memory_order_relaxed);
  }
  if (motors_off_.take() != nullptr) motors_off_.answer(decide_motors_off(command));
  if (command.newest_command_sent_ns != 0) {
    // How long the newest client command took from its publish to this write().
    const std::int64_t latency_ns = monotonic_now_ns() - command.newest_command_sent_ns;
    const std::uint64_t count = latency_count_.load(std::memory_order_relaxed);
    latency_ns_[count % kLatencySamples].store(
        static_cast<std::int32_t>(std::clamp<std::int64_t>(latency_ns, 0, std::numeric_limits<std::int32_t>::max())),
        std::memory_order_relaxed);
    latency_count_.store(count + 1, std::memory_order_release);
  }
  return status;
}

MotorsOffOutcome SimDriver::decide_motors_off(const CommandFrame& command) noexcept {
  using Verdict = MotorsOffOutcome::Verdict;
  if (command.estop) return {.verdict = Verdict::kEstop};
  for (std::size_t j = 0; j < std::min(command.joint_count, params_.joints.size()); ++j) {
    const JointCommand& joint = command.joints[j];
    if (joint.owned) return {.verdict = Verdict::kOwned, .joint = j};
    if (joint.holds()) return {.verdict = Verdict::kHeld, .joint = j};
  }
  motors_enabled_.store(false, std::memory_order_relaxed);
  return {.verdict = Verdict::kDisabled};
}

bool SimDriver::refresh_link_state(FaultInfo& fault) noexcept {
  if (!connected_.load(std::memory_order_acquire)) {
    fault.set(kNotConnectedFaultCode, "simulated link not connected (connect() or recover() first)");
    return false;
  }
  if (const std::uint64_t generation = link_generation_.load(std::memory_order_acquire);
      generation != rt_link_generation_) {
    rt_link_generation_ = generation;
    command_ = CommandFrame{};
    rt_clock_started_ = false;
  }
  // A read that races a write keeps the previous copy; the next tick takes the new one.
  injected_faults_.try_load(rt_injected_faults_);
  return true;
}

IoResult SimDriver::injected_link_status(FaultInfo& fault) const noexcept {
  if (rt_injected_faults_.link_lost) {
    fault.set(kLinkLostFaultCode, "simulated link lost (injected)");
    return IoResult::kDisconnected;
  }
  if (rt_injected_faults_.fault.code != 0) {
    fault = rt_injected_faults_.fault;
    return IoResult::kFault;
  }
  return IoResult::kOk;
}

void SimDriver::advance_physics(std::int64_t now_ns) noexcept {
  const double dt_s = rt_clock_started_ ? static_cast<double>(now_ns - rt_last_step_ns_) * 1e-9 : 0.0;
  rt_clock_started_ = true;
  rt_last_step_ns_ = now_ns;

  const bool powered = motors_enabled_.load(std::memory_order_relaxed);
  const bool damp_all = command_.estop || rt_injected_faults_.halts_motors();
  const std::size_t joint_count = params_.joints.size();
  for (std::size_t i = 0; i < joint_count; ++i) {
    const SimJointParams& joint = params_.joints[i];
    const double zero_offset_rad = zero_offset_rad_[i].load(std::memory_order_relaxed);
    const JointCommand command = i < command_.joint_count ? command_.joints[i] : JointCommand{};
    MotorLaw law;  // disabled motors apply no torque
    if (powered)
      law = damp_all ? MotorLaw{.kd = joint.default_kd}
                     : commanded_motor_law(joint, command, rt_command_zero_offset_rad_[i]);
    const JointPhysics physics{.inertia_kg_m2 = joint.inertia_kg_m2,
                               .damping_nm_s_rad = joint.damping_nm_s_rad,
                               .position_min_rad = joint.limits.position_min_rad + zero_offset_rad,
                               .position_max_rad = joint.limits.position_max_rad + zero_offset_rad,
                               .effort_max_nm = joint.limits.effort_max_nm};
    JointState& state = joints_[i];
    step_joint(physics, law, external_torque_nm_[i].load(std::memory_order_relaxed), dt_s, state);
    rt_snapshot_.joints[i] = SimJointSnapshot{.position_rad = state.position_rad - zero_offset_rad,
                                              .physical_position_rad = state.position_rad,
                                              .velocity_rad_s = state.velocity_rad_s,
                                              .torque_nm = state.motor_torque_nm,
                                              .kp = law.kp,
                                              .kd = law.kd,
                                              .command = command.kind};
  }
  rt_snapshot_.joint_count = joint_count;
  rt_snapshot_.estop = command_.estop;
  snapshot_.store(rt_snapshot_);
}

void SimDriver::fill_feedback(Feedback& out) const noexcept {
  out.joint_count = rt_snapshot_.joint_count;
  for (std::size_t i = 0; i < rt_snapshot_.joint_count; ++i) {
    const SimJointSnapshot& joint = rt_snapshot_.joints[i];
    out.joints[i] = driver::JointFeedback{
        .position_rad = joint.position_rad, .velocity_rad_s = joint.velocity_rad_s, .effort_nm = joint.torque_nm};
  }
  out.estop_input = estop_input_.load(std::memory_order_relaxed);
  out.has_imu = params_.imu;
  out.imu = params_.imu ? rt_imu_ : driver::ImuSample{};
}

}  // namespace robotd::sim
