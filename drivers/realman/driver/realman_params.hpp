// The realman driver's "params" (docs/drivers/realman.md lists each key with its default).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "codec/realman_codec.hpp"
#include "robotd/driver/driver.hpp"
#include "robotd/result.hpp"
#include "robotd/transport/ip_socket.hpp"

namespace robotd::realman {

struct PushParams {
  bool enabled = true;        // feedback from the UDP push; false: poll get_current_arm_state
  std::uint16_t port = 8089;  // where robotd listens (0: any free port, told to the controller)
  /// The address the controller sends to and robotd binds; "" = this PC's address on the TCP
  /// connection to the controller.
  std::string ip;
  int cycle = 1;             // × 5 ms
  bool joint_speed = false;  // ask for joint_speed and use it instead of differentiating positions
  SpeedUnit speed_unit = SpeedUnit::kCentiDegreesPerSecond;
};

struct RealmanParams {
  transport::Endpoint controller{"192.168.1.18", 8080};
  ArmModel model;  // from "model"; the controller's Product_version must name the same model
  int connect_timeout_ms = 1000;
  int request_timeout_ms = 1000;
  double command_rate_hz = 200;  // movej_canfd frames per second
  PassThrough pass_through;
  PushParams push;
  int poll_period_ms = 20;  // without the push
  /// No push / poll reply for this long: the link is lost. Ten push cycles, as RealMan's ROS
  /// driver counts; below robotd's own feedback_timeout_ms (100 ms) so that a silent controller
  /// is reported as a lost link, which robotd reconnects by itself.
  int feedback_timeout_ms = 50;
  int io_priority = 0;  // SCHED_FIFO priority of the link thread; 0 = normal scheduling
  std::array<driver::JointLimits, kMaxDof> limits{};
};

Result<RealmanParams> parse_realman_params(const nlohmann::json& params);

}  // namespace robotd::realman
