#include "gripper_current.hpp"

#include <cmath>
#include <string>

namespace robotd::parol6 {
namespace {

constexpr double kDangerAboveA = 0.7;
constexpr double kTooWeakBelowA = 0.15;

}  // namespace

std::string gripper_current_warning(double current_a, int speed) {
  const std::string milliamps = std::to_string(std::lround(current_a * 1000)) + " mA";
  if (current_a > kDangerAboveA) {
    return "gripper current " + milliamps + " is above 700 mA: it can damage the object being grasped and hurt " +
           "fingers in the jaws" +
           (speed > 127 ? ", the more so at this high speed (" + std::to_string(speed) + ")" : "") +
           "; lower it unless the grip needs that force";
  }
  if (current_a < kTooWeakBelowA) {
    return "gripper current " + milliamps + " is below 150 mA: the gripper usually cannot move with it";
  }
  return {};
}

}  // namespace robotd::parol6
