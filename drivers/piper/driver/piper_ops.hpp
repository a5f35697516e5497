// The PiPER's device_call ops: the vendor API beyond joint streaming (docs/drivers/piper.md has
// the table vendor function → op). Arguments in SI units and radians; vendor units stay in the
// codec. The ops that act on the joints need free motors (robotd refuses them while a session
// holds one); the motion ops (end_pose, move_c, mode, gripper, enable, master_slave) hold joint
// streaming off until a session takes joints again; disable is decided by write() at its tick.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "driver/piper_driver.hpp"
#include "robotd/driver/json_reader.hpp"
#include "robotd/driver/op_arguments.hpp"

namespace robotd::piper {

std::vector<driver::OpDescription> op_descriptions();

/// An op's arguments, checked against this driver's usage lines, and the readers its ops share.
class OpArguments : public driver::OpArguments {
 public:
  OpArguments(std::string_view op, const nlohmann::json& args);
  /// "joint": 1 … 6, or "all" when `allow_all` (then kAllJoints).
  std::optional<std::uint8_t> joint(bool allow_all);
  /// "joint": "j1" … "j6" (the SDK's joint_name) or 1 … 6.
  std::optional<std::uint8_t> sdk_joint();
  /// A pose object {x_m, y_m, z_m, roll_rad, pitch_rad, yaw_rad} under `reader`.
  static std::optional<CartesianPose> pose(JsonReader& reader);
};

class PiperOps {
 public:
  explicit PiperOps(PiperDriver& driver) : driver_(driver) {}
  Result<nlohmann::json> call(const std::string& op, const nlohmann::json& args);

 private:
  // Motion and mode (ops_motion.cpp).
  Result<nlohmann::json> end_pose(const nlohmann::json& args);
  Result<nlohmann::json> move_c(const nlohmann::json& args);
  Result<nlohmann::json> mode(const nlohmann::json& args);
  Result<nlohmann::json> gripper(const nlohmann::json& args);
  Result<nlohmann::json> enable(const nlohmann::json& args, bool on);
  Result<nlohmann::json> master_slave(const nlohmann::json& args);
  Result<nlohmann::json> master_home(const nlohmann::json& args);
  /// Error unless the arm is connected and no session streams to it (robotd runs the ops that
  /// need free motors only then, but the loop may still be ending a session released just before).
  std::optional<Error> check_no_session_streams(std::string_view op);
  /// Error unless the arm may be driven by an op now; on success streaming is held off.
  std::optional<Error> take_arm_for(std::string_view op);
  /// Hands the disable to write(), which decides at its tick (PiperDriver::decide_disable).
  std::optional<Error> disable_now(std::uint8_t motor);
  std::optional<Error> send_all(std::span<const CanMessage> frames);

  // Queries (ops_queries.cpp).
  Result<nlohmann::json> limits(const nlohmann::json& args);
  Result<nlohmann::json> acc_limits(const nlohmann::json& args);
  Result<nlohmann::json> firmware(const nlohmann::json& args);
  Result<nlohmann::json> end_limits(const nlohmann::json& args);
  Result<nlohmann::json> crash_protection(const nlohmann::json& args);
  Result<nlohmann::json> gripper_params(const nlohmann::json& args);
  Result<nlohmann::json> can_fps(const nlohmann::json& args);
  Result<nlohmann::json> state(const nlohmann::json& args);
  Result<nlohmann::json> fk(const nlohmann::json& args);
  Result<nlohmann::json> master_commands(const nlohmann::json& args);
  Result<nlohmann::json> fk_calculation(const nlohmann::json& args);
  Result<nlohmann::json> trajectory_index(const nlohmann::json& args);
  Result<nlohmann::json> query_param(std::uint8_t query, std::uint32_t reply_id);

  // Settings, acknowledged by the arm (ops_settings.cpp).
  Result<nlohmann::json> set_joint_limits(const nlohmann::json& args);
  Result<nlohmann::json> set_max_speed(const nlohmann::json& args);
  Result<nlohmann::json> joint_config(const nlohmann::json& args);
  Result<nlohmann::json> set_max_acc(const nlohmann::json& args);
  Result<nlohmann::json> param_config(const nlohmann::json& args);
  Result<nlohmann::json> set_end_limits(const nlohmann::json& args);
  Result<nlohmann::json> set_crash_protection(const nlohmann::json& args);
  Result<nlohmann::json> set_gripper_params(const nlohmann::json& args);

  // The SDK's software limits, narrowing the described limits at run time (ops_sdk_limits.cpp).
  Result<nlohmann::json> sdk_joint_limit(const nlohmann::json& args);
  Result<nlohmann::json> sdk_gripper_range(const nlohmann::json& args);

  PiperDriver& driver_;
};

/// `frame` encoded, or the codec's refusal() as an invalid-argument error of `op`: the last check
/// before an op's values reach the arm.
template <typename Frame>
Result<CanMessage> checked_encode(std::string_view op, const Frame& frame, const CodecOptions& options) {
  if (const char* reason = refusal(frame, options)) {
    return make_error(ErrorCode::kInvalidArgument, std::string(op) + ": " + reason);
  }
  return encode(frame, options);
}

/// JSON of decoded replies, shared by queries and settings that answer with the new values.
nlohmann::json to_json(const CartesianPose& pose);
nlohmann::json to_json(const GripperParams& params);
nlohmann::json to_json(const EndVelAcc& values);

}  // namespace robotd::piper
