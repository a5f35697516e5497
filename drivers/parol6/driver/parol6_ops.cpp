// The op table, dispatch and argument reading.
#include "driver/parol6_ops.hpp"

#include <algorithm>
#include <array>
#include <exception>

namespace robotd::parol6 {
namespace {

struct OpSpec {
  std::string_view name;
  std::string_view help;
  bool needs_free_motors = false;
};

constexpr std::array<OpSpec, 19> kOps{{
    {"home", R"({"wait": bool}: run the board's homing sequence (HOME); with wait, return when every joint is homed)",
     driver::kNeedsFreeMotors},
    {"jog",
     R"({"joint": 1..6, "velocity_rad_s": number, "duration_s": 0..10}: turn one joint at a speed for a )"
     R"(while (streamed as positions: it stops if robotd stops))",
     driver::kNeedsFreeMotors},
    {"cart_jog",
     R"({"axis": "x"|"y"|"z"|"rx"|"ry"|"rz", "velocity": m/s or rad/s, "duration_s": 0.05..10, "frame": )"
     R"("base"|"tool"}: Cartesian jog, the tool on a straight line or turning about its point (as positions))",
     driver::kNeedsFreeMotors},
    {"move_joints",
     R"({"joints_rad": [6], "duration_s", "speed_fraction", "acceleration_fraction", "profile": )"
     R"("trap"|"poly"}: MoveJoint, all joints arriving together)",
     driver::kNeedsFreeMotors},
    {"move_pose",
     R"({x_m, y_m, z_m, roll_rad, pitch_rad, yaw_rad, "duration_s", "speed_fraction", )"
     R"("acceleration_fraction", "profile"}: MovePose, the tool to a pose, linear in joint space)",
     driver::kNeedsFreeMotors},
    {"move_cart",
     R"({x_m, y_m, z_m, roll_rad, pitch_rad, yaw_rad, "duration_s", "linear_speed_m_s", "profile"}: )"
     R"(MoveCart, the tool on a straight line)",
     driver::kNeedsFreeMotors},
    {"stop", R"({}: end the running move (the arm holds where it is))"},
    {"fk", R"({"joints_rad": [6]}: the tool pose (measured joints if omitted))"},
    {"enable", R"({}: ENABLE the board (after an e-stop or a disable))", driver::kNeedsFreeMotors},
    {"disable", R"({}: DISABLE: motion commands are ignored, the steppers stay energised)", driver::kNeedsFreeMotors},
    {"clear_error", R"({}: CLEAR ERROR (resets the board's homing state))", driver::kNeedsFreeMotors},
    {"output", R"({"out1": bool, "out2": bool}: set the isolated outputs)"},
    {"gripper", R"({"position": 0..255 (0 open), "speed": 0..255, "current_a": 0..1.3, "activate": bool}: )"
                R"(move the SSG-48 gripper (a warning above 0.7 A and below 0.15 A))"},
    {"gripper_calibrate", R"({}: calibrate and activate the gripper)"},
    {"gripper_clear_error", R"({}: clear the gripper's error)"},
    {"io", R"({}: IN1, IN2, OUT1, OUT2 and the E-stop input)"},
    {"gripper_state", R"({}: the gripper's id, position, current, status bits and object detection)"},
    {"state", R"({}: joints (steps, rad, rad/s), homed per joint, I/O, the board's timing and error bytes, frames)"},
    {"demo", R"(not offered: the firmware's demo (69) moves through hard-coded poses without limits)"},
}};

std::string_view help_of(std::string_view op) {
  const auto* spec = std::find_if(kOps.begin(), kOps.end(), [&](const OpSpec& s) { return s.name == op; });
  return spec == kOps.end() ? std::string_view{} : spec->help;
}

}  // namespace

std::vector<driver::OpDescription> op_descriptions() {
  std::vector<driver::OpDescription> ops;
  ops.reserve(kOps.size());
  for (const OpSpec& op : kOps) {
    if (op.name != "demo") ops.push_back({std::string(op.name), std::string(op.help), op.needs_free_motors});
  }
  return ops;
}

OpArguments::OpArguments(std::string_view op, const nlohmann::json& args)
    : driver::OpArguments(op, args, help_of(op)) {}

std::optional<Pose> OpArguments::pose() {
  for (const char* key : {"x_m", "y_m", "z_m", "roll_rad", "pitch_rad", "yaw_rad"}) reader().require(key, "a number");
  const NumberRange reach{.min = -1.0, .max = 1.0};
  const NumberRange angle{.min = -3.1416, .max = 3.1416};
  const auto x = reader().number("x_m", reach);
  const auto y = reader().number("y_m", reach);
  const auto z = reader().number("z_m", reach);
  const auto roll = reader().number("roll_rad", angle);
  const auto pitch = reader().number("pitch_rad", angle);
  const auto yaw = reader().number("yaw_rad", angle);
  if (!x || !y || !z || !roll || !pitch || !yaw) return std::nullopt;
  return Pose{*x, *y, *z, *roll, *pitch, *yaw};
}

motion::MoveTiming OpArguments::timing() {
  constexpr double kDefaultFraction = 0.3;
  motion::MoveTiming timing;
  timing.duration_s = reader().number("duration_s", NumberRange{.min = 0.05, .max = 120});
  const NumberRange fraction{.min = 0.01, .max = 1.0};
  timing.speed_percent = 100 * reader().number_or("speed_fraction", kDefaultFraction, fraction);
  timing.acceleration_percent = 100 * reader().number_or("acceleration_fraction", kDefaultFraction, fraction);
  timing.shape = reader().string_or("profile", "trap", {"trap", "poly"}) == "poly" ? motion::Shape::kPolynomial
                                                                                   : motion::Shape::kTrapezoid;
  return timing;
}

Result<nlohmann::json> Parol6Ops::call(const std::string& op, const nlohmann::json& args) {
  try {
    if (op == "home") return one_shot(op, args, OneShot::kHome);
    if (op == "enable") return one_shot(op, args, OneShot::kEnable);
    if (op == "disable") return one_shot(op, args, OneShot::kDisable);
    if (op == "clear_error") return one_shot(op, args, OneShot::kClearError);
    if (op == "jog") return jog(args);
    if (op == "cart_jog") return cart_jog(args);
    if (op == "move_joints") return move_joints(args);
    if (op == "move_pose") return move_pose(args);
    if (op == "move_cart") return move_cart(args);
    if (op == "stop") return stop(args);
    if (op == "fk") return fk(args);
    if (op == "output") return output(args);
    if (op == "gripper") return gripper(args);
    if (op == "gripper_calibrate") return gripper_mode(op, args, GripperMode::kCalibrate);
    if (op == "gripper_clear_error") return gripper_mode(op, args, GripperMode::kClearError);
    if (op == "io") return io(args);
    if (op == "gripper_state") return gripper_state(args);
    if (op == "state") return state(args);
    if (op == "demo") return make_error(ErrorCode::kRefused, "demo: " + std::string(help_of("demo")));
  } catch (const std::exception& e) {
    return make_error(ErrorCode::kInvalidArgument, op + ": " + e.what());
  }
  std::string known;
  for (const driver::OpDescription& spec : op_descriptions()) known += (known.empty() ? "" : ", ") + spec.name;
  return make_error(ErrorCode::kInvalidArgument, "unknown op \"" + op + "\" (the parol6 driver has: " + known + ")");
}

Result<nlohmann::json> Parol6Driver::call(const std::string& op, const nlohmann::json& args) {
  if (!configured_) return make_error(ErrorCode::kRefused, op + ": the parol6 driver is not configured");
  const std::lock_guard lock(ops_mutex_);
  return Parol6Ops(*this).call(op, args);
}

}  // namespace robotd::parol6
