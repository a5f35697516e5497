// The RealMan device_call ops, named after the controller's own commands (docs/drivers/
// realman.md has the table). Radians, metres and seconds at robotd's surface; the controller's
// integers stay in the codec; the gripper's and hand's 0..1000 ranges are checked before
// anything is sent. Blocking ops (block: true) wait for the completion event on the caller's
// thread, never on the RT thread.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "driver/realman_driver.hpp"
#include "robotd/driver/json_reader.hpp"
#include "robotd/driver/op_arguments.hpp"

namespace robotd::realman {

std::vector<driver::OpDescription> op_descriptions();

class RealmanOps {
 public:
  explicit RealmanOps(RealmanDriver& driver) : driver_(driver) {}
  Result<nlohmann::json> call(const std::string& op, const nlohmann::json& args);

 private:
  // Planned motion and stops (ops_motion.cpp).
  Result<nlohmann::json> movej(const nlohmann::json& args);
  Result<nlohmann::json> cartesian_move(const std::string& op, const nlohmann::json& args);
  Result<nlohmann::json> plain(const std::string& op, const nlohmann::json& args);
  Result<nlohmann::json> set_joint_en_state(const nlohmann::json& args);
  Result<nlohmann::json> set_joint_clear_err(const nlohmann::json& args);
  Result<nlohmann::json> set_arm_power(const nlohmann::json& args);
  std::optional<Error> check_can_move(std::string_view op) const;

  // Gripper and hand (ops_end_effector.cpp).
  Result<nlohmann::json> gripper(const std::string& op, const nlohmann::json& args);
  Result<nlohmann::json> get_gripper_state(const nlohmann::json& args);
  Result<nlohmann::json> hand(const std::string& op, const nlohmann::json& args);

  // Queries in robotd's units (ops_queries.cpp).
  Result<nlohmann::json> get_current_arm_state(const nlohmann::json& args);
  Result<nlohmann::json> get_joint_err_flag(const nlohmann::json& args);
  Result<nlohmann::json> get_joint_en_state(const nlohmann::json& args);
  Result<nlohmann::json> get_arm_all_state(const nlohmann::json& args);
  Result<nlohmann::json> get_controller_state(const nlohmann::json& args);
  Result<nlohmann::json> verbatim(const std::string& op, const nlohmann::json& args);
  Result<nlohmann::json> state(const nlohmann::json& args);

  /// Sends and, with `block`, waits for `device`'s completion event (timeout_s).
  Result<nlohmann::json> send(const nlohmann::json& message, std::optional<Device> block_device, double timeout_s);
  /// The driver's request, refused while robotd is not connected. Ops read and check their
  /// arguments before they get here, so a bad argument is named whether or not the arm is there.
  Result<ControllerLink::Reply> request(const nlohmann::json& message);
  Result<ControllerLink::Reply> request(const nlohmann::json& message, const RequestOptions& options);

  RealmanDriver& driver_;
};

/// An op's arguments, checked against this driver's usage lines, and the readers its ops share.
class OpArguments : public driver::OpArguments {
 public:
  OpArguments(std::string_view op, const nlohmann::json& args);
  /// "block" (default true) and "timeout_s" (default 60).
  bool block();
  double timeout_s();
};

}  // namespace robotd::realman
