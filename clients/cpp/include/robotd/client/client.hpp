// The robotd C++ client: a thin typed layer over robotd's DDS topics and services. It holds
// no control logic: every decision (ownership, limits, timeouts) is robotd's.
//
//   auto client = robotd::Client::connect();
//   auto session = client.value().request_control({.device = "arm"});
//   session.value().send_positions({0.1F, 0, 0, 0, 0, 0});
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "robotd/client/options.hpp"
#include "robotd/client/policy_data_publisher.hpp"
#include "robotd/client/session.hpp"
#include "robotd/client/subscription.hpp"
#include "robotd/messages.hpp"
#include "robotd/result.hpp"

namespace robotd {

class Client {
 public:
  /// Joins robotd's DDS domain. Succeeds even if robotd is not running; calls then fail
  /// with ErrorCode::kNotAvailable after the service timeout. With DDS Security
  /// (options.security), a call or publish the identity's permissions do not grant fails at
  /// once with ErrorCode::kNotPermitted; a read-only identity still connects and subscribes.
  static Result<Client> connect(const ClientOptions& options = ClientOptions::from_environment());

  Client(Client&&) noexcept;
  Client& operator=(Client&&) noexcept;
  ~Client();

  const ClientOptions& options() const;

  // Services. Each waits at most options().service_timeout.
  Result<std::vector<DeviceInfo>> list_devices();
  /// Returns once robotd has granted the session and discovery has matched this client's command
  /// writer with a subscriber (robotd's command reader; at most the service timeout more), so that
  /// the first commands are not lost while the session's timeout runs.
  Result<Session> request_control(const SessionRequest& request);
  Result<ReleaseControlResponse> release_control(const std::string& uuid, Behavior release_mode);
  Result<GetAvailableMotorsResponse> available_motors(const std::string& device = "");
  /// Engages (latches) or resets the e-stop; "" = every device. The response names them.
  Result<EstopResponse> estop(const std::string& device = "", const std::string& reason = "");
  Result<EstopResponse> reset_estop(const std::string& device = "");
  /// Blocks until robotd has zeroed the motors (up to `timeout`, plus the service timeout).
  Result<void> reset_zero(const std::string& device, const std::vector<std::int32_t>& motor_ids,
                          std::chrono::milliseconds timeout = std::chrono::seconds(10));
  /// A device operation (driver op or robotd's recover / blackbox); returns its JSON result.
  /// Finding robotd takes at most the service timeout; the operation itself up to `timeout`.
  Result<std::string> device_call(const std::string& device, const std::string& op, const std::string& args_json = "{}",
                                  std::chrono::milliseconds timeout = std::chrono::seconds(10));

  // Topics. Callbacks run on the client's dispatch thread.
  Subscription on_joint_states(std::function<void(const JointState&)> callback);
  Subscription on_session_status(std::function<void(const SessionStatus&)> callback);
  Subscription on_device_status(std::function<void(const DeviceStatus&)> callback);
  Subscription on_imu(std::function<void(const Imu&)> callback);
  /// End-effector poses of devices whose driver computes one (frame_id = device).
  Subscription on_end_pose(std::function<void(const PoseStamped&)> callback);
  /// robotd's joystick source; `topic` is its config's joystick.topic (ROS name, default "joy").
  Subscription on_joy(std::function<void(const Joy&)> callback, const std::string& topic = "joy");
  /// What policies publish on /policy_data.
  Subscription on_policy_data(std::function<void(const PolicyData&)> callback);
  /// Every client's commands on /control_command, as robotd receives them (for recording; robotd
  /// alone decides what they do).
  Subscription on_control_commands(std::function<void(const ControlCommand&)> callback);

  /// The next JointState / DeviceStatus of `device` ("" = any), or a timeout error.
  Result<JointState> next_joint_state(const std::string& device, std::chrono::milliseconds timeout);
  Result<DeviceStatus> next_device_status(const std::string& device, std::chrono::milliseconds timeout);
  /// The current /session_status (transient local: available as soon as robotd is reachable).
  Result<SessionStatus> session_status(std::chrono::milliseconds timeout);

  /// Publishes a raw ControlCommand (no checks here; robotd checks everything).
  Result<void> publish(const ControlCommand& command);
  /// A writer for /policy_data. Create it once, before the first sample: DDS discovery of a
  /// new writer takes a moment, and samples written before a subscriber matched are not delivered.
  Result<PolicyDataPublisher> policy_data_publisher();

 private:
  explicit Client(std::shared_ptr<detail::ClientCore> core);
  std::shared_ptr<detail::ClientCore> core_;
};

}  // namespace robotd
