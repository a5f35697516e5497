#include "recording/replay_plan.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "recording/record_codec.hpp"
#include "text_format.hpp"

namespace robotctl::recording {
namespace {

robotd::Error refused(const std::string& message) {
  return robotd::make_error(robotd::ErrorCode::kInvalidArgument, message);
}

std::string seconds_text(std::int64_t time_ns) { return "t=" + fixed(static_cast<double>(time_ns) * 1e-9, 3) + " s"; }

bool has_values(const robotd::Command& command) {
  return !command.positions.empty() || !command.velocities.empty() || !command.kp.empty() || !command.kd.empty() ||
         !command.torques.empty();
}

std::string command_at(const std::string& path, std::int64_t time_ns) {
  return path + ": the command at " + seconds_text(time_ns);
}

robotd::Error malformed_command(const std::string& path, std::int64_t time_ns) {
  return refused(command_at(path, time_ns) + " is malformed: the file is damaged");
}

robotd::Error not_one_position_per_motor(const std::string& path, std::int64_t time_ns, const std::string& device,
                                         const robotd::Command& command) {
  return refused(command_at(path, time_ns) + " for '" + device + "' has " + std::to_string(command.positions.size()) +
                 " positions for " + std::to_string(command.motor_ids.size()) +
                 " motor ids; replay needs one position per motor id, as robotd accepts them");
}

robotd::Error no_command_for_motor(const std::string& path, std::int32_t motor, const std::string& device) {
  return refused(path + " has no position command for motor " + std::to_string(motor) + " of '" + device +
                 "'; --motors may name only motors the recording commands");
}

std::string device_names(const std::vector<RecordedDevice>& devices) {
  std::string names;
  for (const auto& device : devices) names += (names.empty() ? "'" : ", '") + device.name + "'";
  return names.empty() ? "none" : names;
}

// Consecutive offending samples of one quantity on one motor: reported as one violation that
// gives the first offence, the worst and how long it lasted.
class ViolationRun {
 public:
  ViolationRun(std::string subject, std::string quantity, std::string limit_name, double limit, int decimals,
               std::string unit, std::string counted)
      : subject_(std::move(subject)),
        quantity_(std::move(quantity)),
        limit_name_(std::move(limit_name)),
        limit_(limit),
        decimals_(decimals),
        unit_(std::move(unit)),
        counted_(std::move(counted)) {}

  /// `excess` > 0 offends; the worst sample is the one with the largest excess.
  void sample(std::int64_t time_ns, double value, double excess, std::vector<std::string>& violations) {
    if (excess <= 0) {
      end(violations);
      return;
    }
    if (count_ == 0) {
      first_ns_ = time_ns;
      first_value_ = value;
    }
    if (count_ == 0 || excess > worst_excess_) {
      worst_excess_ = excess;
      worst_ns_ = time_ns;
      worst_value_ = value;
    }
    last_ns_ = time_ns;
    ++count_;
  }

  void end(std::vector<std::string>& violations) {
    if (count_ == 0) return;
    std::string text = subject_ + ": " + quantity_ + " " + value_text(first_value_) + " is beyond its " + limit_name_ +
                       " " + value_text(limit_) + " at " + seconds_text(first_ns_);
    if (count_ > 1) {
      text += " (worst " + value_text(worst_value_) + " at " + seconds_text(worst_ns_) + "; " + std::to_string(count_) +
              " " + counted_ + " until " + seconds_text(last_ns_) + ")";
    }
    violations.push_back(text);
    count_ = 0;
  }

 private:
  std::string value_text(double value) const { return fixed(value, decimals_) + " " + unit_; }

  std::string subject_, quantity_, limit_name_;
  double limit_;
  int decimals_;
  std::string unit_, counted_;
  std::size_t count_ = 0;
  std::int64_t first_ns_ = 0, worst_ns_ = 0, last_ns_ = 0;
  double first_value_ = 0, worst_value_ = 0, worst_excess_ = 0;
};

struct Sample {
  std::int64_t time_ns;  // recorded receive time, for the reports
  std::int64_t pace_ns;  // for velocities
  double position_rad;
};

std::vector<Sample> samples_of(const ReplayPlan& plan, std::int32_t motor) {
  std::vector<Sample> samples;
  for (const auto& step : plan.steps) {
    for (std::size_t i = 0; i < step.motor_ids.size(); ++i) {
      if (step.motor_ids[i] == motor) {
        samples.push_back({step.time_ns, step.pace_ns, static_cast<double>(step.positions[i])});
      }
    }
  }
  return samples;
}

void set_pace(ReplayPlan& plan) {
  const auto stamp_goes_back = [](const ReplayStep& a, const ReplayStep& b) { return b.stamp_ns < a.stamp_ns; };
  const bool stamped =
      std::all_of(plan.steps.begin(), plan.steps.end(), [](const ReplayStep& step) { return step.stamp_ns > 0; }) &&
      std::adjacent_find(plan.steps.begin(), plan.steps.end(), stamp_goes_back) == plan.steps.end();
  plan.pace_clock = stamped ? PaceClock::kSenderStamps : PaceClock::kReceiveTimes;
  const ReplayStep& first = plan.steps.front();
  for (auto& step : plan.steps) step.pace_ns = stamped ? step.stamp_ns - first.stamp_ns : step.time_ns - first.time_ns;
}

double limit_at(const std::vector<double>& limits, std::size_t joint, double otherwise) {
  return joint < limits.size() ? limits[joint] : otherwise;
}

void check_positions(const std::vector<Sample>& samples, const robotd::DeviceInfo& device, std::size_t joint,
                     const std::string& subject, std::vector<std::string>& violations) {
  const double min_rad = limit_at(device.position_min, joint, -std::numeric_limits<double>::infinity());
  const double max_rad = limit_at(device.position_max, joint, std::numeric_limits<double>::infinity());
  ViolationRun above(subject, "position", "maximum", max_rad, 3, "rad", "commands");
  ViolationRun below(subject, "position", "minimum", min_rad, 3, "rad", "commands");
  for (const auto& sample : samples) {
    above.sample(sample.time_ns, sample.position_rad, sample.position_rad - max_rad, violations);
    below.sample(sample.time_ns, sample.position_rad, min_rad - sample.position_rad, violations);
  }
  above.end(violations);
  below.end(violations);
}

// The peak speed at `speed`, over windows of at least kVelocityWindowNs of recorded time.
double check_velocities(const std::vector<Sample>& samples, double limit_rad_s, double speed,
                        const std::string& subject, std::vector<std::string>& violations) {
  ViolationRun faster(subject, "velocity", "velocity_max", limit_rad_s, 3, "rad/s", "intervals");
  double peak_rad_s = 0;
  std::size_t anchor = 0;
  for (std::size_t i = 1; i < samples.size(); ++i) {
    const std::int64_t elapsed_ns = samples[i].pace_ns - samples[anchor].pace_ns;
    if (elapsed_ns < kVelocityWindowNs) continue;
    const double replayed_s = static_cast<double>(elapsed_ns) * 1e-9 / speed;
    const double velocity = std::fabs(samples[i].position_rad - samples[anchor].position_rad) / replayed_s;
    peak_rad_s = std::max(peak_rad_s, velocity);
    if (limit_rad_s > 0) faster.sample(samples[anchor].time_ns, velocity, velocity - limit_rad_s, violations);
    anchor = i;
  }
  faster.end(violations);
  return peak_rad_s;
}

}  // namespace

double ReplayPlan::recorded_duration_s() const {
  return steps.empty() ? 0.0 : static_cast<double>(steps.back().pace_ns) * 1e-9;
}

robotd::Result<ReplayPlan> read_replay_plan(RecordingReader& reader, const std::string& device,
                                            const std::vector<std::int32_t>& motor_ids) {
  const std::string& path = reader.path();
  const auto& devices = reader.description().devices;
  const auto found =
      std::find_if(devices.begin(), devices.end(), [&](const RecordedDevice& d) { return d.name == device; });
  if (found == devices.end()) {
    return refused(path + " recorded no device '" + device + "' (it recorded " + device_names(devices) + ")");
  }
  const auto device_index = static_cast<std::uint16_t>(found - devices.begin());
  const std::set<std::int32_t> wanted(motor_ids.begin(), motor_ids.end());
  ReplayPlan plan;
  plan.device = *found;
  std::map<std::int32_t, double> first_rad;
  std::size_t torque_commands = 0;
  std::int64_t first_torque_ns = 0;
  while (auto record = reader.next()) {
    if (record->kind != static_cast<std::uint8_t>(RecordKind::kControlCommand)) continue;
    auto command = decode_control_command(record->payload);
    if (!command) return malformed_command(path, record->time_ns);
    if (command->device != device_index) continue;
    const robotd::Command& values = command->values;
    if (values.motor_ids.empty() && !has_values(values)) {
      ++plan.keepalives;
      continue;
    }
    if (!values.torques.empty()) {
      if (torque_commands++ == 0) first_torque_ns = record->time_ns;
      continue;
    }
    if (values.motor_ids.empty() || values.positions.size() != values.motor_ids.size()) {
      return not_one_position_per_motor(path, record->time_ns, device, values);
    }
    ReplayStep step{record->time_ns, command->stamp_ns, {}, {}, 0};
    for (std::size_t i = 0; i < values.motor_ids.size(); ++i) {
      const std::int32_t id = values.motor_ids[i];
      if (!wanted.empty() && wanted.count(id) == 0) continue;
      step.motor_ids.push_back(id);
      step.positions.push_back(values.positions[i]);
      first_rad.try_emplace(id, values.positions[i]);
    }
    if (!step.motor_ids.empty()) plan.steps.push_back(std::move(step));
  }
  if (torque_commands > 0) {
    return refused(path + ": " + std::to_string(torque_commands) + " commands for '" + device +
                   "' carry torques (torque or mixed mode), the first at " + seconds_text(first_torque_ns) +
                   "; replay streams position commands only, since what a torque does depends on the load");
  }
  for (const std::int32_t id : wanted) {
    if (first_rad.count(id) == 0) return no_command_for_motor(path, id, device);
  }
  if (plan.steps.empty()) {
    return refused(path + " has no position commands for '" + device +
                   "'; expected a recording with control_command made while a session moved it");
  }
  set_pace(plan);
  for (const auto& [id, position] : first_rad) {
    plan.motor_ids.push_back(id);
    plan.start_rad.push_back(position);
  }
  plan.ending = reader.ending_text();
  return plan;
}

ReplayCheck check_replay(const ReplayPlan& plan, const robotd::DeviceInfo& current, double speed) {
  ReplayCheck check;
  const std::size_t joints = current.joint_names.size();
  const auto& recorded_names = plan.device.joint_names;
  if (recorded_names.size() != joints) {
    check.violations.push_back("'" + current.name + "' has " + std::to_string(joints) +
                               " joints on robotd; the recording's had " + std::to_string(recorded_names.size()));
  }
  for (std::size_t j = 0; j < std::min(joints, recorded_names.size()); ++j) {
    if (recorded_names[j] != current.joint_names[j]) {
      check.violations.push_back("joint " + std::to_string(j) + " is '" + recorded_names[j] +
                                 "' in the recording and '" + current.joint_names[j] + "' on robotd");
    }
  }
  check.duration_s = plan.recorded_duration_s() / speed;
  for (const std::int32_t motor : plan.motor_ids) {
    const auto joint = static_cast<std::size_t>(motor);
    MotorReplay replay{motor, "?", 0, 0, 0, 0};
    if (motor < 0 || joint >= joints) {
      check.violations.push_back("motor " + std::to_string(motor) + " does not exist on '" + current.name +
                                 "' (it has motors 0.." + std::to_string(static_cast<int>(joints) - 1) + ")");
      check.motors.push_back(replay);
      continue;
    }
    replay.joint = current.joint_names[joint];
    const std::string subject = "motor " + std::to_string(motor) + " (" + replay.joint + ")";
    const std::vector<Sample> samples = samples_of(plan, motor);
    const auto [lowest, highest] =
        std::minmax_element(samples.begin(), samples.end(),
                            [](const Sample& a, const Sample& b) { return a.position_rad < b.position_rad; });
    replay.min_rad = lowest->position_rad;
    replay.max_rad = highest->position_rad;
    replay.velocity_limit_rad_s = limit_at(current.velocity_max, joint, 0.0);
    check_positions(samples, current, joint, subject, check.violations);
    replay.peak_velocity_rad_s =
        check_velocities(samples, replay.velocity_limit_rad_s, speed, subject, check.violations);
    check.motors.push_back(replay);
  }
  return check;
}

}  // namespace robotctl::recording
