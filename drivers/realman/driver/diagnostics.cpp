// What `robotctl status` shows for a realman device.
#include <cmath>

#include "driver/realman_driver.hpp"

namespace robotd::realman {

driver::Diagnostics RealmanDriver::diagnostics() const {
  const LinkCounters counters = link_.counters();
  const LinkHealth health = link_.health();
  const ArmFeedback feedback = link_.feedback();
  driver::Diagnostics out{
      {"controller", params_.controller.to_string()},
      {"product", product_version_.empty() ? "(not read yet)" : product_version_},
      {"controller_version", controller_version_},
      {"link", !connected_.load() ? "not connected"
               : health.lost      ? health.reason.text.data()
                                  : "up"},
      {"feedback", params_.push.enabled
                       ? "UDP push to " + link_.push_endpoint().to_string() + " every " +
                             std::to_string(5 * params_.push.cycle) + " ms"
                       : "polling get_current_arm_state every " + std::to_string(params_.poll_period_ms) + " ms"},
      {"stream", "movej_canfd at " + std::to_string(std::lround(params_.command_rate_hz)) + " Hz, " +
                     (params_.pass_through.follow ? "high follow" : "low follow")},
      {"arm_status", link_.last_arm_status()},
      {"controller_error", feedback.fault.code == 0 ? "none" : feedback.fault.text.data()},
      {"pushes", std::to_string(counters.pushes) + " (" + std::to_string(counters.bad_pushes) + " unreadable)"},
      {"polls", std::to_string(counters.polls)},
      {"stream_frames", std::to_string(counters.stream_frames) + " (" + std::to_string(counters.clipped_frames) +
                            " limited to the pass-through step)"},
      {"stream_interval_max_us", std::to_string(counters.stream_interval_max_ns / 1000)},
      {"requests", std::to_string(counters.requests)},
      {"unmatched_messages", std::to_string(counters.unmatched)},
      {"unreadable_lines", std::to_string(counters.bad_lines)},
  };
  return out;
}

}  // namespace robotd::realman
