// The xarm driver's "params" (docs/drivers/xarm.md lists each key with its default).
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "codec/xarm_codec.hpp"
#include "robotd/driver/driver.hpp"
#include "robotd/result.hpp"
#include "robotd/transport/ip_socket.hpp"

namespace robotd::xarm {

/// When robotd enables the motors (motion_en 8 1).
enum class EnablePolicy : std::uint8_t {
  kOnSession,  // when a session first streams to the arm (default)
  kOnConnect,  // at connect, and again after recover
  kManual,     // only through the motion_en op
};

struct XarmParams {
  ArmModel model;  // from "model"; the controller's get_version must report the same arm
  transport::Endpoint controller{"192.168.1.185", 502};
  ReportKind report_kind = ReportKind::kReal;
  std::uint16_t report_port = 30003;
  int connect_timeout_ms = 1000;
  int request_timeout_ms = 2000;  // the SDKs' reply timeout
  double servo_rate_hz = 250;     // servo_j frames per second; the control box accepts at most 250
  EnablePolicy enable = EnablePolicy::kOnSession;
  /// No report for this long: the link is lost. Below robotd's feedback_timeout_ms (100 ms) so a
  /// silent controller is reported as a lost link, which robotd reconnects by itself.
  int report_timeout_ms = 50;
  int error_poll_ms = 100;  // get_err_code while the report carries no codes
  int io_priority = 0;      // SCHED_FIFO priority of the link thread; 0 = normal scheduling
  std::array<driver::JointLimits, kMaxDof> limits{};
};

Result<XarmParams> parse_xarm_params(const nlohmann::json& params);

}  // namespace robotd::xarm
