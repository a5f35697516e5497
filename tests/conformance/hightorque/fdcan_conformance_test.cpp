// robotd's CAN-FD codec against the HighTorque motor firmware SDK (motor_fdcan_h730): the frames
// of every single-motor builder over a grid of values at each width, the system commands, the
// one-to-many block frames (30 and 7 motors a port) and the fields its parser reads from crafted
// replies.
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hightorque_conformance.hpp"
#include "vector_file.hpp"

namespace robotd::hightorque::conformance {
namespace {

using nlohmann::json;
using robotd::conformance::hex_bytes;
using robotd::conformance::load_json_lines;

Width width_of(const std::string& name) {
  if (name == "int16") return Width::kInt16;
  if (name == "int32") return Width::kInt32;
  if (name == "float") return Width::kFloat;
  throw std::invalid_argument("unknown width " + name);
}

std::optional<Mode> mode_of(const std::string& call) {
  static const std::map<std::string, Mode, std::less<>> modes{
      {"mit", Mode::kMit},
      {"position", Mode::kPosition},
      {"velocity", Mode::kVelocity},
      {"torque", Mode::kTorque},
      {"voltage", Mode::kVoltage},
      {"current", Mode::kCurrent},
      {"pos_vel_tqe", Mode::kPositionVelocityTorque},
      {"pos_vel_acc", Mode::kPositionVelocityAcceleration},
      {"vel_acc", Mode::kVelocityAcceleration},
      {"stop", Mode::kStop},
      {"brake", Mode::kBrake},
  };
  const auto found = modes.find(call);
  return found == modes.end() ? std::nullopt : std::optional<Mode>(found->second);
}

/// The vendor call's arguments (radians, N·m, …: the SDK ran in its RADIAN_2PI configuration)
/// as robotd's command.
MotorCommand command_of(Mode mode, const json& args) {
  MotorCommand command;
  command.mode = mode;
  command.position_rad = args.value("position", 0.0);
  command.velocity_rad_s = args.value("velocity", 0.0);
  command.acceleration_rad_s2 = args.value("acceleration", 0.0);
  command.torque_nm = args.value("torque", 0.0);
  command.kp = args.value("kp", 0.0);
  command.kd = args.value("kd", 0.0);
  command.voltage_q_v = args.value("voltage_q", 0.0);
  command.current_q_a = args.value("current_q", 0.0);
  return command;
}

struct Comparison {
  Outcome outcome = Outcome::passed;
  std::string detail;
  std::string difference;
};

/// robotd's padding byte at `at` of a block frame of `length` bytes with `slot_bytes`-byte
/// slots: unset slots (00 80) where whole ones fit before the query byte, 0 after them.
std::uint8_t robotd_padding(std::size_t at, std::size_t length, std::size_t slot_bytes) {
  const bool in_whole_slot = slot_bytes > 1 && (at / slot_bytes + 1) * slot_bytes <= length - 1;
  return in_whole_slot && at % 2 == 1 ? 0x80 : 0x00;
}

/// A recorded frame against robotd's. int16 fields start at `fields_from`; a block frame
/// (`block_slot_bytes` > 0) pads from the vendor's data_bytes to its last (query) byte.
Comparison compare_frame(const json& vendor, const transport::CanMessage& robotd, Width width, std::size_t fields_from,
                         std::size_t block_slot_bytes) {
  const Bytes expected = hex_bytes(vendor.at("data").get<std::string>());
  const Bytes actual = bytes_of(robotd);
  const auto expected_id = vendor.at("id").get<std::uint32_t>();
  Comparison result;
  result.detail = "vendor id " + std::to_string(expected_id) + " [" + hex(expected) + "]\nrobotd id " +
                  std::to_string(robotd.id) + " [" + hex(actual) + "]";
  if (robotd.id != expected_id || actual.size() != expected.size() || !robotd.extended || !robotd.fd) {
    result.outcome = Outcome::failed;
    return result;
  }
  const std::size_t data_bytes = vendor.value("data_bytes", expected.size());
  for (std::size_t at = 0; at < expected.size(); ++at) {
    if (expected[at] == actual[at]) continue;
    if (block_slot_bytes > 0 && at >= data_bytes && at + 1 < expected.size() &&
        actual[at] == robotd_padding(at, expected.size(), block_slot_bytes)) {
      result.difference = "block-padding";
      continue;
    }
    const std::size_t field = at - (at - fields_from) % 2;
    const bool int16_field = width == Width::kInt16 && at >= fields_from && field + 1 < data_bytes;
    if (int16_field && static_cast<std::uint16_t>(int16_at(expected, field)) == 0x8000U &&
        static_cast<std::uint16_t>(int16_at(actual, field)) == 0x8001U) {
      result.difference = "negative-saturation";
      continue;
    }
    result.outcome = Outcome::failed;
    return result;
  }
  if (!result.difference.empty()) result.outcome = Outcome::deliberate_difference;
  return result;
}

void judge(std::string_view group, const std::string& what, const json& vendor_frames,
           const std::vector<transport::CanMessage>& robotd, Width width, std::size_t fields_from,
           std::size_t block_slot_bytes = 0) {
  if (vendor_frames.size() != robotd.size()) {
    std::string detail =
        "vendor sent " + std::to_string(vendor_frames.size()) + " frame(s), robotd " + std::to_string(robotd.size());
    for (const transport::CanMessage& message : robotd) detail += "\nrobotd [" + hex(bytes_of(message)) + "]";
    verdict(group, Outcome::failed, what, detail);
    return;
  }
  Comparison total;
  for (std::size_t i = 0; i < robotd.size(); ++i) {
    const Comparison one = compare_frame(vendor_frames[i], robotd[i], width, fields_from, block_slot_bytes);
    if (one.outcome == Outcome::failed) {
      verdict(group, Outcome::failed, what, "frame " + std::to_string(i) + ":\n" + one.detail);
      return;
    }
    if (one.outcome == Outcome::deliberate_difference) total = one;
  }
  verdict(group, total.outcome, what, total.detail, total.difference);
}

TEST(HighTorqueFdcan, SingleMotorFramesMatchTheFirmwareSdk) {
  constexpr std::string_view kGroup = "CAN-FD single frames";
  for (const json& vector : load_json_lines("fdcan_single_frames.jsonl")) {
    const std::string call = vector.at("call");
    const Width width = width_of(vector.at("width"));
    const int motor = vector.at("motor");
    const std::string what = call + " " + vector.at("width").get<std::string>() + " " + vector.at("args").dump();
    transport::CanMessage robotd;
    if (call == "query") {
      robotd = encode_query(motor, Query::kState, width);
    } else {
      robotd =
          encode_command(motor, command_of(*mode_of(call), vector.at("args")), width, Query::kState, MotorScaling{});
    }
    judge(kGroup, what, vector.at("frames"), {robotd}, width, 2);
  }
}

std::optional<transport::CanMessage> system_frame(const std::string& call, int motor, const json& args) {
  if (call == "set_zero") return encode_set_zero(motor);
  if (call == "save_to_flash") return encode_save_to_flash(motor);
  if (call == "soft_reboot") return encode_soft_reboot(motor);
  if (call == "firmware_version") return encode_info_request(motor, InfoKind::kFirmwareVersion);
  if (call == "hardware_version") return encode_info_request(motor, InfoKind::kHardwareVersion);
  if (call == "model") return encode_info_request(motor, InfoKind::kModel);
  if (call == "status_push") return encode_status_push(motor, Query::kState, args.at("period_us").get<std::uint32_t>());
  if (call == "change_id") {
    const Result<transport::CanMessage> frame = encode_change_id(motor, args.at("new_id").get<int>());
    if (!frame) return std::nullopt;
    return frame.value();
  }
  throw std::invalid_argument("unknown system call " + call);
}

TEST(HighTorqueFdcan, SystemCommandsMatchTheFirmwareSdk) {
  constexpr std::string_view kGroup = "CAN-FD system commands";
  for (const json& vector : load_json_lines("fdcan_system_commands.jsonl")) {
    const std::string call = vector.at("call");
    const std::string what =
        call + " motor " + std::to_string(vector.at("motor").get<int>()) + " " + vector.at("args").dump();
    const std::optional<transport::CanMessage> robotd = system_frame(call, vector.at("motor"), vector.at("args"));
    std::vector<transport::CanMessage> frames;
    if (robotd) frames.push_back(*robotd);
    judge(kGroup, what, vector.at("frames"), frames, Width::kInt16, 3);
  }
}

/// Bytes per motor in a block frame (motor_many.c get_mode_data_len).
std::size_t slot_bytes(const std::string& call) {
  if (call == "mit") return 10;
  if (call == "pos_vel_tqe" || call == "pos_vel_acc") return 6;
  if (call == "vel_acc") return 4;
  if (call == "stop" || call == "brake" || call == "soft_reboot" || call == "set_zero") return 1;
  return 2;
}

TEST(HighTorqueFdcan, BlockFramesMatchTheFirmwareSdk) {
  constexpr std::string_view kGroup = "CAN-FD block frames";
  const std::array<MotorScaling, kMaxBlockMotorId + 1> scaling{};
  for (const json& vector : load_json_lines("fdcan_block_frames.jsonl")) {
    const std::string call = vector.at("call");
    const int motors = vector.at("motors");
    const std::string what =
        call + " on a port of " + std::to_string(motors) + " motors, slots " + vector.at("slots").dump();
    const auto query = static_cast<Query>(vector.at("query").get<int>());
    std::array<transport::CanMessage, 8> out{};
    const std::optional<Mode> mode = mode_of(call);
    if (!mode) {  // the reboot and rezero blocks (0x87, 0x88): one flag byte per motor
      std::vector<int> flagged;
      for (const json& slot : vector.at("slots")) flagged.push_back(slot.at("motor"));
      const BlockSystem what_block = call == "soft_reboot" ? BlockSystem::kSoftReboot : BlockSystem::kSetZero;
      const std::size_t count = encode_block_system(what_block, flagged, query, motors, out);
      json frames = vector.at("frames");
      for (json& frame : frames) frame["data_bytes"] = static_cast<std::size_t>(motors);
      judge(kGroup, what, frames, {out.begin(), out.begin() + static_cast<std::ptrdiff_t>(count)}, Width::kInt16, 0,
            slot_bytes(call));
      continue;
    }
    std::vector<BlockSlot> slots;
    for (const json& slot : vector.at("slots")) slots.push_back(BlockSlot{slot.at("motor"), command_of(*mode, slot)});
    // motor_many_send() hands fdcan_send() whole frames: its slots are the first 60 bytes at most
    // of the port's slot_bytes × motors, the rest up to the query code is padding.
    json frames = vector.at("frames");
    const std::size_t total = slot_bytes(call) * static_cast<std::size_t>(motors);
    for (std::size_t i = 0; i < frames.size(); ++i) frames[i]["data_bytes"] = std::min<std::size_t>(60, total - 60 * i);
    const std::size_t count = encode_block(slots, query, scaling, motors, out);
    judge(kGroup, what, frames, {out.begin(), out.begin() + static_cast<std::ptrdiff_t>(count)}, Width::kInt16, 0,
          slot_bytes(call));
  }
}

/// One reply field: equal, or the documented difference.
struct FieldCheck {
  bool same = true;
  std::string difference;
  std::string detail;
};

void compare_state(const json& vendor, const MotorState& state, std::uint8_t code, FieldCheck& check) {
  const auto expect = [&](bool same, const std::string& field) {
    if (!same) {
      check.same = false;
      check.detail += field + " differs; ";
    }
  };
  if (code != 0x0E) expect(state.mode == vendor.at("mode").get<int>(), "mode");
  expect(state.fault == vendor.at("fault").get<int>(), "fault");
  expect(same_float(state.position_rad, vendor.at("position")), "position");
  expect(same_float(state.velocity_rad_s, vendor.at("velocity")), "velocity");
  expect(same_float(state.torque_nm, vendor.at("torque")), "torque");
  check.detail += "robotd position " + std::to_string(state.position_rad) + " velocity " +
                  std::to_string(state.velocity_rad_s) + " torque " + std::to_string(state.torque_nm);
  if (code == 0x0C && check.same) {
    const double temperature = state.temperature_c.value_or(NAN);
    // The SDK stores the truncated reading in an int8_t: x86 truncates to 32 bits, then the byte
    // wraps (-3276.8 degrees reads as 52). Converting a double straight to int8_t is undefined.
    const auto whole_degrees = static_cast<std::int8_t>(static_cast<std::int32_t>(std::trunc(temperature)));
    if (whole_degrees != vendor.at("temperature").get<int>()) {
      check.same = false;
      check.detail += "; temperature " + std::to_string(temperature);
    } else if (temperature != vendor.at("temperature").get<double>()) {
      check.difference = "temperature-resolution";
    }
  }
}

TEST(HighTorqueFdcan, RepliesDecodeLikeTheFirmwareSdk) {
  constexpr std::string_view kGroup = "CAN-FD replies";
  for (const json& vector : load_json_lines("fdcan_replies.jsonl")) {
    transport::CanMessage message;
    message.id = vector.at("id");
    message.extended = true;
    message.fd = true;
    const Bytes data = hex_bytes(vector.at("data").get<std::string>());
    std::copy(data.begin(), data.end(), message.data.begin());
    message.length = static_cast<std::uint8_t>(data.size());
    const std::string what = "reply id " + std::to_string(message.id) + " [" + hex(data) + "]";
    const json& vendor = vector.at("vendor");
    const std::optional<Reply> reply = decode_reply(message, kMaxMotorId, MotorScaling{});
    const bool vendor_read = vendor.at("parsed_motor").get<bool>() && (message.id & 0x8000U) == 0;
    const std::uint8_t code = data.at(0);
    const bool vendor_skips = code == 0x05 || code == 0x0A;
    if (!vendor_read) {
      verdict(kGroup, reply ? Outcome::failed : Outcome::passed, what, "the vendor ignores it; robotd decoded it");
      continue;
    }
    if (!reply) {
      verdict(kGroup, Outcome::failed, what, "robotd did not decode it");
      continue;
    }
    FieldCheck check;
    switch (code) {
      case 0x0B:
      case 0x0C:
      case 0x0E:
        compare_state(vendor, reply->state, code, check);
        break;
      case 0x04: {
        const json& v = vendor.at("version");
        check.same = reply->version.major == v[0] && reply->version.minor == v[1] && reply->version.patch == v[2];
        break;
      }
      case 0x07: {
        const std::string name = reply->model.text.data();
        const std::string vendor_name = vendor.at("model");
        check.same = name == vendor_name;
        if (!check.same && vendor_name.empty() && name.size() > 15) check = {true, "replies-the-vendor-skips", {}};
        break;
      }
      case 0x03:
        check.same = reply->result.success == (vendor.at("ack").get<int>() == 1);
        break;
      default:
        check.same = vendor_skips;
        if (vendor_skips) check.difference = "replies-the-vendor-skips";
        break;
    }
    const Outcome outcome = !check.same                ? Outcome::failed
                            : check.difference.empty() ? Outcome::passed
                                                       : Outcome::deliberate_difference;
    verdict(kGroup, outcome, what, "vendor " + vendor.dump() + "\n" + check.detail, check.difference);
  }
}

}  // namespace
}  // namespace robotd::hightorque::conformance
