// The PAROL6's device_call ops (docs/drivers/parol6.md has the table commander function → op).
// SI units and radians at robotd's surface; steps and the board's codes stay in the codec.
// Moves (jog, cart_jog, move_joints, move_pose, move_cart) are planned here, off the RT thread, and run
// by the RT thread from the trajectory buffer; they are refused while a session owns joints or
// an e-stop is engaged, and a session taking joints or an e-stop ends them. The ops that act on
// the joints need free motors: robotd refuses them while a session holds one.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "driver/parol6_driver.hpp"
#include "kinematics/parol6_kinematics.hpp"
#include "robotd/driver/json_reader.hpp"
#include "robotd/driver/op_arguments.hpp"
#include "robotd/motion/joint_move.hpp"
#include "robotd/motion/trajectory.hpp"

namespace robotd::parol6 {

std::vector<driver::OpDescription> op_descriptions();

/// An op's arguments, checked against this driver's usage lines, and the readers its ops share.
class OpArguments : public driver::OpArguments {
 public:
  OpArguments(std::string_view op, const nlohmann::json& args);
  /// {x_m, y_m, z_m, roll_rad, pitch_rad, yaw_rad}
  std::optional<Pose> pose();
  /// duration_s, speed_fraction, acceleration_fraction (0.3 unless given), profile ("trap" unless
  /// "poly"), as the motion layer's timing.
  motion::MoveTiming timing();
};

class Parol6Ops {
 public:
  explicit Parol6Ops(Parol6Driver& driver) : driver_(driver) {}
  Result<nlohmann::json> call(const std::string& op, const nlohmann::json& args);

 private:
  // Board commands and peripherals (ops_board.cpp).
  Result<nlohmann::json> one_shot(std::string_view op, const nlohmann::json& args, OneShot request);
  Result<nlohmann::json> output(const nlohmann::json& args);
  Result<nlohmann::json> gripper(const nlohmann::json& args);
  Result<nlohmann::json> gripper_mode(std::string_view op, const nlohmann::json& args, GripperMode mode);
  Result<nlohmann::json> io(const nlohmann::json& args);
  Result<nlohmann::json> gripper_state(const nlohmann::json& args);
  Result<nlohmann::json> state(const nlohmann::json& args);
  template <class Change>
  void change_peripherals(Change change);

  // Moves (ops_motion.cpp).
  Result<nlohmann::json> jog(const nlohmann::json& args);
  Result<nlohmann::json> move_joints(const nlohmann::json& args);
  Result<nlohmann::json> move_pose(const nlohmann::json& args);
  Result<nlohmann::json> move_cart(const nlohmann::json& args);
  Result<nlohmann::json> cart_jog(const nlohmann::json& args);  // ops_cart_jog.cpp
  Result<nlohmann::json> stop(const nlohmann::json& args);
  Result<nlohmann::json> fk(const nlohmann::json& args);
  /// Error unless the arm may be moved by an op now (`needs_homed`: the move uses positions).
  std::optional<Error> check_can_move(std::string_view op, bool needs_homed) const;
  /// Error when a session still drives the arm after a short wait: robotd runs the ops that need
  /// free motors only when no session holds one, but the board's exchange may lag a release.
  std::optional<Error> check_no_session_streams(std::string_view op) const;
  /// Hands the planned positions (every exchange period) to the RT thread.
  Result<nlohmann::json> run(std::string_view op, const std::vector<JointVector>& samples);
  /// run() on a move the motion layer planned, or its refusal in the op's name.
  Result<nlohmann::json> run(std::string_view op, const Result<motion::Trajectory>& plan);
  /// What the motion layer plans with: the configured limits, the exchange period.
  motion::JointLimits limits() const;
  double period_s() const;
  JointVector measured() const;
  JointVector joint_min() const;
  JointVector joint_max() const;

  Parol6Driver& driver_;
};

}  // namespace robotd::parol6
