#include "robotd/rbtscript/device_runner.hpp"

#include <cstddef>
#include <cstdint>
#include <utility>

#include "arm_session.hpp"
#include "checking_executor.hpp"
#include "device_executor.hpp"
#include "robotd/motion/device_io.hpp"
#include "robotd/rbtscript/arm_planner.hpp"

namespace robotd::rbtscript {
namespace {

constexpr std::chrono::milliseconds kJointStateWait{2000};

Result<DeviceInfo> find_device(Client& client, const std::string& name) {
  auto devices = client.list_devices();
  if (!devices) return devices.error();
  std::string names;
  for (const DeviceInfo& device : devices.value()) {
    if (device.name == name || (name.empty() && devices.value().size() == 1)) return device;
    names += (names.empty() ? "" : ", ") + device.name;
  }
  if (name.empty()) return Error{ErrorCode::kInvalidArgument, "robotd runs several devices (" + names + "); name one"};
  return Error{ErrorCode::kInvalidArgument, "robotd has no device '" + name + "' (it has: " + names + ")"};
}

// The arm's joints (the planner's) where the device reports them.
Result<motion::Joints> measured_joints(Client& client, const DeviceInfo& device, std::size_t arm_joints) {
  auto state = client.next_joint_state(device.name, kJointStateWait);
  if (!state) return state.error();
  if (state.value().position.size() != device.joint_names.size()) {
    return Error{ErrorCode::kRefused, "device '" + device.name + "' published " +
                                          std::to_string(state.value().position.size()) + " joint positions for " +
                                          std::to_string(device.joint_names.size()) + " joints"};
  }
  motion::Joints joints = std::move(state).value().position;
  joints.resize(arm_joints);
  return joints;
}

}  // namespace

Result<DeviceRunReport> run_on_device(Client& client, const Program& program, const DeviceRunOptions& options) {
  auto device = find_device(client, options.device);
  if (!device) return device.error();
  auto planner = ArmPlanner::for_device(device.value());
  if (!planner) return planner.error();
  const motion::DeviceIo io(device.value());
  auto start = measured_joints(client, device.value(), planner.value().joint_count());
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
  auto now = measured_joints(client, device.value(), planner.value().joint_count());
  if (!now) return now.error();
  static const std::atomic<bool> kNeverStop{false};
  const std::atomic<bool>& stop = options.stop != nullptr ? *options.stop : kNeverStop;
  detail::DeviceExecutor executor(arm, planner.value(), io, stop, std::move(now).value());
  report.outcome = run_program(program, executor, RunOptions{options.loops, &stop, options.on_statement});
  return report;
}

}  // namespace robotd::rbtscript
