// What happens to a /control_command once it has arrived: checked against its session and the
// device (command_admission, command_validator), counted, and if accepted written into the
// device's command mailbox for the RT loop. Rejected commands never get further than this.
// No DDS here: the intake (command_intake) feeds it, and tests can drive it directly.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "app/throttled_log.hpp"
#include "dds/surface_counters.hpp"
#include "device/command_mailbox.hpp"
#include "device/device.hpp"
#include "service/command_counters.hpp"
#include "service/session_service.hpp"

namespace robotd::dds {

class CommandGate {
 public:
  /// A command no device's counters can claim is counted in `surface`.
  CommandGate(std::vector<device::Device*> devices, service::SessionService& sessions, SurfaceCounterSet& surface);

  const service::CommandCounterSet& counters(std::size_t device) const { return *counters_[device]; }

  /// Whether a command under `uuid` can belong to an active session; one that cannot is counted
  /// and rejected here. Locks nothing and builds no text unless it logs: safe on Cyclone's
  /// receive thread for every sample.
  bool admit(std::string_view uuid, std::string_view device_name);

  /// Checks one command that arrived at `now_ns` and writes it into its device's mailbox if it
  /// passes. Returns what it wrote (null if it rejected the command).
  const control::ValidatedCommand* handle(const ControlCommand& command, std::int64_t now_ns);

 private:
  /// Counts a command under no active session against the device it names, or the only device;
  /// with neither, in the surface's unattributed count.
  void reject_unknown_session(std::string_view uuid, std::string_view device_name);
  /// Counts one rejected command and logs it (rate-limited); make_detail() says why and who sent
  /// it, and is called only when the line is logged.
  template <class MakeDetail>
  void reject(std::size_t device, control::Rejection reason, MakeDetail make_detail);

  std::vector<device::Device*> devices_;
  service::SessionService& sessions_;
  SurfaceCounterSet& surface_;
  std::vector<std::unique_ptr<service::CommandCounterSet>> counters_;
  std::vector<std::array<std::string, control::kRejectionCount>> log_keys_;  // "<device>/<reason>"
  std::vector<std::unique_ptr<device::CommandMailbox>> mailboxes_;
  control::ValidatedCommand validated_;
  app::ThrottledLog log_;
};

}  // namespace robotd::dds
