#include "robotd/rbtscript/device_runner.hpp"

#include <cstddef>
#include <cstdint>
#include <utility>

#include "arm_session.hpp"
#include "checking_executor.hpp"
#include "device_executor.hpp"
#include "device_lookup.hpp"
#include "robotd/motion/device_io.hpp"
#include "robotd/rbtscript/arm_planner.hpp"

namespace robotd::rbtscript {

Result<DeviceRunReport> run_on_device(Client& client, const Program& program, const DeviceRunOptions& options) {
  auto device = detail::find_device(client, options.device);
  if (!device) return device.error();
  auto planner = ArmPlanner::for_device(device.value());
  if (!planner) return planner.error();
  const motion::DeviceIo io(device.value());
  auto start = detail::measured_joints(client, device.value(), planner.value().joint_count());
  if (!start) return start.error();

  DeviceRunReport report;
  report.device = device.value().name;
  detail::CheckingExecutor checker(planner.value(), io, start.value());
  RunOptions check_options{.loops = 1, .on_statement = [&checker](const Progress& at) { checker.at(at); }};
  (void)run_program(program, checker, check_options);
  report.problems = checker.problems();
  report.moves_planned = checker.moves_planned();
  report.pass_seconds = checker.seconds();
  if (options.dry_run || !report.problems.empty()) return report;

  SessionRequest request;
  request.device = device.value().name;
  for (std::size_t j = 0; j < planner.value().joint_count(); ++j)
    request.motor_ids.push_back(static_cast<std::int32_t>(j));
  request.mode = ControlMode::kPosition;
  request.on_timeout = Behavior::kDamping;  // robotd applies what the arm can (a position-only arm holds)
  request.timeout = options.session_timeout;
  request.on_release = Behavior::kKeep;
  request.policy_name = "rbtscript";
  detail::ArmSession arm(client, request);
  if (auto opened = arm.open(); !opened) return opened.error();
  // The arm may have moved since the dry run looked: plan the first move from where it is now.
  auto now = detail::measured_joints(client, device.value(), planner.value().joint_count());
  if (!now) return now.error();
  static const std::atomic<bool> kNeverStop{false};
  const std::atomic<bool>& stop = options.stop != nullptr ? *options.stop : kNeverStop;
  detail::DeviceExecutor executor(arm, planner.value(), io, stop, std::move(now).value());
  report.outcome = run_program(program, executor, RunOptions{options.loops, &stop, options.on_statement});
  return report;
}

}  // namespace robotd::rbtscript
