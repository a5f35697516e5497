#include "homing_sequence.hpp"

#include <cmath>

namespace robotd::parol6::sim {
namespace {

/// One joint's part of a phase (spec §9; steps and steps/s).
struct JointHoming {
  int joint;                // 0 … 5
  std::int32_t seek_speed;  // towards the switch
  std::int32_t back_off;    // position after backing off the switch
  std::int32_t offset;      // position at the end of the phase
};

struct PhaseScript {
  std::array<JointHoming, 3> joints;
  int count;
  std::uint8_t homed_after;  // bits set when the phase ends
};

// The SSG-48 build's J5 offset (8035; 8900 with the pneumatic gripper).
constexpr std::array<PhaseScript, 4> kScript = {{
    {{{{0, -2050, 850, 13500}, {1, -2550, 1050, 19588}, {2, -2550, 1050, 23020}}}, 3, 0x07},
    {{{{3, 5550, -1550, -10200}}}, 1, 0x08},
    {{{{5, -9550, 1550, 15900}}}, 1, 0x00},
    {{{{4, -5050, 1550, 8035}}}, 1, 0x30},
}};
constexpr int kJ6 = 5;

// Where each part of a phase ends, as a fraction of the phase.
constexpr double kSeekEnd = 0.35;
constexpr double kBackOffEnd = 0.55;
constexpr double kApproachEnd = 0.70;

const PhaseScript& script_of(HomingSequence::Phase phase) { return kScript.at(static_cast<std::size_t>(phase) - 1); }

std::int64_t toward(double from, double to, double fraction) { return std::llround(from + (to - from) * fraction); }

}  // namespace

HomingSequence::HomingSequence(std::int64_t duration_ms)
    : phase_s_(static_cast<double>(duration_ms) / 1000.0 / static_cast<double>(kScript.size())) {}

void HomingSequence::start(Steppers& joints, std::uint8_t& homed_mask) {
  homed_mask = 0;
  for (StepperJoint& joint : joints) joint.set_speed(0);
  begin_phase(Phase::kBase, joints);
}

void HomingSequence::begin_phase(Phase phase, const Steppers& joints) {
  phase_ = phase;
  elapsed_s_ = 0;
  for (std::size_t j = 0; j < joints.size(); ++j) phase_start_steps_[j] = joints[j].steps;
}

void HomingSequence::step(double dt_s, Steppers& joints, std::uint8_t& homed_mask) {
  if (!active()) return;
  elapsed_s_ += dt_s;
  if (elapsed_s_ >= phase_s_) {
    finish_phase(joints, homed_mask);
    return;
  }
  place(joints);
}

void HomingSequence::place(Steppers& joints) const {
  const PhaseScript& script = script_of(phase_);
  const double f = elapsed_s_ / phase_s_;
  for (int i = 0; i < script.count; ++i) {
    const JointHoming& part = script.joints.at(static_cast<std::size_t>(i));
    StepperJoint& joint = joints.at(static_cast<std::size_t>(part.joint));
    const double back_off = part.back_off;
    if (f < kSeekEnd) {  // running into the switch from wherever it was
      const double start = static_cast<double>(phase_start_steps_.at(static_cast<std::size_t>(part.joint)));
      joint.set_position(std::llround(start + part.seek_speed * elapsed_s_));
      joint.set_speed(part.seek_speed);
    } else if (f < kBackOffEnd) {  // the counter was zeroed on the switch; back off
      joint.set_position(toward(0, back_off, (f - kSeekEnd) / (kBackOffEnd - kSeekEnd)));
      joint.set_speed(std::llround(back_off / ((kBackOffEnd - kSeekEnd) * phase_s_)));
    } else if (f < kApproachEnd) {  // slowly onto the switch again
      joint.set_position(toward(back_off, 0, (f - kBackOffEnd) / (kApproachEnd - kBackOffEnd)));
      joint.set_speed(std::llround(-back_off / ((kApproachEnd - kBackOffEnd) * phase_s_)));
    } else {  // zeroed again; to the offset
      joint.set_position(toward(0, part.offset, (f - kApproachEnd) / (1 - kApproachEnd)));
      joint.set_speed(std::llround(part.offset / ((1 - kApproachEnd) * phase_s_)));
    }
  }
  if (phase_ == Phase::kWrist2 && f >= kApproachEnd) {  // J6 returns to 0 while J5 moves to its offset
    StepperJoint& j6 = joints.at(kJ6);
    const double start = static_cast<double>(phase_start_steps_.at(kJ6));
    j6.set_position(toward(start, 0, (f - kApproachEnd) / (1 - kApproachEnd)));
    j6.set_speed(std::llround(-start / ((1 - kApproachEnd) * phase_s_)));
  }
}

void HomingSequence::finish_phase(Steppers& joints, std::uint8_t& homed_mask) {
  const PhaseScript& script = script_of(phase_);
  for (int i = 0; i < script.count; ++i) {
    const JointHoming& part = script.joints.at(static_cast<std::size_t>(i));
    joints.at(static_cast<std::size_t>(part.joint)).set_position(part.offset);
    joints.at(static_cast<std::size_t>(part.joint)).set_speed(0);
  }
  if (phase_ == Phase::kWrist2) {
    joints.at(kJ6).set_position(0);
    joints.at(kJ6).set_speed(0);
  }
  homed_mask = static_cast<std::uint8_t>(homed_mask | script.homed_after);
  switch (phase_) {
    case Phase::kBase:
      begin_phase(Phase::kWrist1, joints);
      break;
    case Phase::kWrist1:
      begin_phase(Phase::kWrist3, joints);
      break;
    case Phase::kWrist3:
      begin_phase(Phase::kWrist2, joints);
      break;
    case Phase::kWrist2:
    case Phase::kIdle:
      for (std::size_t j = 0; j < joints.size(); ++j) joints[j].set_position(kStandbySteps[j]);
      homed_mask = kAllJointsMask;
      phase_ = Phase::kIdle;
      elapsed_s_ = 0;
      break;
  }
}

std::string phase_text(HomingSequence::Phase phase) {
  switch (phase) {
    case HomingSequence::Phase::kIdle:
      return "idle";
    case HomingSequence::Phase::kBase:
      return "J1-J3";
    case HomingSequence::Phase::kWrist1:
      return "J4";
    case HomingSequence::Phase::kWrist3:
      return "J6";
    case HomingSequence::Phase::kWrist2:
      return "J5";
  }
  return "idle";
}

}  // namespace robotd::parol6::sim
