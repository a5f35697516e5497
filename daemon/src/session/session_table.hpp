// Who controls which motors. Pure bookkeeping (no threads, no DDS): the rules of
// DESIGN.md "Sessions" — per-motor ownership, overlap refused naming the holder, disjoint
// sessions side by side, a bounded number of session slots per device. The caller serialises
// access and tells the RT loop about grants and releases.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "control/command_validator.hpp"
#include "control/device_model.hpp"
#include "robotd/messages.hpp"
#include "robotd/result.hpp"

namespace robotd::session {

inline constexpr std::size_t kMaxSessionsPerDevice = 16;

struct SessionLimits {
  std::int32_t min_timeout_ms = 10;
  std::int32_t max_timeout_ms = 600'000;
};

struct SessionRecord {
  std::string uuid;        // the capability: known to robotd and the holder only
  std::string session_id;  // the public name of the session (session_ids.hpp)
  std::string node_name;
  std::size_t device_index = 0;
  std::string device;
  std::uint8_t slot = 0;
  std::uint32_t generation = 0;  // unique per device, tells a slot's successive sessions apart
  control::MotorSet motors;
  std::vector<std::int32_t> motor_ids;
  ControlMode mode = ControlMode::kPosition;
  Behavior requested_behavior = Behavior::kKeep;
  Behavior applied_behavior = Behavior::kKeep;
  std::int32_t timeout_ms = 0;
  std::vector<float> default_kp;  // parallel to motor_ids, or empty
  std::vector<float> default_kd;
  std::string policy_name;  // who commands, as the request named it ("" = not named)
  std::string policy_file_name;
  float min_command_success_rate = 0;  // closed loop: 0 = no minimum
  LowRateAction on_low_success_rate = LowRateAction::kWarn;
  std::int64_t granted_ns = 0;       // CLOCK_MONOTONIC
  std::int64_t granted_wall_ns = 0;  // CLOCK_REALTIME, for display
  std::int64_t last_command_ns = 0;  // CLOCK_MONOTONIC of the last accepted command
  std::uint64_t commands_accepted = 0;

  std::int64_t time_left_ms(std::int64_t now_ns) const;
};

class SessionTable {
 public:
  SessionTable(std::vector<const control::DeviceModel*> devices, SessionLimits limits);

  /// Device index for `name`; "" means the only device. Error text lists the devices.
  Result<std::size_t> resolve_device(std::string_view name) const;
  /// The same without the error text: allocates nothing.
  std::optional<std::size_t> find_device(std::string_view name) const;

  /// Grants `request` if it is valid and its motors are free, as a session with `uuid` and the
  /// public `session_id` (which no live session may have).
  Result<SessionRecord> grant(const RequestControlRequest& request, std::string uuid, std::string session_id,
                              std::int64_t now_ns, std::int64_t wall_ns);
  /// Removes the session `uuid` (explicit release). Only the uuid releases: a refusal says so
  /// when `uuid` is a live session's public id.
  Result<SessionRecord> release(std::string_view uuid);
  /// Removes the session in `slot` if it is still `generation` (the loop ended it).
  std::optional<SessionRecord> end(std::size_t device, std::uint8_t slot, std::uint32_t generation);

  SessionRecord* find(std::string_view uuid);
  /// The live session whose public id is `session_id`, if any.
  const SessionRecord* find_by_id(std::string_view session_id) const;
  bool any_active(std::size_t device) const;
  /// Who holds motors of `device` ("" if nobody), as a refusal names them.
  std::string holders(std::size_t device, std::int64_t now_ns) const;
  bool any_active() const;
  std::vector<std::int32_t> idle_motors(std::size_t device) const;
  /// Every session, ordered by device then grant time.
  std::vector<SessionRecord> sessions() const;
  const control::DeviceModel& device(std::size_t index) const { return *devices_[index]; }
  std::size_t device_count() const { return devices_.size(); }

 private:
  struct DeviceSessions {
    std::vector<std::optional<SessionRecord>> slots = std::vector<std::optional<SessionRecord>>(kMaxSessionsPerDevice);
    std::uint32_t next_generation = 1;
  };

  Result<void> check_request(const RequestControlRequest& request, const control::DeviceModel& model) const;
  std::string describe_holders(const DeviceSessions& sessions, const control::MotorSet& wanted,
                               std::int64_t now_ns) const;

  std::vector<const control::DeviceModel*> devices_;
  SessionLimits limits_;
  std::vector<DeviceSessions> sessions_;
};

}  // namespace robotd::session
