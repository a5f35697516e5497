// Planned motion: lines, joint moves, going home and queued pauses, through the controller's
// command cache (position mode).
#include <chrono>
#include <cmath>
#include <thread>

#include "driver/xarm_ops.hpp"

namespace robotd::xarm {
namespace {

constexpr auto kWaitPoll = std::chrono::milliseconds(20);
constexpr auto kLeaveServoWait = std::chrono::seconds(2);

struct WaitArguments {
  bool wait = false;
  double timeout_s = 60;
};

WaitArguments read_wait(JsonReader& reader) {
  return WaitArguments{.wait = reader.boolean_or("wait", false),
                       .timeout_s = reader.number_or("timeout_s", 60, NumberRange{.min = 0.1, .max = 3600})};
}

}  // namespace

std::optional<Error> XarmOps::check_can_plan(std::string_view op) const {
  if (auto refused = check_connected(op)) return refused;
  // A session that just ended is still leaving servo mode (the arm settles on its last servo_j,
  // then set_mode 0): a planned move asked for meanwhile waits for position mode.
  const auto deadline = std::chrono::steady_clock::now() + kLeaveServoWait;
  ArmFeedback feedback = driver_.link_.feedback();
  while (!driver_.session_streaming_.load(std::memory_order_relaxed) && feedback.phase != ServoPhase::kPosition &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    feedback = driver_.link_.feedback();
  }
  if (driver_.session_streaming_.load(std::memory_order_relaxed) || feedback.phase != ServoPhase::kPosition) {
    return make_error(ErrorCode::kRefused, std::string(op) +
                                               ": a session is streaming joint commands to this arm in servo mode; "
                                               "planned moves need position mode — release the session first");
  }
  if (feedback.fault.code != 0) {
    return make_error(ErrorCode::kRefused,
                      std::string(op) + ": " + feedback.fault.text.data() + "; clear it first (robotctl recover)");
  }
  return std::nullopt;
}

Result<nlohmann::json> XarmOps::queue_motion(std::string_view op, const Request& request, bool wait, double timeout_s) {
  if (auto refused = check_can_plan(op)) return *refused;
  auto reply = exchange(op, request);
  if (!reply) return reply.error();
  nlohmann::json result = execution_of(reply.value());
  if (auto queued = parse_cmdnum(reply.value().data)) result["cmdnum"] = queued.value();
  if (!wait) return result;
  // The getters queue behind the move on the same connection, so they see it already accepted.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  for (;;) {
    auto state_reply = exchange(op, plain_request(Register::kGetState));
    if (!state_reply) return state_reply.error();
    auto cmdnum_reply = exchange(op, plain_request(Register::kGetCmdnum));
    if (!cmdnum_reply) return cmdnum_reply.error();
    const auto state = parse_state(state_reply.value().data);
    const auto cmdnum = parse_cmdnum(cmdnum_reply.value().data);
    if (!state || !cmdnum) return make_error(ErrorCode::kTransport, std::string(op) + ": unreadable state reply");
    if (state.value() == kStateStopped || state.value() == kStateReset) {
      const ArmFeedback feedback = driver_.link_.feedback();
      return make_error(ErrorCode::kRefused,
                        std::string(op) + ": the arm stopped before the move finished (" +
                            motion_state_text(state.value()) + ")" +
                            (feedback.error_code != 0 ? ": " + controller_error_text(feedback.error_code) : ""));
    }
    if (state.value() != kStateMoving && state.value() != kStatePaused && cmdnum.value() == 0) break;
    if (std::chrono::steady_clock::now() > deadline) {
      return make_error(ErrorCode::kTimeout, std::string(op) + ": still " + motion_state_text(state.value()) +
                                                 " after " + std::to_string(std::lround(timeout_s)) + " s");
    }
    std::this_thread::sleep_for(kWaitPoll);
  }
  result["completed"] = true;
  return result;
}

Result<nlohmann::json> XarmOps::move_line(const std::string& op, const nlohmann::json& args) {
  driver::OpArguments arguments(op, args, op_usage(op));
  JsonReader& reader = arguments.reader();
  const auto pose = pose_argument(arguments);
  LineMove move;
  move.speed_m_s = reader.number_or("speed_m_s", move.speed_m_s);
  move.acc_m_s2 = reader.number_or("acc_m_s2", move.acc_m_s2);
  move.mvtime_s = reader.number_or("mvtime_s", 0, NumberRange{.min = 0, .max = 3600});
  if (op == "move_lineb") move.blend_radius_m = reader.number_or("radius_m", 0, NumberRange{.min = 0, .max = 1});
  const WaitArguments wait = read_wait(reader);
  if (auto bad = check_tcp_speed(move.speed_m_s, driver_.params_.model); !bad)
    reader.error("speed_m_s", bad.error().message);
  if (auto bad = check_tcp_acc(move.acc_m_s2); !bad) reader.error("acc_m_s2", bad.error().message);
  if (auto error = arguments.finish()) return *error;
  move.pose = *pose;
  return queue_motion(op, op == "move_lineb" ? move_lineb_request(move) : move_line_request(move), wait.wait,
                      wait.timeout_s);
}

Result<nlohmann::json> XarmOps::move_joint(const nlohmann::json& args) {
  driver::OpArguments arguments("move_joint", args, op_usage("move_joint"));
  JsonReader& reader = arguments.reader();
  const auto joints = joints_argument(arguments);
  JointMove move;
  move.speed_rad_s = reader.number_or("speed_rad_s", move.speed_rad_s);
  move.acc_rad_s2 = reader.number_or("acc_rad_s2", move.acc_rad_s2);
  move.mvtime_s = reader.number_or("mvtime_s", 0, NumberRange{.min = 0, .max = 3600});
  const WaitArguments wait = read_wait(reader);
  if (auto bad = check_joint_speed(move.speed_rad_s); !bad) reader.error("speed_rad_s", bad.error().message);
  if (auto bad = check_joint_acc(move.acc_rad_s2); !bad) reader.error("acc_rad_s2", bad.error().message);
  if (joints) {
    if (auto bad = check_joints_within(*joints, driver_.params_.model); !bad) {
      reader.error("joints_rad", bad.error().message);
    }
  }
  if (auto error = arguments.finish()) return *error;
  move.joints_rad = *joints;
  return queue_motion("move_joint", move_joint_request(move), wait.wait, wait.timeout_s);
}

Result<nlohmann::json> XarmOps::move_gohome(const nlohmann::json& args) {
  driver::OpArguments arguments("move_gohome", args, op_usage("move_gohome"));
  JsonReader& reader = arguments.reader();
  JointMove move;
  move.speed_rad_s = reader.number_or("speed_rad_s", move.speed_rad_s);
  move.acc_rad_s2 = reader.number_or("acc_rad_s2", move.acc_rad_s2);
  move.mvtime_s = reader.number_or("mvtime_s", 0, NumberRange{.min = 0, .max = 3600});
  const WaitArguments wait = read_wait(reader);
  if (auto bad = check_joint_speed(move.speed_rad_s); !bad) reader.error("speed_rad_s", bad.error().message);
  if (auto bad = check_joint_acc(move.acc_rad_s2); !bad) reader.error("acc_rad_s2", bad.error().message);
  if (auto error = arguments.finish()) return *error;
  return queue_motion("move_gohome", move_gohome_request(move), wait.wait, wait.timeout_s);
}

Result<nlohmann::json> XarmOps::sleep_instruction(const nlohmann::json& args) {
  driver::OpArguments arguments("sleep_instruction", args, op_usage("sleep_instruction"));
  JsonReader& reader = arguments.reader();
  reader.require("seconds", "the pause in seconds");
  const auto seconds = reader.number("seconds");
  if (seconds) {
    if (auto bad = check_sleep(*seconds); !bad) reader.error("seconds", bad.error().message);
  }
  if (auto error = arguments.finish()) return *error;
  return queue_motion("sleep_instruction", sleep_instruction_request(*seconds), false, 0);
}

}  // namespace robotd::xarm
