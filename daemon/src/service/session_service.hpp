// The session side of robotd: request_control, release_control, get_available_motors, the
// ownership check for every command, and sessions the loop ended. Serialises access to the
// session table and tells each device's loop about grants and releases. Never called on an
// RT thread.
#pragma once

#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "control/command_validator.hpp"
#include "device/device.hpp"
#include "robotd/messages.hpp"
#include "rt/monotonic_clock.hpp"
#include "service/device_observer.hpp"
#include "session/active_uuids.hpp"
#include "session/session_table.hpp"

namespace robotd::service {

class SessionService {
 public:
  /// `on_change` is called (outside any lock) whenever the set of sessions changes.
  /// The clock stamps grants (CLOCK_MONOTONIC, the loops' clock); a test that ticks a loop at
  /// simulated times passes its own.
  using Clock = std::int64_t (*)() noexcept;
  SessionService(std::vector<device::Device*> devices, session::SessionLimits limits, std::function<void()> on_change,
                 Clock monotonic_now_ns = &rt::monotonic_now_ns);

  RequestControlResponse request_control(const RequestControlRequest& request);
  ReleaseControlResponse release_control(const ReleaseControlRequest& request);
  GetAvailableMotorsResponse available_motors(const GetAvailableMotorsRequest& request);

  struct Authorization {
    std::string session_id;  // for log lines: never the uuid
    std::size_t device = 0;
    std::uint8_t slot = 0;
    std::uint32_t generation = 0;
    ControlMode mode = ControlMode::kPosition;
    control::MotorSet motors;
  };
  /// The session a command's uuid names, if it is active.
  std::optional<Authorization> authorize(std::string_view uuid);
  /// Whether `text` is a live session's public id (someone used it where a uuid belongs).
  bool is_session_id(std::string_view text) const;
  /// Records an accepted command: renews the session's timeout clock for time_left.
  void note_command(std::string_view uuid, std::int64_t now_ns);
  /// Whether `uuid` names an active session. Never waits on the session lock, allocates nothing:
  /// safe on Cyclone's receive thread for every command.
  bool is_active(std::string_view uuid) const { return active_.contains(uuid); }

  /// The loop ended a session (timeout, release, shutdown). Returns it if it was still known.
  std::optional<session::SessionRecord> session_ended(std::size_t device, std::uint8_t slot, std::uint32_t generation);

  bool any_active(std::size_t device) const;

  /// Keeps new sessions off `device` while `operation` (recover, reset_zero) runs on it, so no
  /// client takes motors that maintenance is about to move or re-zero. Refused while a session
  /// holds any of its motors (the error names the holders) or another operation has it.
  Result<void> reserve_for_maintenance(std::size_t device, const std::string& operation);
  void end_maintenance(std::size_t device);
  /// The operation that holds `device` for maintenance, "" if none.
  std::string maintenance_operation(std::size_t device) const;
  Result<std::size_t> resolve_device(std::string_view name) const;
  /// The device `name` names ("": the only one), if any. The devices never change: no lock, no
  /// allocation.
  std::optional<std::size_t> find_device(std::string_view name) const { return table_.find_device(name); }
  /// Where status() reads each closed-loop session's answers: the device's loop state (its state
  /// publisher, created after this service). Set once before any status() call.
  void read_answers_from(std::vector<DeviceObserver*> observers) { observers_ = std::move(observers); }
  SessionStatus status(std::int64_t now_ns) const;

 private:
  std::vector<device::Device*> devices_;
  std::vector<DeviceObserver*> observers_;
  mutable std::mutex mutex_;
  session::SessionTable table_;
  session::ActiveUuids active_;  // the uuids in table_, for is_active()
  Clock monotonic_now_ns_;
  std::vector<std::string> maintenance_;  // per device: the operation that holds it, "" = none
  std::function<void()> on_change_;
};

}  // namespace robotd::service
