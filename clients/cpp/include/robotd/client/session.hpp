// An exclusive control session on some motors of one device. While it lives, only its
// commands move those motors. Destroying it releases them (with `release_behavior`).
// If it sends nothing for its timeout, robotd applies its fallback and ends it.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "robotd/messages.hpp"
#include "robotd/result.hpp"

namespace robotd {

namespace detail {
class ClientCore;
}

struct SessionRequest {
  std::string device;                   // "" = the daemon's only device
  std::vector<std::int32_t> motor_ids;  // empty = every motor of the device
  ControlMode mode = ControlMode::kPosition;
  Behavior on_timeout = Behavior::kDamping;
  std::chrono::milliseconds timeout{1000};
  std::vector<float> default_kp;  // empty, or one per motor
  std::vector<float> default_kd;
  Behavior on_release = Behavior::kKeep;  // what the destructor's release asks for
  // Who will command, shown to everyone in /session_status (e.g. "walk", "walk_v3.onnx").
  std::string policy_name;
  std::string policy_file_name;
};

/// One command. Arrays are parallel to motor_ids (empty motor_ids = the session's motors in
/// order). Which arrays are required depends on the session's mode (see docs/design.md, "Sessions").
struct Command {
  std::vector<std::int32_t> motor_ids;
  std::vector<float> positions;   // rad
  std::vector<float> velocities;  // rad/s
  std::vector<float> kp;
  std::vector<float> kd;
  std::vector<float> torques;  // N·m

  bool operator==(const Command&) const = default;
};

class Session {
 public:
  Session(Session&& other) noexcept;
  Session& operator=(Session&& other) noexcept;
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  ~Session();

  /// The session's capability: it commands and releases the session. Keep it to this client;
  /// robotd shows others only session_id().
  const std::string& uuid() const { return uuid_; }
  /// The session's public id, as /session_status (SessionInfo.uuid, active_uuids), refusals and
  /// robotd's log name it.
  const std::string& session_id() const { return session_id_; }
  /// The device robotd granted (also when the request named none).
  const std::string& device() const { return device_; }
  const std::vector<std::int32_t>& motor_ids() const { return motor_ids_; }
  ControlMode mode() const { return mode_; }
  /// What robotd will really do on timeout (a position-only arm cannot damp).
  Behavior applied_timeout_behavior() const { return applied_behavior_; }
  bool active() const { return core_ != nullptr; }

  /// Publishes a command for this session. Fails only on malformed input or a DDS error;
  /// robotd's verdict on the command shows in /device_status (robotctl status).
  Result<void> command(const Command& command);
  /// Positions for every motor of the session, in motor_ids() order.
  Result<void> send_positions(const std::vector<float>& positions_rad);
  /// Renews the session without moving anything.
  Result<void> keepalive();
  /// Time until robotd's timeout fires, counted from the last command this object sent.
  std::chrono::milliseconds time_left() const;
  /// Releases the motors now; the session is inactive afterwards.
  Result<ReleaseControlResponse> release(Behavior release_mode);

 private:
  friend class Client;
  Session(std::shared_ptr<detail::ClientCore> core, RequestControlResponse granted, const SessionRequest& request);

  std::shared_ptr<detail::ClientCore> core_;
  std::string uuid_;
  std::string session_id_;
  std::string device_;
  std::vector<std::int32_t> motor_ids_;
  ControlMode mode_ = ControlMode::kPosition;
  Behavior applied_behavior_ = Behavior::kKeep;
  Behavior release_behavior_ = Behavior::kKeep;
  std::chrono::milliseconds timeout_{0};
  std::chrono::steady_clock::time_point last_sent_;
};

}  // namespace robotd
