// The arm: joint positions, enables, power, the controller's and the joints' errors, and the two
// ways it moves — planned trajectories (TrajectoryQueue) and pass-through frames (movej_canfd,
// spec §3.3) with their rules. advance() brings it to a given time; what ended meanwhile is taken
// with take_ends().
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "arm_kinematics.hpp"
#include "codec/realman_codec.hpp"
#include "frame_intervals.hpp"
#include "robotd/result.hpp"
#include "trajectory_queue.hpp"

namespace robotd::realman::sim {

/// The push's arm_current_status (§6.2) for what the arm does.
enum class ArmStatus : std::uint8_t { kIdle, kMoveJ, kMoveL, kMoveThroughJoint, kStop, kSlowStop, kPause };
std::string_view status_text(ArmStatus status);

struct PassThroughFrame {
  JointValues joints{};
  bool follow = false;  // high follow: the joints take the target at once; low: a 50 ms lag
};

struct PassThroughCounters {
  std::uint64_t frames = 0;     // movej_canfd frames that reached the arm
  std::uint64_t accepted = 0;   // became the target
  std::uint64_t ignored = 0;    // broke a §3.3 rule (beyond a limit, > 10°, > 180 °/s)
  std::uint64_t refused = 0;    // the arm could not take any motion (error, power, e-stop, trajectory)
  std::uint64_t malformed = 0;  // fields missing, of the wrong type or size
  std::string last_rejection;   // why the last ignored or refused frame was
  std::optional<bool> follow;   // of the last frame
};

class Arm {
 public:
  /// The pass-through rules of §3.3 and the low-follow lag.
  static constexpr double kMaxFrameStepRad = kPassThroughMaxStepRad;
  static constexpr double kMaxFrameSpeedRadS = kPassThroughMaxSpeedRadS;
  static constexpr double kLowFollowLagS = 0.05;
  /// How long after its last accepted frame the arm reports move_through_joint.
  static constexpr std::int64_t kStreamingNs = 100'000'000;

  Arm(std::string product_version, const ArmModel& model, std::int64_t now_ns);
  Arm(const Arm&) = delete;  // its trajectory queue plans through `this`
  Arm& operator=(const Arm&) = delete;

  std::size_t dof() const { return model_.dof; }
  const ArmModel& model() const { return model_; }
  const JointValues& position() const { return position_; }
  const JointValues& velocity() const { return velocity_; }  // rad/s, low-passed over 10 ms
  /// Where the arm is headed: the end of the planned motion, the pass-through target, or here.
  JointValues target() const;
  /// The flange pose; nullopt for a model without a DH table.
  std::optional<EulerPose> flange_pose() const;
  /// The DH table the kinematics use; nullopt for a model without one.
  const std::optional<ArmKinematics>& kinematics() const { return kinematics_; }
  ArmStatus status(std::int64_t now_ns) const;
  const TrajectoryQueue& trajectories() const { return trajectories_; }

  /// kRefused naming the joint, its value and its range.
  Result<void> check_limits(const JointValues& joints) const;
  /// The joints for a flange pose, solved from where the next segment starts (movej_p).
  Result<JointValues> solve(const EulerPose& pose) const;
  /// Where the next planned segment starts: the end of those queued, else here.
  JointValues next_start() const { return trajectories_.next_start(position_); }
  /// The flange there (set_pos_step, set_ort_step); kRefused without Cartesian planning.
  Result<Eigen::Isometry3d> next_start_flange() const;
  /// Checks a planned segment (movel: plans it) and queues it; kRefused with the reason.
  Result<void> plan(Segment segment, bool connect);
  /// Judges a pass-through frame by §3.3 and takes it or counts why not.
  void pass_through(const PassThroughFrame& frame, std::int64_t now_ns);
  /// A movej_canfd frame that could not be read: counted, and its arrival timed.
  void malformed_frame(std::string why, std::int64_t now_ns);

  void stop();  // set_arm_stop: at once; the trajectory is aborted
  void slow_stop();
  void pause();
  void resume();
  Result<void> delete_current();
  Result<void> delete_all();
  void set_emergency_stop(bool engaged);  // stops, and refuses motion while engaged
  bool emergency_stop() const { return emergency_stop_; }

  Result<void> set_enabled(std::size_t joint, bool enable);  // joint index from 0
  bool enabled(std::size_t joint) const { return enabled_[joint]; }
  void set_power(bool on);
  bool powered() const { return powered_; }

  /// Latches a controller error; whatever moved stops where it is.
  void raise_error(std::uint16_t code);
  void clear_system_errors() { system_errors_.clear(); }
  const std::vector<std::uint16_t>& system_errors() const { return system_errors_; }
  void set_joint_error(std::size_t joint, std::uint16_t bits) { joint_errors_[joint] = bits; }
  std::uint16_t joint_errors(std::size_t joint) const { return joint_errors_[joint]; }

  /// Puts the joints there at once (control channel); refused while a trajectory is pending.
  Result<void> teleport(const JointValues& joints);

  void advance(std::int64_t now_ns);
  std::vector<TrajectoryEnd> take_ends();

  const PassThroughCounters& pass_through_counters() const { return counters_; }
  const FrameIntervals& frame_intervals() const { return intervals_; }

 private:
  Result<void> ready_to_move() const;
  Result<void> check_disabled(const JointValues& to, const JointValues& from) const;
  Result<PlannedPath> plan_path(const Segment& segment, const JointValues& from) const;
  bool cartesian() const { return kinematics_ && kinematics_->solves_poses(); }
  void reject_frame(std::uint64_t& counter, std::string why);
  void hold();  // no pass-through target: stay where it is

  std::string product_version_;
  ArmModel model_;
  std::optional<ArmKinematics> kinematics_;
  JointValues position_{};
  JointValues velocity_{};
  std::array<bool, kMaxDof> enabled_{};
  std::array<std::uint16_t, kMaxDof> joint_errors_{};
  std::vector<std::uint16_t> system_errors_;
  bool powered_ = true;
  bool emergency_stop_ = false;
  bool stopped_ = false;  // by a stop, until the next motion

  TrajectoryQueue trajectories_;
  std::vector<TrajectoryEnd> ends_;

  std::optional<JointValues> stream_target_;
  bool stream_follow_ = false;
  std::int64_t last_accepted_ns_ = 0;
  PassThroughCounters counters_;
  FrameIntervals intervals_;

  std::int64_t advanced_ns_;
};

}  // namespace robotd::realman::sim
