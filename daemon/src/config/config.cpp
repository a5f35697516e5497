#include "config/config.hpp"

#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <unistd.h>

#include "robotd/driver/json_reader.hpp"
#include "wire/dds_security.hpp"

namespace robotd::config {
namespace {

Behavior behavior_or(JsonReader& reader, std::string_view key, Behavior fallback) {
  const auto text = reader.string(key, {"KEEP", "DAMPING", "ZERO_TORQUE"});
  return text ? *parse_behavior(*text) : fallback;
}

bool is_identifier(const std::string& text) {
  static const std::regex identifier("[A-Za-z][A-Za-z0-9_]{0,62}");
  return std::regex_match(text, identifier);
}

void read_daemon(JsonReader& reader, DaemonConfig& daemon) {
  daemon.node_name = reader.string_or("node_name", daemon.node_name);
  daemon.log_level =
      reader.string_or("log_level", daemon.log_level, {"trace", "debug", "info", "warn", "error", "critical", "off"});
  daemon.plugin_dirs = reader.string_array("plugin_dirs").value_or(std::vector<std::string>{});
  daemon.status_rate_hz = static_cast<int>(reader.integer_or("status_rate_hz", daemon.status_rate_hz, 1, 100));
  daemon.session_status_period_ms =
      static_cast<int>(reader.integer_or("session_status_period_ms", daemon.session_status_period_ms, 100, 60'000));
  daemon.min_session_timeout_ms =
      static_cast<std::int32_t>(reader.integer_or("min_session_timeout_ms", daemon.min_session_timeout_ms, 1, 60'000));
  daemon.max_session_timeout_ms = static_cast<std::int32_t>(
      reader.integer_or("max_session_timeout_ms", daemon.max_session_timeout_ms, 10, 86'400'000));
  daemon.stats_window_ticks =
      static_cast<int>(reader.integer_or("stats_window_ticks", daemon.stats_window_ticks, 100, 1'000'000));
  daemon.cpu_dma_latency_us =
      static_cast<std::int32_t>(reader.integer_or("cpu_dma_latency_us", daemon.cpu_dma_latency_us, -1, 1'000'000));
  daemon.yesense_imu_topics = reader.boolean_or("yesense_imu_topics", daemon.yesense_imu_topics);
  daemon.loop_io_priority = static_cast<int>(reader.integer_or("loop_io_priority", daemon.loop_io_priority, 0, 98));
  if (daemon.min_session_timeout_ms > daemon.max_session_timeout_ms) {
    reader.error("min_session_timeout_ms", "must not exceed max_session_timeout_ms");
  }
  reader.finish();
}

// Present = DDS Security on. Each file is checked here, so robotd refuses to start naming the
// file at fault rather than Cyclone failing later without naming any.
void read_dds_security(JsonReader& reader, DdsSecurityFiles& files) {
  for (const auto& field : wire::kSecurityFileFields) files.*field.path = reader.string_or(field.name, "");
  for (const auto& problem : wire::find_security_file_problems(files)) reader.error(problem.field, problem.message);
  reader.finish();
}

void read_dds(JsonReader& reader, wire::DdsSettings& dds) {
  dds.domain_id = static_cast<int>(reader.integer_or("domain_id", dds.domain_id, 0, 230));
  dds.network_interface = reader.string_or("interface", dds.network_interface);
  dds.multicast = reader.boolean_or("multicast", dds.multicast);
  if (auto peers = reader.string_array("peers")) dds.peers = *peers;
  dds.max_participant_index =
      static_cast<int>(reader.integer_or("max_participant_index", dds.max_participant_index, 1, 1000));
  dds.receive_thread_priority =
      static_cast<int>(reader.integer_or("receive_thread_priority", dds.receive_thread_priority, 0, 98));
  dds.cyclonedds_xml = reader.string_or("cyclonedds_xml", "");
  if (auto security = reader.object("security")) read_dds_security(*security, dds.security);
  if (reader.has("security") && !dds.cyclonedds_xml.empty()) {
    reader.error("security", "cannot be combined with cyclonedds_xml (put a <Security> section into that XML instead)");
  }
  if (!dds.multicast && dds.peers.empty() && dds.cyclonedds_xml.empty()) {
    reader.error("peers", "must list at least one peer when multicast is false (use [\"127.0.0.1\"] for one host)");
  }
  reader.finish();
}

JointLimitOverride read_limit_override(const std::string& joint, JsonReader& reader) {
  constexpr NumberRange kPositive{1e-9, 1e9};
  JointLimitOverride limits;
  limits.joint = joint;
  limits.path = reader.path();
  limits.position_min_rad = reader.number("position_min_rad");
  limits.position_max_rad = reader.number("position_max_rad");
  limits.velocity_max_rad_s = reader.number("velocity_max_rad_s", kPositive);
  limits.acceleration_max_rad_s2 = reader.number("acceleration_max_rad_s2", kPositive);
  limits.effort_max_nm = reader.number("effort_max_nm", kPositive);
  limits.kp_max = reader.number("kp_max", {0, 1e9});
  limits.kd_max = reader.number("kd_max", {0, 1e9});
  if (limits.position_min_rad && limits.position_max_rad && *limits.position_min_rad >= *limits.position_max_rad) {
    reader.error("position_min_rad", "must be below position_max_rad");
  }
  reader.finish();
  return limits;
}

DeviceConfig read_device(JsonReader& reader, int cpu_count) {
  DeviceConfig device;
  device.path = reader.path();
  reader.require("name", "a device name ([A-Za-z][A-Za-z0-9_]*)");
  reader.require("driver", "a driver plugin name, e.g. \"sim\"");
  device.name = reader.string_or("name", "");
  if (!device.name.empty() && !is_identifier(device.name)) {
    reader.error("name",
                 "expected a name of letters, digits and _ starting with a letter, got \"" + device.name + "\"");
  }
  device.driver = reader.string_or("driver", "");
  if (!device.driver.empty() && !is_identifier(device.driver)) {
    reader.error("driver", "expected a plugin name of letters, digits and _, got \"" + device.driver + "\"");
  }
  device.required = reader.boolean_or("required", device.required);
  device.rate_hz = static_cast<int>(reader.integer_or("rate_hz", device.rate_hz, 1, 10'000));
  device.rt_priority = static_cast<int>(reader.integer_or("rt_priority", device.rt_priority, 1, 99));
  device.cpu = static_cast<int>(reader.integer_or("cpu", device.cpu, -1, cpu_count - 1));
  const auto realtime = reader.string_or("realtime", "prefer", {"require", "prefer", "off"});
  device.realtime = realtime == "require" ? rt::RealtimePolicy::kRequire
                    : realtime == "off"   ? rt::RealtimePolicy::kOff
                                          : rt::RealtimePolicy::kPrefer;
  device.limit_policy = reader.string_or("limit_policy", "reject", {"reject", "clamp"}) == "clamp"
                            ? control::LimitPolicy::kClamp
                            : control::LimitPolicy::kReject;
  for (auto& [joint, limits] : reader.object_map("joint_limits")) {
    device.joint_limits.push_back(read_limit_override(joint, limits));
  }
  device.safe_behavior = behavior_or(reader, "safe_behavior", device.safe_behavior);
  device.shutdown_behavior = behavior_or(reader, "shutdown_behavior", device.shutdown_behavior);
  device.shutdown_ms = static_cast<int>(reader.integer_or("shutdown_ms", device.shutdown_ms, 0, 10'000));
  device.feedback_timeout_ms =
      static_cast<int>(reader.integer_or("feedback_timeout_ms", device.feedback_timeout_ms, 1, 60'000));
  device.reconnect_interval_ms =
      static_cast<int>(reader.integer_or("reconnect_interval_ms", device.reconnect_interval_ms, 0, 600'000));
  device.reconnect_max_interval_ms =
      static_cast<int>(reader.integer_or("reconnect_max_interval_ms", device.reconnect_max_interval_ms, 0, 3'600'000));
  device.joint_state_rate_hz =
      static_cast<int>(reader.integer_or("joint_state_rate_hz", device.joint_state_rate_hz, 0, 10'000));
  device.end_pose_rate_hz = static_cast<int>(reader.integer_or("end_pose_rate_hz", device.end_pose_rate_hz, 0, 1000));
  if (device.joint_state_rate_hz > device.rate_hz) {
    reader.error("joint_state_rate_hz", "must not exceed rate_hz (" + std::to_string(device.rate_hz) + ")");
  }
  // Validated by the driver once its plugin is loaded; its errors then name devices[i].params.*.
  if (auto params = reader.raw("params")) {
    if (params->is_object()) {
      device.params = std::move(*params);
    } else {
      reader.error("params", "expected an object, got " + params->dump());
    }
  }
  reader.finish();
  return device;
}

}  // namespace

Result<Config> parse_config(std::string_view text, std::string_view origin) {
  std::vector<std::string> errors;
  const auto document = parse_json_with_comments(text, origin, errors);
  if (!document) return make_error(ErrorCode::kInvalidArgument, join_errors(errors));

  Config config;
  config.origin = origin;
  JsonReader root(*document, "", errors);
  config.dds.receive_thread_priority = kDefaultReceiveThreadPriority;
  config.dds.thread_stack_bytes = kCycloneThreadStackBytes;
  if (auto daemon = root.object("daemon")) read_daemon(*daemon, config.daemon);
  if (auto dds = root.object("dds")) read_dds(*dds, config.dds);
  if (auto joystick = root.object("joystick")) {
    if (auto read = joystick::read_joystick_config(*joystick, errors); read.enabled) config.joystick = std::move(read);
  }
  const int cpu_count = static_cast<int>(sysconf(_SC_NPROCESSORS_CONF));
  root.require("devices", "an array with at least one device");
  std::set<std::string> names;
  for (auto& reader : root.object_array("devices")) {
    DeviceConfig device = read_device(reader, cpu_count);
    if (!device.name.empty() && !names.insert(device.name).second) {
      reader.error("name", "duplicate device name \"" + device.name + "\"");
    }
    if (device.realtime != rt::RealtimePolicy::kOff && device.rt_priority <= config.dds.receive_thread_priority) {
      reader.error("rt_priority", "must be above dds.receive_thread_priority (" +
                                      std::to_string(config.dds.receive_thread_priority) +
                                      "): the loop must preempt DDS's receive thread");
    }
    if (device.realtime != rt::RealtimePolicy::kOff && device.rt_priority <= config.daemon.loop_io_priority) {
      reader.error("rt_priority", "must be above daemon.loop_io_priority (" +
                                      std::to_string(config.daemon.loop_io_priority) +
                                      "): the loop must preempt the threads that publish its state");
    }
    config.devices.push_back(std::move(device));
  }
  if (config.devices.empty() && document->is_object() && document->contains("devices") &&
      (*document)["devices"].is_array()) {
    root.error("devices", "must list at least one device");
  }
  root.finish();

  if (!errors.empty()) {
    std::string message = "invalid config " + std::string(origin) + ":";
    for (const auto& e : errors) message += "\n  " + e;
    return make_error(ErrorCode::kInvalidArgument, message);
  }
  return config;
}

Result<Config> load_config_file(const std::string& path) {
  std::ifstream file(path);
  if (!file) {
    return make_error(ErrorCode::kInvalidArgument,
                      "cannot read config file '" + path + "' (does it exist, is it readable?)");
  }
  std::ostringstream text;
  text << file.rdbuf();
  return parse_config(text.str(), path);
}

}  // namespace robotd::config
