#include "driver_loop.hpp"

#include <cmath>

namespace robotd::testing {

using namespace std::chrono_literals;
using driver::IoResult;

DriverLoop::DriverLoop(driver::Driver& driver, std::size_t joint_count) : driver_(driver) {
  command_.joint_count = joint_count;
  thread_ = std::thread([this] { run(); });
}

DriverLoop::~DriverLoop() {
  running_ = false;
  thread_.join();
}

void DriverLoop::set_command(const driver::CommandFrame& command) {
  const std::lock_guard lock(mutex_);
  command_ = command;
}

void DriverLoop::pause() {
  paused_ = true;
  while (!idle_) std::this_thread::sleep_for(1ms);
}

driver::Feedback DriverLoop::feedback() {
  const std::lock_guard lock(mutex_);
  return feedback_;
}

std::string DriverLoop::fault_text() {
  const std::lock_guard lock(mutex_);
  return fault_.text.data();
}

void DriverLoop::run() {
  auto next = std::chrono::steady_clock::now();
  while (running_) {
    next += 1ms;
    std::this_thread::sleep_until(next);
    if (paused_) {
      idle_ = true;
      continue;
    }
    idle_ = false;
    tick();
  }
}

void DriverLoop::tick() {
  driver::Feedback feedback;
  driver::FaultInfo fault;
  const IoResult read = driver_.read(feedback, fault);
  driver::CommandFrame command;
  {
    const std::lock_guard lock(mutex_);
    command = command_;
    if (read == IoResult::kOk) feedback_ = feedback;
    if (fault.code != 0) fault_ = fault;
  }
  last_read_ = read;
  if (read == IoResult::kDisconnected) return;
  command.tick_deadline_ns =
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count();
  driver::FaultInfo write_fault;
  last_write_ = driver_.write(command, write_fault);
  if (last_write_ == IoResult::kFault) write_faults_.fetch_add(1);
  if (write_fault.code != 0) {
    const std::lock_guard lock(mutex_);
    fault_ = write_fault;
  }
}

driver::CommandFrame position_frame(std::span<const double> q, bool owned, std::size_t joint_count) {
  driver::CommandFrame frame;
  frame.joint_count = joint_count == 0 ? q.size() : joint_count;
  for (std::size_t j = 0; j < q.size(); ++j) {
    frame.joints[j] = {.kind = driver::JointCommandKind::kPosition, .owned = owned, .position_rad = q[j]};
  }
  return frame;
}

bool joints_near(const driver::Feedback& feedback, std::span<const double> q, double tolerance) {
  for (std::size_t j = 0; j < q.size(); ++j) {
    if (std::fabs(feedback.joints[j].position_rad - q[j]) > tolerance) return false;
  }
  return true;
}

std::string diagnostic(const driver::Driver& driver, const std::string& key) {
  for (const auto& [name, value] : driver.diagnostics()) {
    if (name == key) return value;
  }
  return "(no " + key + ")";
}

std::vector<std::string> ops_needing_free_motors(const driver::DeviceDescription& description) {
  std::vector<std::string> names;
  for (const driver::OpDescription& op : description.ops) {
    if (op.needs_free_motors) names.push_back(op.name);
  }
  return names;
}

}  // namespace robotd::testing
