// Joint and Cartesian moves on a session, the library way: planned in this process from the
// joints robotd measures, on the device's joint limits and the arm model its driver names
// (DeviceInfo.kinematic_model), then streamed through the session at the device's rate
// (TrajectoryStreamer) until every joint has arrived. The daemon only follows the stream.
// The timing rules are RBTscript's (joint_move.hpp): t overrides v and a; v and a are percent of
// the leading joint's maximum; "poly" unless told "trap" with t; conservative defaults.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <numbers>
#include <vector>

#include "robotd/client/client.hpp"
#include "robotd/kinematics/arm_model.hpp"
#include "robotd/motion/joint_move.hpp"
#include "robotd/motion/trajectory_streamer.hpp"
#include "robotd/result.hpp"

namespace robotd::motion {

/// When a move has arrived: every joint within 0.1° of its goal, at most 3 s after the last
/// sample. RBTscript's moves and these use the same.
inline constexpr double kMoveArrivalToleranceRad = 0.1 * std::numbers::pi / 180.0;
inline constexpr std::chrono::milliseconds kMoveArrivalTimeout{3000};

enum class CartesianPath : std::uint8_t {
  kJoint,  // IK of the goal, then a joint move (RBTscript MovePose): the tool's path is not a line
  kLine,   // the tool on a straight line (MoveCart), IK along it; stops before a singularity
};

/// `session`: POSITION mode on every joint of its device, in joint order (as request_control
/// grants a request that names no motors). `stop` (may be null) ends the move with the arm held
/// where it is (StreamReport::end kStopped). Errors: kInvalidArgument (a target of the wrong size,
/// one outside the limits, a move too fast for the device: nothing moved; the message says what
/// is expected), kRefused (an e-stop, a fault or the end of the session mid-move), kTimeout (the
/// joints did not arrive), and the client's own.
Result<StreamReport> move_joints(Client& client, Session& session, const std::vector<double>& target_rad,
                                 const MoveTiming& timing = {}, const std::atomic<bool>* stop = nullptr);

/// The tool (the arm model's) to `goal`, in the base frame: m, and the three angles of the arm's
/// own Euler convention (ArmModel::euler) in rad. A line takes only `timing`'s t and func. Fails
/// as move_joints does, and when the device names no arm model, the goal is out of reach or
/// (a line) the path meets a singularity or a joint limit (kInvalidArgument, before anything moves).
Result<StreamReport> move_cartesian(Client& client, Session& session, const kinematics::EulerPose& goal,
                                    const MoveTiming& timing = {}, CartesianPath path = CartesianPath::kJoint,
                                    const std::atomic<bool>* stop = nullptr);

}  // namespace robotd::motion
