// Command 100's built-in homing (spec §9) as a fixed-duration script: four phases of equal
// length (J1–J3 together, J4, J6, J5 with J6 returning), each one a seek at the firmware's seek
// speed ending on the switch (counter zeroed), a back-off, a re-approach (zeroed again) and the
// move to the joint's offset; then every counter is overwritten with its standby value.
// Homed bits: all drop at the start; J1–J3 after phase 1, J4 after phase 2, J5 and J6 after
// phase 4. It advances only on passes the arm gives it (command 100 or 255, enabled).
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "codec/parol6_frames.hpp"
#include "stepper_joint.hpp"

namespace robotd::parol6::sim {

using Steppers = std::array<StepperJoint, kJoints>;

/// The counters after homing (firmware constants; 90°, −90°, 180°, 0°, 0°, 180°).
inline constexpr std::array<std::int32_t, kJoints> kStandbySteps = {10240, -32000, 57905, 0, 0, 32000};
inline constexpr std::uint8_t kAllJointsMask = 0x3F;  // bit j = joint j (J1 = bit 0)

class HomingSequence {
 public:
  enum class Phase : std::uint8_t { kIdle, kBase, kWrist1, kWrist3, kWrist2 };  // J1–J3, J4, J6, J5

  /// `duration_ms` for the whole sequence.
  explicit HomingSequence(std::int64_t duration_ms);

  /// Starts from the first phase; every homed bit drops and every joint's speed is zeroed.
  void start(Steppers& joints, std::uint8_t& homed_mask);
  /// Stops where it is (101, 102, 103, 123, 156): counters stay, the bits earned so far stay.
  void abort() { phase_ = Phase::kIdle; }
  bool active() const { return phase_ != Phase::kIdle; }
  Phase phase() const { return phase_; }
  /// Seconds into the current phase.
  double phase_elapsed_s() const { return elapsed_s_; }

  /// One main-loop pass: moves the phase's joints, sets their speeds and homed bits.
  void step(double dt_s, Steppers& joints, std::uint8_t& homed_mask);

 private:
  void begin_phase(Phase phase, const Steppers& joints);
  void finish_phase(Steppers& joints, std::uint8_t& homed_mask);
  void place(Steppers& joints) const;

  double phase_s_;
  Phase phase_ = Phase::kIdle;
  double elapsed_s_ = 0;
  std::array<std::int64_t, kJoints> phase_start_steps_{};
};

/// "idle", "J1-J3", "J4", "J6", "J5".
std::string phase_text(HomingSequence::Phase phase);

}  // namespace robotd::parol6::sim
