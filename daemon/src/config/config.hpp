// robotd's configuration: one JSON file (comments allowed), validated completely at start.
// Every problem is reported with its key path and what was expected; nothing is defaulted
// silently except keys that are absent.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "control/device_model.hpp"
#include "joystick/joystick_config.hpp"
#include "robotd/messages.hpp"
#include "robotd/result.hpp"
#include "rt/realtime_thread.hpp"
#include "wire/dds_settings.hpp"

namespace robotd::config {

struct JointLimitOverride {
  std::string joint;
  std::string path;  // for messages: "devices[0].joint_limits.joint2"
  std::optional<double> position_min_rad;
  std::optional<double> position_max_rad;
  std::optional<double> velocity_max_rad_s;
  std::optional<double> acceleration_max_rad_s2;
  std::optional<double> effort_max_nm;
  std::optional<double> kp_max;
  std::optional<double> kd_max;
};

struct DeviceConfig {
  std::string path;  // "devices[0]"
  std::string name;
  std::string driver;
  bool required = true;  // a device that fails to start stops robotd (false: robotd runs without it)
  int rate_hz = 1000;
  int rt_priority = 80;
  int cpu = -1;
  rt::RealtimePolicy realtime = rt::RealtimePolicy::kPrefer;
  control::LimitPolicy limit_policy = control::LimitPolicy::kReject;
  std::vector<JointLimitOverride> joint_limits;
  Behavior safe_behavior = Behavior::kDamping;      // on e-stop and on a device fault
  Behavior shutdown_behavior = Behavior::kDamping;  // when robotd stops
  int shutdown_ms = 300;
  int feedback_timeout_ms = 100;
  int reconnect_interval_ms = 1000;      // after a lost link, first try recover() after this; 0 = only by hand
  int reconnect_max_interval_ms = 5000;  // then at doubling intervals up to this
  int joint_state_rate_hz = 0;           // 0 = rate_hz
  int end_pose_rate_hz = 50;             // /end_pose for devices whose driver reports one; 0 = off
  nlohmann::json params = nlohmann::json::object();
};

struct DaemonConfig {
  std::string node_name = "robotd";
  std::string log_level = "info";
  std::vector<std::string> plugin_dirs;
  int status_rate_hz = 10;
  int session_status_period_ms = 1000;
  std::int32_t min_session_timeout_ms = 10;
  std::int32_t max_session_timeout_ms = 600'000;
  int stats_window_ticks = 5000;
  std::int32_t cpu_dma_latency_us = 0;  // PM QoS request held while robotd runs; -1 = none
  bool yesense_imu_topics = true;       // also publish /imu as the PI Plus /yesense_imu/* topics
  // SCHED_FIFO priority of the threads that carry each loop's state out and commands in (the state
  // publishers and the command intake); 0 = normal scheduling.
  int loop_io_priority = 10;
};

/// robotd's DDS receive thread runs at this SCHED_FIFO priority unless `dds.receive_thread_priority`
/// says otherwise: below every loop, above every ordinary process (docs/configuration.md).
inline constexpr int kDefaultReceiveThreadPriority = 10;

/// The stack of each of Cyclone DDS's threads in robotd. How it was chosen: the deepest of them,
/// measured as the resident part of its stack mapping (pages are locked as touched) with the
/// 7-device demo serving clients, was 20 KiB (dq.builtins, discovery); with DDS Security on, the
/// handshake thread (fsm) used 16 KiB and the others no more than without. Cyclone is not robotd's
/// code and another version may go deeper, so the margin is twice that of robotd's own threads
/// (driver::kThreadStackBytes). Untouched pages cost address space only.
inline constexpr std::size_t kCycloneThreadStackBytes = std::size_t{512} * 1024;

struct Config {
  std::string origin;  // file path, for messages
  DaemonConfig daemon;
  wire::DdsSettings dds;
  std::vector<DeviceConfig> devices;
  std::optional<joystick::JoystickConfig> joystick;  // a game controller published on /joy; none = off
};

/// Parses and validates config text. On failure the error lists every problem found.
Result<Config> parse_config(std::string_view text, std::string_view origin);
Result<Config> load_config_file(const std::string& path);

}  // namespace robotd::config
