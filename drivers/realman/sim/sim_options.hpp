// What the command line sets (main.cpp), checked: one value per option.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace robotd::realman::sim {

/// Which controller generation is emulated; the generations differ on the wire (spec §3.3, §4, §6).
enum class Generation : std::uint8_t {
  k2 = 2,  // movej_canfd answered with joint_state; get_arm_software_version; no UDP push
  k3 = 3,  // movej_canfd silent; get_arm_software_info; UDP push
  k4 = 4,  // as 3, and get_arm_software_info reports robot_controller_version "4.0"
};

/// How controller errors appear in get_current_arm_state, get_arm_all_state and the push (§4.1).
enum class ErrorShape : std::uint8_t {
  kList,    // "err": [codes…], [0] when healthy
  kLegacy,  // "arm_err": code, "sys_err": code
  kScalar,  // "err": code
};

struct SimOptions {
  std::string host = "127.0.0.1";
  std::uint16_t port = 0;    // --port: the TCP command port (required)
  std::string control_path;  // --control; empty: no control channel
  std::string model = "RM65-B";
  Generation generation = Generation::k3;
  ErrorShape error_shape = ErrorShape::kList;
  bool quiet = false;
};

std::optional<Generation> parse_generation(std::string_view text);   // "2", "3", "4"
std::optional<ErrorShape> parse_error_shape(std::string_view text);  // "list", "legacy", "scalar"
std::string_view error_shape_name(ErrorShape shape);

}  // namespace robotd::realman::sim
