// Servo mode's targets (spec §4.1 "servo mode"): the newest accepted servo_j target wins and the
// joints step toward it at up to 180 °/s each. A target beyond the joint limits, or one further
// from the previous accepted target than 180 °/s allows (with 10 % margin, over the time since
// that one, at least 4 ms), is refused: the controller latches C23 or C24. The first target of a
// stream (after entering the mode, a stop or a reset) has no previous one to be judged against.
#pragma once

#include <cstdint>
#include <optional>

#include <nlohmann/json.hpp>

#include "codec/xarm_codec.hpp"

namespace robotd::xarm::sim {

class ServoStream {
 public:
  static constexpr std::int64_t kMinIntervalNs = 4'000'000;  // the 250 Hz command rate (§2.6)
  static constexpr double kSpeedMargin = 1.1;

  enum class Verdict : std::uint8_t { kAccepted, kBeyondLimit, kTooFast };

  /// Judges a target received at `now_ns` and takes it if it passes.
  Verdict offer(const JointValues& requested, std::int64_t now_ns, const ArmModel& model);
  /// A servo_j the arm could not take (another mode, not ready): counted.
  void ignore() { ++ignored_; }
  /// Forgets the target: the joints hold, the next servo_j starts a new stream.
  void drop() { target_.reset(); }
  bool active() const { return target_.has_value(); }
  /// The newest accepted target; nullopt while the joints hold.
  const std::optional<JointValues>& target() const { return target_; }

  /// Moves `joints` toward the target for `dt_s`, each at up to kMaxJointSpeedRadS; true when
  /// they are on it.
  bool step(JointValues& joints, std::size_t dof, double dt_s) const;
  /// The velocity step() drives `joints` at: kMaxJointSpeedRadS toward the target for each joint
  /// off it, 0 for one on it.
  JointValues drive_velocity(const JointValues& joints, std::size_t dof) const;

  /// {"frames", "ignored", "max_interval_us", "last_target_rad"} for the control channel.
  nlohmann::json statistics(std::size_t dof) const;

 private:
  std::optional<JointValues> target_;
  std::int64_t accepted_ns_ = 0;
  JointValues last_target_{};  // kept after drop(), for the statistics
  std::uint64_t frames_ = 0;
  std::uint64_t ignored_ = 0;
  std::int64_t max_interval_ns_ = 0;
};

}  // namespace robotd::xarm::sim
