// The real run's executor: each move is planned from where the arm was last told to be (the
// first from the measured joints), streamed through the session and waited for; a Delay holds
// the arm for its time through the same streamer, so that the session stays alive and a stop or
// an e-stop ends it at once; Output and Gripper go to the device's ops.
#pragma once

#include <atomic>

#include "arm_session.hpp"
#include "robotd/motion/device_io.hpp"
#include "robotd/rbtscript/arm_planner.hpp"
#include "robotd/rbtscript/interpreter.hpp"

namespace robotd::rbtscript::detail {

class DeviceExecutor final : public Executor {
 public:
  DeviceExecutor(ArmSession& arm, const ArmPlanner& planner, const motion::DeviceIo& io, const std::atomic<bool>& stop,
                 motion::Joints start);

  Result<void> move_joint(const MoveJoint& statement) override { return follow(planner_.plan(statement, held_)); }
  Result<void> move_pose(const MovePose& statement) override { return follow(planner_.plan(statement, held_)); }
  Result<void> move_cart(const MoveCart& statement) override { return follow(planner_.plan(statement, held_)); }
  Result<void> move_cart_rel_trf(const MoveCartRelTrf& statement) override {
    return follow(planner_.plan(statement, held_));
  }
  Result<void> delay(const Delay& statement) override;
  Result<void> output(const Output& statement) override;
  Result<void> gripper_calibrate(const GripperCalibrate& statement) override;
  Result<void> gripper(const Gripper& statement) override;

 private:
  Result<void> follow(const Result<PlannedMove>& move);
  // Streams `trajectory`; where the arm was measured when it ended, or why it did not complete.
  Result<motion::Joints> stream(const motion::SampledTrajectory& trajectory, const motion::StreamOptions& options);
  Result<void> call(const Result<motion::DeviceCall>& call);

  ArmSession& arm_;
  const ArmPlanner& planner_;
  const motion::DeviceIo& io_;
  const std::atomic<bool>& stop_;
  motion::Joints held_;  // where the arm was last told to be
};

}  // namespace robotd::rbtscript::detail
