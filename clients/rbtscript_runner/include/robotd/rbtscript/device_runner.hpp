// Running an RBTscript program on a device through robotd: first a dry run of the whole program
// (every move planned from where the one before it ends, on the device's limits and arm model;
// every Output and Gripper statement mapped to a device op), then, when nothing is wrong and a
// dry run was not all that was asked for, the run itself in a POSITION session on the arm's
// joints (ArmPlanner::joint_count: a PiPER's gripper joint is left to the Gripper statement).
// A stop (the flag), an e-stop, a fault or the end of the session ends the run with the arm held
// where it was.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "robotd/client/client.hpp"
#include "robotd/rbtscript/interpreter.hpp"
#include "robotd/rbtscript/program.hpp"
#include "robotd/result.hpp"

namespace robotd::rbtscript {

struct DeviceRunOptions {
  std::string device;  // "" = robotd's only device
  bool dry_run = false;
  /// Passes through Loop() at most (RunOptions::loops); unset: until stopped.
  std::optional<std::size_t> loops;
  const std::atomic<bool>* stop = nullptr;
  std::function<void(const Progress&)> on_statement;
  /// The session's timeout: robotd holds the arm (or damps it) this long after the last command
  /// if this process dies.
  std::chrono::milliseconds session_timeout{2000};
};

struct DeviceRunReport {
  std::string device;
  /// The dry run's findings, each with the statement's line and column; when there are any,
  /// nothing was sent to the device.
  std::vector<RunError> problems;
  std::size_t moves_planned = 0;  // by the dry run, on one pass
  double pass_seconds = 0;        // one pass's moves and delays, as planned
  /// Set when the program ran (no problems, not a dry run).
  std::optional<RunOutcome> outcome;
};

/// Fails (nothing moved) when robotd does not answer, the device is unknown or cannot be
/// planned for, or the session is refused. A program that fails while running (an e-stop, a
/// refused op) is not an error here: see DeviceRunReport::outcome.
Result<DeviceRunReport> run_on_device(Client& client, const Program& program, const DeviceRunOptions& options);

}  // namespace robotd::rbtscript
