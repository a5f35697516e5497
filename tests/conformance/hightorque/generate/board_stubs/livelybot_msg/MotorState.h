// Stand-in for the generated livelybot_msg/MotorState message: the fields motor.cc writes.
#pragma once

namespace livelybot_msg {
struct MotorState {
  float pos = 0;
  float vel = 0;
  float tau = 0;
};
}  // namespace livelybot_msg
