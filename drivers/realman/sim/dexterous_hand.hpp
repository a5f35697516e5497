// The Inspire five-finger hand (spec §5.2): six degrees of freedom (little, ring, middle, index,
// thumb bend, thumb rotate), each an angle from 0 (closed) to 1000 (open) that moves towards its
// target at 2 × speed units per second. Postures and sequences are fixed tables (README.md):
// posture n closes every finger to 1000 − ⌊1000 (n − 1) / 39⌋; sequence n is posture n, then
// posture 1 (open).
#pragma once

#include <array>
#include <cstddef>
#include <deque>

#include <nlohmann/json.hpp>

namespace robotd::realman::sim {

class DexterousHand {
 public:
  static constexpr std::size_t kDof = 6;
  static constexpr int kPresets = 40;
  static constexpr double kUnitsPerSecondPerSpeed = 2.0;
  using Angles = std::array<int, kDof>;

  static Angles posture_angles(int posture);  // 1 … 40

  /// set_hand_angle / hand_follow_angle: −1 keeps that degree of freedom where it is heading.
  void set_angles(const Angles& angles);
  void set_posture(int posture);
  void run_sequence(int sequence);
  void set_speed(int speed) { speed_ = speed; }
  void set_force(int force) { force_ = force; }

  /// Runs the motion for `dt_s`; true when a motion (a whole sequence) ended during it.
  bool advance(double dt_s);

  Angles angles() const;
  /// The push's "hand" object (§6.2): hand_pos and hand_angle (the same here), hand_force (no
  /// contact is simulated: 0), hand_state (0 at its target, 1 moving), hand_err.
  nlohmann::json push_fields() const;
  nlohmann::json control_state() const;

 private:
  bool moving() const;  // some degree of freedom is not at its target

  std::array<double, kDof> angles_{1000, 1000, 1000, 1000, 1000, 1000};
  std::array<double, kDof> targets_{1000, 1000, 1000, 1000, 1000, 1000};
  std::deque<Angles> steps_;  // a sequence's postures still to come
  bool running_ = false;      // a motion not yet reported as ended
  int speed_ = 500;
  int force_ = 500;
};

}  // namespace robotd::realman::sim
