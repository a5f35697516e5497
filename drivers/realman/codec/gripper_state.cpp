// get_gripper_state's reply (§5.1): {"command": "get_gripper_state", "enable", "status",
// "error", "mode", "current_force", "temperature", "actpos"}.
#include <cstdint>
#include <limits>
#include <string>

#include "field_reader.hpp"
#include "realman_codec.hpp"

namespace robotd::realman {

Result<GripperState> parse_gripper_state(const Message& reply) {
  constexpr std::int64_t kIntMin = std::numeric_limits<int>::min();
  constexpr std::int64_t kIntMax = std::numeric_limits<int>::max();
  std::string problem;
  FieldReader body(reply.body, "", problem);
  GripperState state;
  state.enabled = body.flag("enable");
  state.online = body.flag("status");
  state.error_bits = static_cast<std::uint16_t>(body.integer("error", 0, 0xFFFF));
  state.mode = static_cast<int>(body.integer("mode", kIntMin, kIntMax));
  state.force_g = static_cast<int>(body.integer("current_force", kIntMin, kIntMax));
  state.temperature_c = static_cast<int>(body.integer("temperature", kIntMin, kIntMax));
  state.opening = static_cast<int>(body.integer("actpos", kIntMin, kIntMax));
  if (!problem.empty()) return make_error(ErrorCode::kInvalidArgument, "get_gripper_state reply: " + problem);
  return state;
}

}  // namespace robotd::realman
