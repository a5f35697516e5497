// Ops that command the board or its peripherals, and the ops that report what it says.
#include <chrono>
#include <cmath>
#include <string>
#include <thread>
#include <utility>

#include "codec/joint_units.hpp"
#include "driver/gripper_current.hpp"
#include "driver/parol6_ops.hpp"

namespace robotd::parol6 {
namespace {

using namespace std::chrono_literals;

constexpr auto kHomingTimeout = 60s;  // the API gives up after 45 s

const char* object_detection_text(ObjectDetection detection) {
  switch (detection) {
    case ObjectDetection::kMoving:
      return "moving";
    case ObjectDetection::kClosingOnObject:
      return "object detected while closing";
    case ObjectDetection::kOpeningOnObject:
      return "object detected while opening";
    case ObjectDetection::kAtPosition:
      return "at position";
  }
  return "unknown";
}

const char* command_text(std::uint8_t code) {
  switch (code) {
    case command::kNone:
      return "none";
    case command::kHome:
      return "home";
    case command::kEnable:
      return "enable";
    case command::kDisable:
      return "disable";
    case command::kClearError:
      return "clear error";
    case command::kJog:
      return "jog";
    case command::kGoToPosition:
      return "go to position";
    case command::kIdle:
      return "idle";
    default:
      return "other";
  }
}

nlohmann::json joint_bits(std::uint8_t byte) {
  nlohmann::json joints = nlohmann::json::array();
  for (int j = 0; j < kJoints; ++j) joints.push_back(((static_cast<unsigned>(byte) >> (7 - j)) & 1U) != 0);
  return joints;
}

}  // namespace

template <class Change>
void Parol6Ops::change_peripherals(Change change) {
  const std::lock_guard lock(driver_.peripherals_writer_mutex_);
  Peripherals peripherals = driver_.peripherals_.load_non_rt();
  change(peripherals);
  driver_.peripherals_.store(peripherals);
}

Result<nlohmann::json> Parol6Ops::one_shot(std::string_view op, const nlohmann::json& args, OneShot request) {
  OpArguments arguments(op, args);
  const bool wait = request == OneShot::kHome && arguments.reader().boolean_or("wait", false);
  if (auto error = arguments.finish()) return *error;
  const BoardSnapshot snapshot = driver_.snapshot();
  if (!snapshot.link_up) return make_error(ErrorCode::kNotAvailable, std::string(op) + ": the board is not connected");
  // Under the e-stop the board gets DISABLE every frame and one ENABLE at its reset, so a
  // one-shot frame now would be dropped, and a disable would not outlast the reset.
  if (snapshot.estop) {
    return make_error(ErrorCode::kRefused,
                      std::string(op) +
                          ": robotd's e-stop is engaged (the board is disabled every frame until its "
                          "reset, which enables it); reset it first");
  }
  if (request == OneShot::kHome) {
    if (auto refused = check_no_session_streams(op)) return *refused;
  }
  driver_.trajectory_.cancel(200ms);
  driver_.one_shot_.store(request, std::memory_order_release);
  if (!wait) return nlohmann::json{{"sent", op}};
  const auto deadline = std::chrono::steady_clock::now() + kHomingTimeout;
  std::this_thread::sleep_for(200ms);  // let the board drop its homed bits first
  while (std::chrono::steady_clock::now() < deadline) {
    const BoardSnapshot now = driver_.snapshot();
    if (!now.link_up) return make_error(ErrorCode::kNotAvailable, "home: the link was lost while homing");
    if (now.have_reply && now.reply.all_homed()) return nlohmann::json{{"homed", true}};
    std::this_thread::sleep_for(20ms);
  }
  return make_error(ErrorCode::kTimeout, "home: not every joint homed within 60 s (a limit switch not reached?)");
}

Result<nlohmann::json> Parol6Ops::output(const nlohmann::json& args) {
  OpArguments arguments("output", args);
  JsonReader& reader = arguments.reader();
  const bool set_out1 = reader.has("out1");
  const bool set_out2 = reader.has("out2");
  const bool out1 = reader.boolean_or("out1", false);
  const bool out2 = reader.boolean_or("out2", false);
  if (!set_out1 && !set_out2) reader.error("out1", "give out1, out2 or both");
  if (auto error = arguments.finish()) return *error;
  Peripherals now;
  change_peripherals([&](Peripherals& p) {
    if (set_out1) p.out1 = out1;
    if (set_out2) p.out2 = out2;
    now = p;
  });
  return nlohmann::json{{"out1", now.out1}, {"out2", now.out2}};
}

Result<nlohmann::json> Parol6Ops::gripper(const nlohmann::json& args) {
  OpArguments arguments("gripper", args);
  JsonReader& reader = arguments.reader();
  reader.require("position", "0 (open) … 255 (closed)");
  const auto position = reader.integer("position", 0, 255);
  const auto speed = reader.integer_or("speed", driver_.params_.gripper_speed, 0, 255);
  const double current = reader.number_or("current_a", driver_.params_.gripper_current_a,
                                          NumberRange{.min = kGripperCurrentMinA, .max = kGripperCurrentMaxA});
  const bool activate = reader.boolean_or("activate", true);
  if (auto error = arguments.finish()) return *error;
  change_peripherals([&](Peripherals& p) {
    p.gripper_position = static_cast<std::int16_t>(*position);
    p.gripper_speed = static_cast<std::int16_t>(speed);
    p.gripper_current_ma = static_cast<std::int16_t>(std::lround(current * 1000));
    p.gripper_command = static_cast<std::uint8_t>((activate ? gripper_command::kActivate : 0) | gripper_command::kMove);
  });
  nlohmann::json sent{{"position", *position}, {"speed", speed}, {"current_a", current}, {"activate", activate}};
  if (std::string warning = gripper_current_warning(current, static_cast<int>(speed)); !warning.empty()) {
    sent["warning"] = std::move(warning);
  }
  return sent;
}

Result<nlohmann::json> Parol6Ops::gripper_mode(std::string_view op, const nlohmann::json& args, GripperMode mode) {
  OpArguments arguments(op, args);
  if (auto error = arguments.finish()) return *error;
  if (!driver_.snapshot().link_up) {
    return make_error(ErrorCode::kNotAvailable, std::string(op) + ": the board is not connected");
  }
  if (mode == GripperMode::kCalibrate) {
    change_peripherals([](Peripherals& p) {
      p.gripper_command = static_cast<std::uint8_t>(p.gripper_command | gripper_command::kActivate);
    });
  }
  driver_.gripper_mode_once_.store(static_cast<std::uint8_t>(mode), std::memory_order_release);
  return nlohmann::json{{"sent", op}};
}

Result<nlohmann::json> Parol6Ops::io(const nlohmann::json& args) {
  OpArguments arguments("io", args);
  if (auto error = arguments.finish()) return *error;
  const BoardSnapshot snapshot = driver_.snapshot();
  if (!snapshot.have_reply) return make_error(ErrorCode::kNotAvailable, "io: no reply from the board yet");
  const std::uint8_t bits = snapshot.reply.io;
  return nlohmann::json{{"in1", (bits & io::kIn1) != 0},
                        {"in2", (bits & io::kIn2) != 0},
                        {"out1", (bits & io::kOut1) != 0},
                        {"out2", (bits & io::kOut2) != 0},
                        {"estop_pressed", snapshot.reply.estop_pressed()}};
}

Result<nlohmann::json> Parol6Ops::gripper_state(const nlohmann::json& args) {
  OpArguments arguments("gripper_state", args);
  if (auto error = arguments.finish()) return *error;
  const BoardSnapshot snapshot = driver_.snapshot();
  if (!snapshot.have_reply) return make_error(ErrorCode::kNotAvailable, "gripper_state: no reply from the board yet");
  const RobotFrame& reply = snapshot.reply;
  const std::uint8_t status = reply.gripper_status;
  // Until the gripper first answers, the board reports its power-up constants (position 0,
  // current 2, status 1), whose status bit 0 would read as "calibrated".
  const bool answered = !(reply.gripper_position == 0 && reply.gripper_current == 2 && status == 1);
  if (!answered) {
    return nlohmann::json{{"id", driver_.params_.gripper_id},
                          {"answered", false},
                          {"note", "no answer from a gripper yet (is one connected, with this id?)"}};
  }
  return nlohmann::json{{"id", driver_.params_.gripper_id},
                        {"answered", true},
                        {"position", reply.gripper_position},
                        {"current_a", reply.gripper_current / 1000.0},
                        {"status", status},
                        {"activated", (status & gripper_status::kActivated) != 0},
                        {"moving", (status & gripper_status::kMoving) != 0},
                        {"calibrated", (status & gripper_status::kCalibrated) != 0},
                        {"temperature_error", (status & gripper_status::kTemperatureError) != 0},
                        {"timeout_error", (status & gripper_status::kTimeoutError) != 0},
                        {"estop_error", (status & gripper_status::kEstopError) != 0},
                        {"object_detection", object_detection_text(object_detection(status))}};
}

Result<nlohmann::json> Parol6Ops::state(const nlohmann::json& args) {
  OpArguments arguments("state", args);
  if (auto error = arguments.finish()) return *error;
  const BoardSnapshot snapshot = driver_.snapshot();
  const RobotFrame& reply = snapshot.reply;
  nlohmann::json joints = nlohmann::json::array();
  for (int j = 0; j < kJoints; ++j) {
    const auto index = static_cast<std::size_t>(j);
    joints.push_back({{"steps", reply.position_steps[index]},
                      {"position_rad", steps_to_rad(j, reply.position_steps[index])},
                      {"speed_setpoint_steps_s", reply.speed_steps_s[index]},
                      {"homed", reply.joint_homed(j)}});
  }
  return nlohmann::json{{"link", snapshot.link_up ? "up" : "down"},
                        {"joints", joints},
                        {"all_homed", reply.all_homed()},
                        {"command_in_force", command_text(reply.echoed_command)},
                        {"last_command_sent", command_text(snapshot.last_command_sent)},
                        {"estop_pressed", reply.estop_pressed()},
                        {"board_frame_interval_ms", reply.timing_ticks * kTimingTickSeconds * 1e3},
                        {"temperature_error_joints", joint_bits(reply.temperature_error)},
                        {"position_error_joints", joint_bits(reply.position_error)},
                        {"moving_by_op", driver_.trajectory_.running()},
                        {"frames_sent", snapshot.frames_sent},
                        {"replies", snapshot.replies},
                        {"frames_rejected", snapshot.rejected},
                        {"bytes_discarded", snapshot.discarded}};
}

}  // namespace robotd::parol6
