// The /control_command path: one thread takes every command sample, checks it against its
// session and the device (command_validator), counts the verdict and, if accepted, writes the
// targets into the device's command mailbox for the RT loop. Rejected commands never get
// further than this. A command under no active session's uuid is counted and dropped before
// that, as it arrives (a topic filter on Cyclone's receive thread): a flood of them takes no
// place in the reader's history, so it cannot push out a session's commands, and it never wakes
// the intake thread (docs/reliability.md, "Command flood").
#pragma once

#include <array>
#include <atomic>
#include <memory>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "app/throttled_log.hpp"
#include "dds/surface_counters.hpp"
#include "device/command_mailbox.hpp"
#include "device/device.hpp"
#include "service/command_counters.hpp"
#include "service/session_service.hpp"
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

  Result<void> start();
  void stop();

  const service::CommandCounterSet& counters(std::size_t device) const { return *counters_[device]; }

  /// Handles one command as if it had arrived now (the thread's work; public for tests).
  void handle(const ControlCommand& command, std::int64_t now_ns);

 private:
  void run();
  /// The topic filter: true for a command under an active session's uuid; any other is
  /// rejected here. Runs on Cyclone's receive thread.
  static bool admits(const void* sample, void* intake);
  /// Counts a command under no active session against the device it names, or the only device;
  /// with neither, in the surface's unattributed count.
  void reject_unknown_session(std::string_view uuid, std::string_view device_name);
  /// Counts one rejected command and logs it (rate-limited); make_detail() says why and who sent
  /// it, and is called only when the line is logged.
  template <class MakeDetail>
  void reject(std::size_t device, control::Rejection reason, MakeDetail make_detail);

  const wire::Participant& participant_;
  std::vector<device::Device*> devices_;
  service::SessionService& sessions_;
  SurfaceCounterSet& surface_;
  std::vector<std::unique_ptr<service::CommandCounterSet>> counters_;
  std::vector<std::array<std::string, control::kRejectionCount>> log_keys_;  // "<device>/<reason>"
  std::vector<std::unique_ptr<device::CommandMailbox>> mailboxes_;
  control::ValidatedCommand validated_;

  std::unique_ptr<wire::TopicReader<ControlCommand>> reader_;
  wire::Entity waitset_;
  dds_entity_t stop_condition_ = 0;
  std::atomic<bool> stopping_{false};
  std::thread thread_;
  app::ThrottledLog log_;
};

}  // namespace robotd::dds
