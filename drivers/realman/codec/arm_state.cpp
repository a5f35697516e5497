// get_current_arm_state's reply (§4): joints, pose and the controller's errors in any shape.
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "field_reader.hpp"
#include "realman_codec.hpp"

namespace robotd::realman {

Result<ArmState> parse_current_arm_state(const Message& reply) {
  std::string problem;
  FieldReader body(reply.body, "", problem);
  FieldReader arm_state = body.object("arm_state");
  const auto joints = arm_state.integers("joint", 1, kMaxDof);
  const bool has_pose = arm_state.has("pose");
  const auto pose = has_pose ? arm_state.integers("pose", 6, 6) : std::vector<std::int64_t>{};
  auto errors = arm_state.error_codes();
  if (!problem.empty()) return make_error(ErrorCode::kInvalidArgument, "current_arm_state reply: " + problem);

  ArmState state;
  state.dof = joints.size();
  for (std::size_t j = 0; j < joints.size(); ++j) state.joints_rad[j] = rad_from_millidegrees(joints[j]);
  state.has_pose = has_pose;
  if (has_pose) {
    for (std::size_t i = 0; i < 3; ++i) {
      state.pose.position_m[i] = m_from_micrometres(pose[i]);
      state.pose.euler_rad[i] = rad_from_milliradians(pose[i + 3]);
    }
  }
  state.errors = std::move(errors);
  return state;
}

}  // namespace robotd::realman
