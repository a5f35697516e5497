// The control channel's ops (README.md in this folder): what tests ask the simulator to report
// or to do wrong.
#include <array>
#include <cstdio>
#include <linux/can/error.h>
#include <stdexcept>
#include <string>

#include <spdlog/spdlog.h>

#include "robotd/sim_control/control_request.hpp"
#include "simulator.hpp"

namespace robotd::piper::sim {
namespace {

using nlohmann::json;
using sim_control::boolean_field;
using sim_control::expect_fields;
using sim_control::integer_field;
using sim_control::number_field;
using sim_control::RequestError;

constexpr std::int64_t kMaxDurationMs = 3'600'000;
constexpr std::int64_t kMaxGarbageFrames = 100'000;
constexpr const char* kOps =
    "state, reset_counters, silence, drop_replies, garbage, bus_error, raise_error, clear_error, disconnect, "
    "set_joint, set_gripper, restart";

std::string id_text(std::uint32_t key) {
  std::array<char, 16> text{};
  if ((key & 0x80000000U) != 0) {
    std::snprintf(text.data(), text.size(), "0x%08X", key & 0x1FFFFFFFU);  // extended id
  } else {
    std::snprintf(text.data(), text.size(), "0x%03X", key);
  }
  return text.data();
}

json pose_json(const CartesianPose& pose) {
  return {{"x_m", pose.x_m},       {"y_m", pose.y_m},       {"z_m", pose.z_m},
          {"rx_rad", pose.rx_rad}, {"ry_rad", pose.ry_rad}, {"rz_rad", pose.rz_rad}};
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
    if (op == "reset_counters") {
      expect_fields(request, op, {});
      frames_received_.clear();
      frames_sent_ = 0;
    } else if (op == "silence") {
      expect_fields(request, op, {"ms"});
      const std::int64_t ms = integer_field(request, op, "ms", 0, kMaxDurationMs);
      silent_until_ns_ = now + ms * 1'000'000;
    } else if (op == "drop_replies") {
      expect_fields(request, op, {"enabled"});
      drop_replies_ = boolean_field(request, op, "enabled");
    } else if (op == "garbage") {
      expect_fields(request, op, {"frames"});
      const std::int64_t frames = integer_field(request, op, "frames", 1, kMaxGarbageFrames);
      garbage_pending_ += frames;
      reply["queued"] = garbage_pending_;
    } else if (op == "bus_error") {
      // What a CAN controller reports to SocketCAN readers: an error frame, here bus-off.
      expect_fields(request, op, {});
      CanMessage error_frame;
      error_frame.error_frame = true;
      error_frame.id = CAN_ERR_BUSOFF;
      error_frame.length = CAN_ERR_DLC;
      send(error_frame);
    } else if (op == "raise_error") {
      reply = raise_error(request);
    } else if (op == "clear_error") {
      expect_fields(request, op, {});
      arm_.clear_errors();
    } else if (op == "disconnect") {
      expect_fields(request, op, {"ms"});
      const std::int64_t ms = integer_field(request, op, "ms", 0, kMaxDurationMs);
      bus_->close();  // every node sees its connection end
      bus_open_ = false;
      reopen_bus_at_ns_ = now + ms * 1'000'000;
    } else if (op == "set_joint") {
      expect_fields(request, op, {"joint", "position_rad"});
      const auto joint = static_cast<int>(integer_field(request, op, "joint", 1, kArmJoints));
      const double position = number_field(request, op, "position_rad");
      if (!arm_.teleport(joint, position)) {
        const JointSettings& limits = arm_.settings().joints.at(static_cast<std::size_t>(joint - 1));
        throw RequestError("op \"set_joint\": position_rad " + std::to_string(position) + " is outside joint " +
                           std::to_string(joint) + "'s limits [" + std::to_string(limits.min_rad) + ", " +
                           std::to_string(limits.max_rad) + "] rad");
      }
    } else if (op == "set_gripper") {
      expect_fields(request, op, {"stroke_m"});
      const double stroke = number_field(request, op, "stroke_m");
      if (!arm_.place_gripper(stroke)) {
        throw RequestError("op \"set_gripper\": stroke_m " + std::to_string(stroke) + " is outside 0 … " +
                           std::to_string(arm_.max_gripper_stroke_m()) + " m");
      }
    } else if (op == "restart") {
      expect_fields(request, op, {});
      restart();
      reply["role"] = leader_ ? "leader" : "follower";
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

json Simulator::raise_error(const json& request) {
  const std::string op = "raise_error";
  expect_fields(request, op, {"arm_status", "joint", "driver_status_bits", "comm_error", "gripper_status_bits"});
  const bool has_joint = request.contains("joint");
  const bool joint_fields = request.contains("driver_status_bits") || request.contains("comm_error");
  if (has_joint != joint_fields) {
    throw RequestError(
        "op \"raise_error\": \"joint\" (1 … 6) goes with \"driver_status_bits\" (0 … 255) and/or "
        "\"comm_error\" (true/false)");
  }
  if (!has_joint && !request.contains("arm_status") && !request.contains("gripper_status_bits")) {
    throw RequestError(
        "op \"raise_error\" needs one of: {\"arm_status\": 0 … 255}, {\"joint\": 1 … 6, \"driver_status_bits\": "
        "0 … 255}, {\"joint\": 1 … 6, \"comm_error\": true}, {\"gripper_status_bits\": 0 … 255}");
  }
  // Check everything before changing anything.
  std::optional<std::uint8_t> arm_status;
  std::optional<std::uint8_t> driver_bits;
  std::optional<bool> comm_error;
  std::optional<std::uint8_t> gripper_bits;
  int joint = 0;
  if (request.contains("arm_status"))
    arm_status = static_cast<std::uint8_t>(integer_field(request, op, "arm_status", 0, 255));
  if (has_joint) joint = static_cast<int>(integer_field(request, op, "joint", 1, kArmJoints));
  if (request.contains("driver_status_bits")) {
    driver_bits = static_cast<std::uint8_t>(integer_field(request, op, "driver_status_bits", 0, 255));
  }
  if (request.contains("comm_error")) comm_error = boolean_field(request, op, "comm_error");
  if (request.contains("gripper_status_bits")) {
    gripper_bits = static_cast<std::uint8_t>(integer_field(request, op, "gripper_status_bits", 0, 255));
  }
  if (arm_status) arm_.inject_arm_status(*arm_status);
  if (driver_bits) arm_.inject_driver_bits(joint, *driver_bits);
  if (comm_error) arm_.inject_comm_error(joint, *comm_error);
  if (gripper_bits) arm_.inject_gripper_bits(*gripper_bits);
  return {{"ok", true}, {"arm_status", arm_.arm_status()}};
}

json Simulator::state() const {
  json joints = json::array();
  for (std::size_t i = 0; i < arm_.joints().size(); ++i) {
    const SimJoint& joint = arm_.joints()[i];
    const JointSettings& limits = arm_.settings().joints[i];
    joints.push_back({{"position_rad", joint.position_rad},
                      {"velocity_rad_s", joint.velocity_rad_s},
                      {"enabled", joint.enabled},
                      {"target_rad", joint.target_rad},
                      {"torque_nm", joint.torque_nm},
                      {"mit", joint.mit.has_value()},
                      {"min_rad", limits.min_rad},
                      {"max_rad", limits.max_rad},
                      {"max_speed_rad_s", limits.max_speed_rad_s},
                      {"max_acc_rad_s2", limits.max_acc_rad_s2},
                      {"driver_status_bits", joint.injected_driver_bits},
                      {"comm_error", joint.comm_error}});
  }
  const SimGripper& gripper = arm_.gripper();
  json received = json::object();
  for (const auto& [key, count] : frames_received_) received[id_text(key)] = count;
  return {{"ok", true},
          {"joints", joints},
          {"gripper",
           {{"stroke_m", gripper.stroke_m},
            {"target_m", gripper.target_m},
            {"effort_nm", gripper.effort_nm},
            {"enabled", gripper.enabled},
            {"max_stroke_m", arm_.max_gripper_stroke_m()}}},
          {"end_pose", pose_json(arm_.end_pose())},
          {"ctrl_mode", static_cast<int>(arm_.ctrl_mode())},
          {"move_mode", static_cast<int>(arm_.move_mode())},
          {"mit", arm_.mit()},
          {"speed_percent", arm_.speed_percent()},
          {"installation", arm_.installation()},
          {"teach_status", arm_.teach_status()},
          {"arm_status", arm_.arm_status()},
          {"motion_status", arm_.motion_status()},
          {"angle_limit_bits", arm_.angle_limit_bits()},
          {"comm_error_bits", arm_.comm_error_bits()},
          {"estop", arm_.estop()},
          {"estop_since_ns", arm_.estop() ? estop_since_ns_ : 0},
          {"collision_levels", arm_.settings().collision_levels},
          {"payload", arm_.settings().payload},
          {"master_slave", arm_.settings().master_slave.linkage},
          {"master_slave_offsets",
           {arm_.settings().master_slave.feedback_offset, arm_.settings().master_slave.control_offset,
            arm_.settings().master_slave.linkage_offset}},
          {"role", leader_ ? "leader" : "follower"},
          {"feedback_id_offset", codec_.feedback_id_offset},
          {"control_id_offset", codec_.control_id_offset},
          {"frames_received", received},
          {"frames_sent", frames_sent_},
          {"bus_open", bus_open_},
          {"drop_replies", drop_replies_},
          {"silent", monotonic_ns() < silent_until_ns_},
          {"garbage_pending", garbage_pending_},
          {"firmware", controller_.software_version()}};
}

}  // namespace robotd::piper::sim
