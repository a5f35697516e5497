#include "replay_report.hpp"

#include "text_format.hpp"
#include "text_table.hpp"

namespace robotctl {

std::string replay_report(const std::string& path, const recording::Description& description,
                          const recording::ReplayPlan& plan, const recording::ReplayCheck& check,
                          const std::string& device, double speed) {
  std::string text =
      path + ": recorded " + recording::utc_time_text(description.start_time_ns) + " by robotd " +
      (description.robotd_version.empty() ? "?" : description.robotd_version) + "; " +
      std::to_string(plan.steps.size()) + " position commands for motors " + id_ranges(plan.motor_ids) + " of '" +
      device + "' over " + fixed(plan.recorded_duration_s(), 2) + " s, paced by " +
      (plan.pace_clock == recording::PaceClock::kSenderStamps ? "the senders' stamps" : "the receive times");
  if (plan.keepalives > 0) text += " (and " + std::to_string(plan.keepalives) + " keepalives, not replayed)";
  text += "\nreplay at speed " + fixed(speed, 2) + ": " + fixed(check.duration_s, 2) + " s\n";
  TextTable table({"MOTOR", "JOINT", "RECORDED rad", "PEAK VELOCITY rad/s", "VELOCITY MAX rad/s"});
  for (const auto& motor : check.motors) {
    table.add_row({std::to_string(motor.motor), motor.joint, fixed(motor.min_rad, 3) + ".." + fixed(motor.max_rad, 3),
                   fixed(motor.peak_velocity_rad_s, 2),
                   motor.velocity_limit_rad_s > 0 ? fixed(motor.velocity_limit_rad_s, 2) : "-"});
  }
  text += table.render();
  if (check.violations.empty()) return text + "check: every command is within the current limits of '" + device + "'\n";
  text += std::to_string(check.violations.size()) + " violation(s) of the current limits of '" + device +
          "' (times are recorded times):\n";
  for (const auto& violation : check.violations) text += "  " + violation + "\n";
  return text;
}

}  // namespace robotctl
