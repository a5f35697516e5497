#include "sim_options.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <string_view>

#include "arm_model.hpp"

namespace robotd::piper::sim {

Result<std::array<double, kArmJoints>> parse_initial_joints(const std::string& text) {
  std::array<double, kArmJoints> joints{};
  std::string_view rest = text;
  const auto limits = default_joint_settings();
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const std::size_t comma = rest.find(',');
    if ((comma == std::string_view::npos) != (i + 1 == joints.size())) {
      return make_error(ErrorCode::kInvalidArgument,
                        "--initial '" + text + "' must be six comma-separated angles in rad, e.g. 0,0.5,-0.5,0,0,0");
    }
    const std::string_view item = rest.substr(0, comma);
    rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
    const auto [end, error] = std::from_chars(item.data(), item.data() + item.size(), joints[i]);
    if (error != std::errc{} || end != item.data() + item.size() || !std::isfinite(joints[i])) {
      return make_error(ErrorCode::kInvalidArgument, "--initial: '" + std::string(item) + "' (joint " +
                                                         std::to_string(i + 1) + ") is not a number in rad");
    }
    if (joints[i] < limits[i].min_rad || joints[i] > limits[i].max_rad) {
      std::array<char, 160> message{};
      std::snprintf(message.data(), message.size(), "--initial: joint %zu at %g rad is outside its limits [%g, %g] rad",
                    i + 1, joints[i], limits[i].min_rad, limits[i].max_rad);
      return make_error(ErrorCode::kInvalidArgument, message.data());
    }
  }
  return joints;
}

}  // namespace robotd::piper::sim
