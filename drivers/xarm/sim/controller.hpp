// The xArm controller without its sockets: takes one request frame at a time and gives the reply
// (spec §2–§4 and the seed's API), keeps the state machine (§3.1: 1 moving, 2 sleeping, 3
// paused, 4 stopped, 5 system reset), the mode, the error and warning codes, the motors, the
// command cache and the servo target; moves the joints through time; produces the motion-feedback
// frames and the reports' fields. Simulator routes the bytes.
//
// Registers are dispatched by number (controller.cpp holds the table); each handler is in the
// commands_*.cpp file of its family. The status byte of every reply is computed after the
// handler ran, from the live state (§2.3).
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "arm_kinematics.hpp"
#include "codec/xarm_codec.hpp"
#include "command_cache.hpp"
#include "motion_config.hpp"
#include "robotd/result.hpp"
#include "servo_stream.hpp"
#include "sim_options.hpp"
#include "xarm_gripper.hpp"

namespace robotd::xarm::sim {

/// A register's number on the wire.
constexpr std::uint8_t number(Register reg) { return static_cast<std::uint8_t>(reg); }

/// A frame for one client that it did not ask for: a motion-feedback frame (§2.5).
struct Feedback {
  ClientId client = 0;
  Frame frame;
};

class Controller {
 public:
  static constexpr std::size_t kServoSlots = 8;  // joints 1–7, then the gripper (reg 106)

  Controller(const SimOptions& options, const ArmModel& model, std::int64_t now_ns);

  /// One request frame from `client`: the reply. Call advance() to its arrival time first.
  Frame handle(const Frame& request, ClientId client);
  /// Moves everything to `now_ns`.
  void advance(std::int64_t now_ns);
  /// The motion-feedback frames since the last call, for the clients that asked for them.
  std::vector<Feedback> take_feedback();
  /// The connection closed: its set_feedback_type goes with it.
  void forget_client(ClientId client) { feedback_masks_.erase(client); }

  /// The reports' fields now (§5).
  Report report(std::int64_t now_ns) const;
  /// The status byte a reply would carry now, nothing being wrong with the request.
  std::uint8_t status_byte() const { return status_byte(false, false); }
  const ArmModel& model() const { return model_; }

  // For the control channel (control_ops.cpp).
  /// Latches controller error `code` (1 … 255) as if the arm raised it; 0 clears the code.
  void latch_error(int code);
  void set_warning(int code) { warning_ = code; }
  /// Servo `slot` (0 … 6 a joint, 7 the gripper) reports (1, code); a joint also latches error
  /// 10 + joint. Code 0 clears the slot's entry.
  void set_servo_error(std::size_t slot, int code);
  /// The gripper reports error `code` (0 clears it) and stops.
  void set_gripper_error(int code) { gripper_.set_error(code); }
  void set_gripper_object(int width_pulses) { gripper_.set_object(width_pulses); }
  /// The e-stop button: pressed latches error 1, which clean_err cannot clear until released.
  void set_estop(bool pressed);
  /// Puts the joints there (within the limits); kRefused while the cache holds commands.
  Result<void> set_joints(const JointValues& joints);
  nlohmann::json state() const;

 private:
  struct Request {
    const Frame& frame;
    ClientId client;
  };
  /// What a handler decided: the reply data and the request's own status bits.
  struct Outcome {
    Bytes data;
    bool invalid = false;  // 0x08: bad parameters, unknown register, could not be done
    bool refused = false;  // 0x10 although the arm could move: a motion in the wrong mode or state
  };
  static Outcome answer(Bytes data) { return Outcome{.data = std::move(data), .invalid = false, .refused = false}; }
  static Outcome failed() { return Outcome{.data = {}, .invalid = true, .refused = false}; }
  static Outcome not_ready() { return Outcome{.data = {}, .invalid = false, .refused = true}; }
  using Handler = Outcome (Controller::*)(const Request&);
  static const std::map<std::uint8_t, Handler>& handlers();

  std::uint8_t status_byte(bool invalid, bool refused) const;
  /// Every joint of the model enabled with its brake released.
  bool motors_ready() const;
  /// What the status byte's 0x10 says is not so: no error, not stopped or reset, motors ready.
  bool can_move() const;
  /// Whether a planned motion may be queued now (mode 0, can move, not decelerating to a stop).
  bool can_queue() const;
  /// Sets warning 12 (parameter error) and says why in the log.
  Outcome parameter_error(const Request& request, const std::string& why);
  /// Sets warning 13 (command does not exist): a register this simulator does not emulate. The
  /// reply carries zeros for the data a getter of §4.2 answers, so that a client reading it sees
  /// the failed status rather than a short reply.
  Outcome not_emulated(const Request& request);
  /// Sets warning 14 (command has no solution).
  Outcome no_solution(const Request& request, const std::string& why);
  /// [Reset System]: motion stops, the cache is cleared, state 5 until set_state(0) (4 while an
  /// error is latched).
  void reset_system();
  /// Halts at once: the cache cleared (discarded feedback), the servo target dropped.
  void stop_motion();
  void emit_feedback(const std::vector<CacheEvent>& events);
  /// Queues a planned command (or sets warning 11 when the cache is full).
  Outcome queue(const Request& request, CachedCommand command);
  Eigen::Isometry3d tcp_offset() const { return isometry_of(config_.tcp_offset); }
  Pose tcp_pose(const JointValues& joints) const;
  JointValues joint_efforts() const;
  /// The rich report's tail (§5.3): the model, the firmware, the motion limits, the servos.
  RichFields rich_fields() const;

  // commands_system.cpp
  Outcome get_version(const Request& request);
  Outcome get_robot_sn(const Request& request);
  Outcome motion_enable(const Request& request);
  Outcome set_state(const Request& request);
  Outcome get_state(const Request& request);
  Outcome get_cmdnum(const Request& request);
  Outcome get_err_code(const Request& request);
  Outcome clean_err(const Request& request);
  Outcome clean_war(const Request& request);
  Outcome set_brake(const Request& request);
  Outcome set_mode(const Request& request);
  Outcome set_sensitivity(const Request& request);
  Outcome clean_conf(const Request& request);
  Outcome save_conf(const Request& request);
  Outcome servo_get_dbmsg(const Request& request);
  Outcome feedback_check(const Request& request);
  Outcome set_feedback_type(const Request& request);
  Outcome get_reduced_mode(const Request& request);
  Outcome set_reduced_mode(const Request& request);

  // commands_motion.cpp
  Outcome move_line(const Request& request);
  Outcome move_joint(const Request& request);
  Outcome move_gohome(const Request& request);
  Outcome sleep_instruction(const Request& request);
  Outcome servo_j(const Request& request);
  Outcome set_motion_limit(const Request& request);
  Outcome queue_joint_move(const Request& request, const JointValues& target, double speed_rad_s, double acc_rad_s2);

  // commands_tool.cpp
  Outcome tool_modbus(const Request& request);
  Outcome tool_gpio_error(const Request& request);
  Outcome tool_read(const Request& request);
  Outcome tool_write(const Request& request);

  // commands_kinematics.cpp
  Outcome set_tcp_offset(const Request& request);
  Outcome set_load_param(const Request& request);
  Outcome get_tcp_pose(const Request& request);
  Outcome get_joint_pos(const Request& request);
  Outcome get_ik(const Request& request);
  Outcome get_fk(const Request& request);
  Outcome is_joint_limit(const Request& request);

  SimOptions options_;
  ArmModel model_;
  ArmKinematics kinematics_;
  JointValues joints_{};
  JointValues velocity_{};  // rad/s, low-passed over 10 ms
  std::array<bool, kMaxDof> enabled_{};
  std::array<bool, kMaxDof> brake_released_{};
  int state_ = kStateStopped;
  int mode_ = kModePosition;
  int error_ = 0;
  int warning_ = 0;
  bool estop_held_ = false;
  bool slow_stopping_ = false;  // set_state(6): the move brakes, then state 4
  bool reduced_mode_ = false;   // a flag only: the reduced speeds, boundary and ranges are not simulated

  CommandCache cache_;
  std::uint16_t next_task_id_ = 1;
  ServoStream servo_;
  MotionConfig config_;
  std::optional<MotionConfig> saved_config_;
  std::array<ServoStatus, kServoSlots> servo_status_{};
  XarmGripper gripper_;
  int tool_baud_index_ = 11;  // 2 Mbit/s, the xArm gripper's rate
  int tool_digital_out_ = 0;
  std::map<ClientId, std::uint8_t> feedback_masks_;  // set_feedback_type, per connection
  std::vector<Feedback> feedback_;

  std::int64_t started_ns_;
  std::int64_t advanced_ns_;
  std::map<std::string, std::uint64_t, std::less<>> command_counts_;
  std::map<std::string, std::int64_t, std::less<>> command_last_ns_;  // CLOCK_MONOTONIC, when last read
};

}  // namespace robotd::xarm::sim
