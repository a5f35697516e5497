// The /control_command reader: one thread takes every command sample and hands it to the
// command gate (command_gate), which checks, counts and writes it into the device's mailbox. A
// command under no active session's uuid is counted and dropped before that, as it arrives (a
// topic filter on Cyclone's receive thread): a flood of them takes no place in the reader's
// history, so it cannot push out a session's commands, and it never wakes the intake thread
// (docs/reliability.md, "Command flood").
#pragma once

#include <atomic>
#include <memory>
#include <vector>

#include "dds/command_gate.hpp"
#include "robotd/driver/named_thread.hpp"
#include "wire/entity.hpp"
#include "wire/topic_io.hpp"

namespace robotd::dds {

class CommandIntake {
 public:
  /// A command no device's counters can claim is counted in `surface`.
  CommandIntake(const wire::Participant& participant, std::vector<device::Device*> devices,
                service::SessionService& sessions, SurfaceCounterSet& surface);
  CommandIntake(const CommandIntake&) = delete;
  CommandIntake& operator=(const CommandIntake&) = delete;
  ~CommandIntake();

  /// Starts taking commands on a thread of its own, SCHED_FIFO at `fifo_priority` (0 = normal).
  Result<void> start(int fifo_priority);
  void stop();

  const service::CommandCounterSet& counters(std::size_t device) const { return gate_.counters(device); }

 private:
  void run();
  /// The topic filter: true for a command under an active session's uuid (CommandGate::admit).
  /// Runs on Cyclone's receive thread.
  static bool admits(const void* sample, void* intake);

  const wire::Participant& participant_;
  CommandGate gate_;

  std::unique_ptr<wire::TopicReader<ControlCommand>> reader_;
  wire::Entity waitset_;
  dds_entity_t stop_condition_ = 0;
  std::atomic<bool> stopping_{false};
  driver::NamedThread thread_;
};

}  // namespace robotd::dds
