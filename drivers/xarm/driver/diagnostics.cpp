// What `robotctl status` shows for an xarm device.
#include <cmath>

#include "driver/xarm_driver.hpp"

namespace robotd::xarm {

driver::Diagnostics XarmDriver::diagnostics() const {
  const LinkCounters counters = link_.counters();
  const LinkHealth health = link_.health();
  const ArmFeedback feedback = link_.feedback();
  driver::Diagnostics out{
      {"controller", params_.controller.to_string()},
      {"arm", version_.axes == 0 ? "(not read yet)"
                                 : std::string(params_.model.display) + ", " + std::to_string(version_.axes) +
                                       " axes, type " + std::to_string(version_.type) + ", SN " + version_.robot_sn},
      {"firmware", version_.firmware},
      {"link", !connected_.load() ? "not connected"
               : health.lost      ? health.reason.text.data()
                                  : "up"},
      {"report",
       std::string(report_kind_name(params_.report_kind)) + " report on port " + std::to_string(params_.report_port)},
      {"state", motion_state_text(feedback.state)},
      {"mode", mode_text(feedback.mode)},
      {"servo", std::string(servo_phase_name(feedback.phase)) + ", servo_j at " +
                    std::to_string(std::lround(params_.servo_rate_hz)) + " Hz"},
      {"controller_error", feedback.error_code == 0 ? "none" : controller_error_text(feedback.error_code)},
      {"controller_warning", feedback.warning_code == 0 ? "none" : controller_warning_text(feedback.warning_code)},
      {"queued_commands", std::to_string(feedback.cmd_num)},
      {"reports", std::to_string(counters.reports) + " (" + std::to_string(counters.bad_reports) + " unreadable)"},
      {"servo_frames", std::to_string(counters.servo_frames) + " (" + std::to_string(counters.clipped_frames) +
                           " limited to the joint speed, " + std::to_string(counters.skipped_frames) +
                           " skipped behind slow replies)"},
      {"servo_interval_max_us", std::to_string(counters.servo_interval_max_ns / 1000)},
      {"requests", std::to_string(counters.requests) + " (" + std::to_string(counters.timeouts) + " timed out)"},
      {"unmatched_replies", std::to_string(counters.unmatched)},
      {"error_polls", std::to_string(counters.error_polls)},
  };
  return out;
}

}  // namespace robotd::xarm
