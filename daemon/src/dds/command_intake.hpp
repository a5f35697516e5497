// The /control_command path: one thread takes every command sample, checks it against its
// session and the device (command_validator), counts the verdict and, if accepted, writes the
// targets into the device's command mailbox for the RT loop. Rejected commands never get
// further than this.
#pragma once

#include <atomic>
#include <memory>
#include <thread>
#include <vector>

#include "app/throttled_log.hpp"
#include "dds/surface_counters.hpp"
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
  /// Counts one rejected command and logs it (rate-limited); make_detail() says why and who sent
  /// it, and is called only when the line is logged.
  template <class MakeDetail>
  void reject(std::size_t device, control::Rejection reason, MakeDetail make_detail);
  /// The device whose counters take a command without a usable session: the one it names, or
  /// the only one; devices_.size() when there is none.
  std::size_t counting_device(const ControlCommand& command) const;

  const wire::Participant& participant_;
  std::vector<device::Device*> devices_;
  service::SessionService& sessions_;
  SurfaceCounterSet& surface_;
  std::vector<std::unique_ptr<service::CommandCounterSet>> counters_;
  std::vector<std::unique_ptr<device::CommandSnapshot>> working_;  // intake's copy of each mailbox
  std::vector<std::uint64_t> sequence_;
  control::ValidatedCommand validated_;

  std::unique_ptr<wire::TopicReader<ControlCommand>> reader_;
  wire::Entity waitset_;
  dds_entity_t stop_condition_ = 0;
  std::atomic<bool> stopping_{false};
  std::thread thread_;
  app::ThrottledLog log_;
};

}  // namespace robotd::dds
