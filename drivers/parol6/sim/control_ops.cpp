// The control channel's ops (README.md in this folder): what tests ask the simulator to report
// or to do wrong.
#include <string>

#include <spdlog/spdlog.h>

#include "robotd/sim_control/control_request.hpp"
#include "simulator.hpp"

namespace robotd::parol6::sim {
namespace {

using nlohmann::json;
using sim_control::boolean_field;
using sim_control::expect_fields;
using sim_control::integer_field;
using sim_control::RequestError;

constexpr std::int64_t kMaxDurationMs = 3'600'000;
constexpr std::int64_t kMaxByteCount = 1'000'000;
constexpr const char* kOps =
    "state, estop, inputs, silence, drop_bytes, garble, garbage, disconnect, set_steps, gripper_object, "
    "gripper_error, reset_counters";

json gripper_state(const Board& board) {
  const Ssg48Gripper* gripper = board.gripper();
  if (gripper == nullptr) return {{"present", false}};
  json answer = nullptr;
  if (const auto& last = board.last_gripper_answer()) {
    answer = {{"position", last->position}, {"current_ma", last->current_ma}, {"status", last->status}};
  }
  return {{"present", true},
          {"position", gripper->position()},
          {"target", gripper->target()},
          {"speed", gripper->speed()},
          {"current_setting_ma", gripper->current_setting_ma()},
          {"current_ma", gripper->current_ma()},
          {"status", gripper->status()},
          {"activated", gripper->activated()},
          {"calibrated", gripper->calibrated()},
          {"calibrating", gripper->calibrating()},
          {"moving", gripper->moving()},
          {"estop_error", gripper->estop_error()},
          {"temperature_error", gripper->temperature_error()},
          {"timeout_error", gripper->timeout_error()},
          {"object_detection", static_cast<int>(gripper->object_detection())},
          {"object_position", gripper->object() ? json(*gripper->object()) : json(nullptr)},
          {"last_answer", answer}};
}

}  // namespace

json Simulator::control(const json& request) {
  try {
    const std::string op = sim_control::op_of(request, kOps);
    const std::int64_t now = monotonic_ns();
    json reply = {{"ok", true}};
    if (op == "state") {
      expect_fields(request, op, {});
      return state();
    }
    if (op == "estop") {
      expect_fields(request, op, {"pressed"});
      board_.set_estop_pressed(boolean_field(request, op, "pressed"));
    } else if (op == "inputs") {
      expect_fields(request, op, {"in1", "in2"});
      if (!request.contains("in1") && !request.contains("in2")) {
        throw RequestError("op \"inputs\" needs \"in1\" and/or \"in2\": true (high) or false (low)");
      }
      const bool in1 = request.contains("in1") ? boolean_field(request, op, "in1") : board_.in1();
      const bool in2 = request.contains("in2") ? boolean_field(request, op, "in2") : board_.in2();
      board_.set_in1(in1);
      board_.set_in2(in2);
    } else if (op == "silence") {
      expect_fields(request, op, {"ms"});
      silent_until_ns_ = now + integer_field(request, op, "ms", 0, kMaxDurationMs) * 1'000'000;
    } else if (op == "drop_bytes") {
      expect_fields(request, op, {"count"});
      faults_.drop_next(integer_field(request, op, "count", 1, kMaxByteCount));
    } else if (op == "garble") {
      expect_fields(request, op, {"count"});
      faults_.garble_next(integer_field(request, op, "count", 1, kMaxByteCount));
    } else if (op == "garbage") {
      expect_fields(request, op, {"bytes"});
      faults_.queue_garbage(integer_field(request, op, "bytes", 1, kMaxByteCount));
      reply["queued"] = faults_.garbage_pending();
    } else if (op == "disconnect") {
      expect_fields(request, op, {"ms"});
      const std::int64_t ms = integer_field(request, op, "ms", 0, kMaxDurationMs);
      close_line();
      reopen_line_at_ns_ = now + ms * 1'000'000;
    } else if (op == "set_steps") {
      expect_fields(request, op, {"joint", "steps"});
      const auto joint = static_cast<int>(integer_field(request, op, "joint", 1, kJoints));
      board_.arm().set_steps(joint - 1, integer_field(request, op, "steps", kMinInt24, kMaxInt24));
    } else if (op == "gripper_object") {
      expect_fields(request, op, {"position"});
      const auto field = request.find("position");
      if (field == request.end()) {
        throw RequestError("op \"gripper_object\" needs \"position\": 0 … 255, or null for no object");
      }
      if (board_.gripper() == nullptr) throw RequestError("op \"gripper_object\": no gripper (--no-gripper)");
      if (field->is_null()) {
        board_.gripper()->set_object(std::nullopt);
      } else {
        board_.gripper()->set_object(static_cast<std::uint8_t>(integer_field(request, op, "position", 0, 255)));
      }
    } else if (op == "gripper_error") {
      expect_fields(request, op, {"temperature", "timeout"});
      if (!request.contains("temperature") && !request.contains("timeout")) {
        throw RequestError("op \"gripper_error\" needs \"temperature\" and/or \"timeout\": true to raise it");
      }
      if (board_.gripper() == nullptr) throw RequestError("op \"gripper_error\": no gripper (--no-gripper)");
      const bool temperature = request.contains("temperature") && boolean_field(request, op, "temperature");
      const bool timeout = request.contains("timeout") && boolean_field(request, op, "timeout");
      board_.gripper()->raise_errors(temperature, timeout);
    } else if (op == "reset_counters") {
      expect_fields(request, op, {});
      reset_counters();
    } else {
      throw RequestError("unknown op \"" + op + "\": expected one of " + kOps);
    }
    if (!options_.quiet) spdlog::info("control: {}", request.dump());
    return reply;
  } catch (const RequestError& error) {
    return sim_control::error_reply(error.what());
  } catch (const std::exception& error) {
    return sim_control::error_reply(std::string("the simulator failed on this request: ") + error.what());
  }
}

void Simulator::reset_counters() {
  bytes_received_ = 0;
  frames_received_ = 0;
  rejected_base_ = parser_.rejected();
  frames_unanswered_ = 0;
  replies_sent_ = 0;
  replies_dropped_ = 0;
  faults_.reset_counters();
}

json Simulator::state() const {
  const StepperArm& arm = board_.arm();
  json joints = json::array();
  json homed = json::array();
  for (std::size_t j = 0; j < arm.joints().size(); ++j) {
    const StepperJoint& joint = arm.joints()[j];
    joints.push_back({{"steps", joint.steps},
                      {"speed_steps_s", joint.speed_steps_s},
                      {"position_command_steps", arm.position_command()[j]},
                      {"speed_command_steps_s", arm.speed_command()[j]}});
    homed.push_back((arm.homed_mask() & (1U << j)) != 0);
  }
  return {{"ok", true},
          {"joints", joints},
          {"command", arm.command()},
          {"command_since_ns", command_since_ns_},
          {"enabled", !arm.disabled()},
          {"homed", homed},
          {"homed_byte", homed_byte(arm.homed_mask())},
          {"homing", arm.homing().active()},
          {"homing_phase", phase_text(arm.homing().phase())},
          {"io",
           {{"in1", board_.in1()},
            {"in2", board_.in2()},
            {"out1", (board_.outputs() & io::kOut1) != 0},
            {"out2", (board_.outputs() & io::kOut2) != 0},
            {"estop_pressed", board_.estop_pressed()},
            {"byte", board_.io_byte()}}},
          {"estop_pressed", board_.estop_pressed()},
          {"gripper", gripper_state(board_)},
          {"timing_ticks", board_.timing_ticks()},
          {"frames_received", frames_received_},
          {"frames_rejected", parser_.rejected() - rejected_base_},
          {"frames_unanswered", frames_unanswered_},
          {"replies_sent", replies_sent_},
          {"replies_dropped", replies_dropped_},
          {"bytes_received", bytes_received_},
          {"bytes_dropped", faults_.dropped()},
          {"bytes_garbled", faults_.garbled()},
          {"garbage_sent", faults_.garbage_sent()},
          {"pending",
           {{"drop_bytes", faults_.drop_pending()},
            {"garble", faults_.garble_pending()},
            {"garbage", faults_.garbage_pending()}}},
          {"silent", monotonic_ns() < silent_until_ns_},
          {"line",
           {{"open", line_open_},
            {"device", pty_.device_path()},
            {"link", options_.pty_path},
            {"host_connected", host_connected_}}}};
}

}  // namespace robotd::parol6::sim
