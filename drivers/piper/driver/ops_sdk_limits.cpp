// The SDK's software limits as ops: SetSDKJointLimitParam(joint_name, min_val, max_val) and
// SetSDKGripperRangeParam(min_val, max_val) (agilexrobotics/piper_sdk,
// piper_sdk/interface/piper_interface_v2.py and piper_sdk/piper_param/piper_param_manager.py).
// The SDK clamps what it sends to them; here they narrow the limits the driver describes, and
// robotd takes those after the op (Device::narrow_to_described): the loop and the command
// validation hold them from the next tick. They only narrow: robotd never widens a running
// device's limits.
#include <cmath>
#include <sstream>

#include "driver/piper_ops.hpp"

namespace robotd::piper {
namespace {

constexpr const char* kHowToWiden =
    "robotd only narrows limits at run time; to widen one, raise it in the device's config "
    "(params.joints.<joint> or joint_limits) and restart robotd";

/// `limits` narrowed to `min`..`max`, or why not: an empty range, or a bound beyond the one in
/// force (a widening). `name` and `unit` are for the message.
Result<void> narrow_range(std::string_view op, const std::string& name, driver::JointLimits& limits, double min,
                          double max, const char* unit) {
  std::ostringstream text;
  text << op << ": " << name << ": ";
  if (!(min < max)) {
    text << "min " << min << " must be below max " << max << " " << unit;
    return make_error(ErrorCode::kInvalidArgument, text.str());
  }
  if (min < limits.position_min_rad || max > limits.position_max_rad) {
    text << min << ".." << max << " " << unit << " is wider than the limits in force " << limits.position_min_rad
         << ".." << limits.position_max_rad << " " << unit << ": " << kHowToWiden;
    return make_error(ErrorCode::kRefused, text.str());
  }
  limits.position_min_rad = min;
  limits.position_max_rad = max;
  return {};
}

}  // namespace

Result<nlohmann::json> PiperOps::sdk_joint_limit(const nlohmann::json& args) {
  OpArguments arguments("sdk_joint_limit", args);
  JsonReader& reader = arguments.reader();
  const auto joint = arguments.sdk_joint();
  reader.require("min_rad", "a number (rad)");
  reader.require("max_rad", "a number (rad)");
  const auto min = reader.number("min_rad");
  const auto max = reader.number("max_rad");
  if (auto error = arguments.finish()) return *error;
  const std::size_t j = *joint - 1U;
  const std::lock_guard lock(driver_.limits_mutex_);
  PiperJointParams& params = driver_.params_.joints[j];
  if (auto narrowed = narrow_range("sdk_joint_limit", params.name, params.limits, *min, *max, "rad"); !narrowed) {
    return narrowed.error();
  }
  // A reconnect reads the arm's limits again and narrows these with them: keep the narrowing.
  driver_.configured_limits_[j].position_min_rad = std::fmax(driver_.configured_limits_[j].position_min_rad, *min);
  driver_.configured_limits_[j].position_max_rad = std::fmin(driver_.configured_limits_[j].position_max_rad, *max);
  return nlohmann::json{{"joint", params.name}, {"min_rad", *min}, {"max_rad", *max}};
}

Result<nlohmann::json> PiperOps::sdk_gripper_range(const nlohmann::json& args) {
  OpArguments arguments("sdk_gripper_range", args);
  JsonReader& reader = arguments.reader();
  reader.require("min_m", "a number (m)");
  reader.require("max_m", "a number (m)");
  const auto min = reader.number("min_m");
  const auto max = reader.number("max_m");
  if (auto error = arguments.finish()) return *error;
  if (!driver_.params_.gripper) {
    return make_error(ErrorCode::kRefused,
                      "sdk_gripper_range: this device has no gripper joint (params.gripper is false)");
  }
  const std::lock_guard lock(driver_.limits_mutex_);
  PiperJointParams& gripper = driver_.params_.gripper_joint;
  if (auto narrowed = narrow_range("sdk_gripper_range", gripper.name, gripper.limits, *min, *max, "m"); !narrowed) {
    return narrowed.error();
  }
  return nlohmann::json{{"joint", gripper.name}, {"min_m", *min}, {"max_m", *max}};
}

}  // namespace robotd::piper
