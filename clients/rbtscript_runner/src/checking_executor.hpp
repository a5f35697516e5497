// The dry run's executor: plans every move from where the one before it ends (the first from the
// measured joints) and asks the device's I/O map for every Output and Gripper statement, without
// sending anything. Every problem is kept with the statement it belongs to; after one, the
// script goes on from where it was, so that one run lists them all.
#pragma once

#include <cstddef>
#include <vector>

#include "robotd/motion/device_io.hpp"
#include "robotd/rbtscript/arm_planner.hpp"
#include "robotd/rbtscript/interpreter.hpp"

namespace robotd::rbtscript::detail {

class CheckingExecutor final : public Executor {
 public:
  CheckingExecutor(const ArmPlanner& planner, const motion::DeviceIo& io, motion::Joints start);

  /// Before each statement (RunOptions::on_statement): the statement a problem belongs to.
  void at(const Progress& progress);
  const std::vector<RunError>& problems() const { return problems_; }
  std::size_t moves_planned() const { return moves_planned_; }
  /// The planned moves' durations and the delays, summed: how long one pass takes at least.
  double seconds() const { return seconds_; }

  Result<void> move_joint(const MoveJoint& statement) override { return check(planner_.plan(statement, joints_)); }
  Result<void> move_pose(const MovePose& statement) override { return check(planner_.plan(statement, joints_)); }
  Result<void> move_cart(const MoveCart& statement) override { return check(planner_.plan(statement, joints_)); }
  Result<void> move_cart_rel_trf(const MoveCartRelTrf& statement) override {
    return check(planner_.plan(statement, joints_));
  }
  Result<void> delay(const Delay& statement) override;
  Result<void> output(const Output& statement) override;
  Result<void> gripper_calibrate(const GripperCalibrate& statement) override;
  Result<void> gripper(const Gripper& statement) override;

 private:
  Result<void> check(const Result<PlannedMove>& move);
  Result<void> check(const Result<motion::DeviceCall>& call);
  void keep(const Error& error);

  const ArmPlanner& planner_;
  const motion::DeviceIo& io_;
  motion::Joints joints_;
  Progress current_;
  std::string current_text_;
  std::vector<RunError> problems_;
  std::size_t moves_planned_ = 0;
  double seconds_ = 0;
};

}  // namespace robotd::rbtscript::detail
