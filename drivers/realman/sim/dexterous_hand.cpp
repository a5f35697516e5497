#include "dexterous_hand.hpp"

#include <algorithm>
#include <cmath>

namespace robotd::realman::sim {

DexterousHand::Angles DexterousHand::posture_angles(int posture) {
  Angles angles{};
  angles.fill(1000 - 1000 * (posture - 1) / (kPresets - 1));
  return angles;
}

void DexterousHand::set_angles(const Angles& angles) {
  steps_.clear();
  for (std::size_t i = 0; i < kDof; ++i) {
    if (angles[i] >= 0) targets_[i] = angles[i];
  }
  running_ = true;
}

void DexterousHand::set_posture(int posture) { set_angles(posture_angles(posture)); }

void DexterousHand::run_sequence(int sequence) {
  set_angles(posture_angles(sequence));
  steps_.push_back(posture_angles(1));
}

bool DexterousHand::advance(double dt_s) {
  if (!running_) return false;
  const double step = kUnitsPerSecondPerSpeed * speed_ * dt_s;
  for (std::size_t i = 0; i < kDof; ++i) {
    angles_[i] =
        targets_[i] > angles_[i] ? std::min(targets_[i], angles_[i] + step) : std::max(targets_[i], angles_[i] - step);
  }
  if (moving()) return false;
  if (!steps_.empty()) {
    for (std::size_t i = 0; i < kDof; ++i) targets_[i] = steps_.front()[i];
    steps_.pop_front();
    return false;
  }
  running_ = false;
  return true;
}

DexterousHand::Angles DexterousHand::angles() const {
  Angles out{};
  for (std::size_t i = 0; i < kDof; ++i) out[i] = static_cast<int>(std::lround(angles_[i]));
  return out;
}

bool DexterousHand::moving() const { return angles_ != targets_; }

nlohmann::json DexterousHand::push_fields() const {
  Angles states{};
  for (std::size_t i = 0; i < kDof; ++i) states[i] = angles_[i] == targets_[i] ? 0 : 1;
  return {{"hand_pos", angles()},
          {"hand_angle", angles()},
          {"hand_force", Angles{}},
          {"hand_state", states},
          {"hand_err", 0}};
}

nlohmann::json DexterousHand::control_state() const {
  Angles targets{};
  for (std::size_t i = 0; i < kDof; ++i) targets[i] = static_cast<int>(std::lround(targets_[i]));
  return {{"angles", angles()}, {"targets", targets}, {"speed", speed_},
          {"force", force_},    {"moving", running_}, {"sequence_steps_left", steps_.size()}};
}

}  // namespace robotd::realman::sim
