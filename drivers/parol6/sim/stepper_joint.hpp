// One joint's stepper as the firmware drives it through AccelStepper: an integer step counter
// and a speed set point, run at constant speed (runSpeed(): no ramp), clamped to the firmware's
// ±50 000 steps/s.
#pragma once

#include <algorithm>
#include <cstdint>

namespace robotd::parol6::sim {

inline constexpr std::int32_t kMaxSpeedStepsPerSecond = 50'000;

struct StepperJoint {
  std::int64_t steps = 0;          // currentPosition()
  double fraction = 0;             // progress towards the next step, (-1, 1)
  std::int32_t speed_steps_s = 0;  // the speed last set (what the reply reports)

  void set_speed(std::int64_t steps_per_s) {
    speed_steps_s = static_cast<std::int32_t>(
        std::clamp<std::int64_t>(steps_per_s, -kMaxSpeedStepsPerSecond, kMaxSpeedStepsPerSecond));
  }
  /// setCurrentPosition(): the counter is overwritten, a step in progress is forgotten.
  void set_position(std::int64_t new_steps) {
    steps = new_steps;
    fraction = 0;
  }
  /// Steps at the set speed for `dt_s` (what runSpeed() averages to over one main-loop pass).
  void run(double dt_s) {
    fraction += speed_steps_s * dt_s;
    const auto whole = static_cast<std::int64_t>(fraction);  // towards zero
    steps += whole;
    fraction -= static_cast<double>(whole);
  }
};

}  // namespace robotd::parol6::sim
