#include "checking_executor.hpp"

#include <utility>

namespace robotd::rbtscript::detail {

CheckingExecutor::CheckingExecutor(const ArmPlanner& planner, const motion::DeviceIo& io, motion::Joints start)
    : planner_(planner), io_(io), joints_(std::move(start)) {}

void CheckingExecutor::at(const Progress& progress) {
  current_ = progress;
  current_text_ = std::string(progress.text);
}

void CheckingExecutor::keep(const Error& error) {
  problems_.push_back(RunError{current_.index, current_.location, current_text_, error.message});
}

Result<void> CheckingExecutor::check(const Result<PlannedMove>& move) {
  if (!move) {
    keep(move.error());  // the arm stays where the move would have started
    return {};
  }
  ++moves_planned_;
  seconds_ += move.value().trajectory.duration_s;
  joints_ = move.value().trajectory.positions.back();
  return {};
}

Result<void> CheckingExecutor::check(const Result<motion::DeviceCall>& call) {
  if (!call) keep(call.error());
  return {};
}

Result<void> CheckingExecutor::delay(const Delay& statement) {
  seconds_ += statement.seconds;
  return {};
}

Result<void> CheckingExecutor::output(const Output& statement) {
  return check(io_.output(statement.number, statement.level == Level::kHigh));
}

Result<void> CheckingExecutor::gripper_calibrate(const GripperCalibrate& /*statement*/) {
  return check(io_.gripper_calibrate());
}

Result<void> CheckingExecutor::gripper(const Gripper& statement) {
  return check(io_.gripper({statement.position, statement.speed, statement.current_ma}));
}

}  // namespace robotd::rbtscript::detail
