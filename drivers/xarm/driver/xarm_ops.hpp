// The xArm device_call ops, named after the vendor API's functions (docs/drivers/xarm.md has the
// table). Metres, radians and seconds at robotd's surface; the controller's millimetres stay in
// the codec. Every op that reaches the control box answers with its execution state (seed
// Appendix I) as code and text; one the box refuses is an error that says why, in its words.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "driver/xarm_driver.hpp"
#include "robotd/driver/op_arguments.hpp"

namespace robotd::xarm {

std::vector<driver::OpDescription> op_descriptions();

class XarmOps {
 public:
  explicit XarmOps(XarmDriver& driver) : driver_(driver) {}
  Result<nlohmann::json> call(const std::string& op, const nlohmann::json& args);

 private:
  // Planned motion (ops_motion.cpp).
  Result<nlohmann::json> move_line(const std::string& op, const nlohmann::json& args);
  Result<nlohmann::json> move_joint(const nlohmann::json& args);
  Result<nlohmann::json> move_gohome(const nlohmann::json& args);
  Result<nlohmann::json> sleep_instruction(const nlohmann::json& args);
  /// Refused while a session streams in servo mode or the arm has an error.
  std::optional<Error> check_can_plan(std::string_view op) const;
  /// Sends a queued motion; with `wait`, polls until the cache is empty and the arm stopped.
  Result<nlohmann::json> queue_motion(std::string_view op, const Request& request, bool wait, double timeout_s);

  // States, enabling, errors and settings (ops_settings.cpp).
  Result<nlohmann::json> motion_en(const nlohmann::json& args);
  Result<nlohmann::json> set_state(const nlohmann::json& args);
  Result<nlohmann::json> set_mode(const nlohmann::json& args);
  Result<nlohmann::json> set_brake(const nlohmann::json& args);
  Result<nlohmann::json> set_limit(const std::string& op, const nlohmann::json& args);
  Result<nlohmann::json> set_tcp_offset(const nlohmann::json& args);
  Result<nlohmann::json> set_reduced_mode(const nlohmann::json& args);
  /// Ops without arguments that only say whether the box took them.
  Result<nlohmann::json> plain(const std::string& op, Register reg, const nlohmann::json& args);

  // Queries in robotd's units (ops_queries.cpp).
  Result<nlohmann::json> get_state(const nlohmann::json& args);
  Result<nlohmann::json> get_cmdnum(const nlohmann::json& args);
  Result<nlohmann::json> get_err_code(const nlohmann::json& args);
  Result<nlohmann::json> get_tcp_pose(const nlohmann::json& args);
  Result<nlohmann::json> get_joint_pose(const nlohmann::json& args);
  Result<nlohmann::json> get_fk(const nlohmann::json& args);
  Result<nlohmann::json> is_joint_limit(const nlohmann::json& args);
  Result<nlohmann::json> servo_get_dbmsg(const nlohmann::json& args);
  Result<nlohmann::json> get_version(const nlohmann::json& args);
  Result<nlohmann::json> get_reduced_mode(const nlohmann::json& args);
  Result<nlohmann::json> state(const nlohmann::json& args);
  /// Sends `request`, decodes the reply's data with `parse` and lets `fill` add it to the
  /// execution state.
  template <class Parse, class Fill>
  Result<nlohmann::json> answer(std::string_view op, const Request& request, Parse parse, Fill fill);

  // The xArm gripper on the tool's RS-485 bus (ops_gripper.cpp).
  Result<nlohmann::json> gripper_enable(const nlohmann::json& args);
  Result<nlohmann::json> gripper_set_speed(const nlohmann::json& args);
  /// gripper_set_position, gripper_open (850 pulses) and gripper_close (0).
  Result<nlohmann::json> gripper_move(const std::string& op, const nlohmann::json& args);
  Result<nlohmann::json> gripper_get_position(const nlohmann::json& args);
  Result<nlohmann::json> gripper_get_error(const nlohmann::json& args);
  Result<nlohmann::json> gripper_get_status(const nlohmann::json& args);
  /// The status register's bits 0–1 (GripperStatus).
  Result<int> gripper_status(std::string_view op);
  Result<nlohmann::json> gripper_clean_error(const nlohmann::json& args);
  /// Reads `count` gripper registers from `reg`.
  Result<std::vector<std::uint16_t>> gripper_read(std::string_view op, GripperRegister reg, std::uint16_t count);
  /// Writes gripper registers from `reg`, then reads the gripper's error code: a write the
  /// gripper took while it reports an error is refused in its words.
  Result<nlohmann::json> gripper_write(std::string_view op, GripperRegister reg, std::span<const std::uint16_t> values);
  /// Refuses unless the tool's RS-485 bus runs at the gripper's 2 Mbit/s.
  std::optional<Error> check_tool_baud_rate(std::string_view op);

  // Shared by the files above (xarm_ops.cpp).
  /// Sends and judges: the reply, or kRefused "<op>: <execution state text>: <controller error
  /// or warning>" when the execution state is not a success for this register.
  Result<Reply> exchange(std::string_view op, const Request& request);
  /// Refuses while robotd is not connected. Ops read and check their arguments first, so a bad
  /// argument is named whether or not the arm is there.
  std::optional<Error> check_connected(std::string_view op) const;
  /// exchange(), answered with the execution state alone.
  Result<nlohmann::json> acknowledge(std::string_view op, const Request& request);
  /// {"execution_state": n, "execution_text": "…"}
  static nlohmann::json execution_of(const Reply& reply);
  /// "joint": 1..dof, or "all" (→ 8) when allowed.
  std::optional<int> joint_argument(driver::OpArguments& arguments, bool allow_all) const;
  /// "joints_rad": an array of dof numbers (the tail up to 7 zero).
  std::optional<JointValues> joints_argument(driver::OpArguments& arguments) const;
  /// x_m, y_m, z_m, roll_rad, pitch_rad, yaw_rad.
  static std::optional<Pose> pose_argument(driver::OpArguments& arguments);
  static nlohmann::json pose_json(const Pose& pose);
  nlohmann::json joints_json(const JointValues& joints) const;

  XarmDriver& driver_;
};

/// The usage line of `op` ("" for an op that does not exist).
std::string_view op_usage(std::string_view op);

}  // namespace robotd::xarm
