// The UDP real-time push's settings (spec §6.1): set_realtime_push changes the keys it names and
// keeps the others; get_realtime_push reports them.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "command_request.hpp"

namespace robotd::realman::sim {

struct PushConfig {
  static constexpr std::int64_t kCycleNs = 5'000'000;  // cycle 1
  static constexpr std::int64_t kMaxCycle = 100;       // 0.5 s

  int cycle = 1;
  bool enable = true;
  int port = 8089;
  std::string ip;  // empty: the address of the TCP client
  int force_coordinate = 0;
  /// custom: every key §6.1 and ROS1 name, all false at start. joint_speed, arm_current_status
  /// and hand add to the datagram; the others are kept and reported only (no lift, extension
  /// joint, ALOHA I/O or RM+ end effector is simulated).
  std::map<std::string, bool> custom = {{"joint_speed", false},        {"lift_state", false},   {"expand_state", false},
                                        {"arm_current_status", false}, {"aloha_state", false},  {"hand", false},
                                        {"rm_plus_state", false},      {"rm_plus_base", false}, {"tail_end", false},
                                        {"joint_acc", false}};

  std::int64_t period_ns() const { return cycle * kCycleNs; }
  bool custom_on(const std::string& key) const { return custom.at(key); }

  /// The config with the request's keys applied; throws Refusal (nothing changes) for a bad value
  /// or an unknown custom key.
  PushConfig updated(const CommandRequest& request) const;
  /// get_realtime_push's fields (cycle, enable, port, ip, force_coordinate, custom).
  nlohmann::json fields() const;
};

}  // namespace robotd::realman::sim
