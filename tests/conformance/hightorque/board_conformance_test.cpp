// robotd's board codec against the livelybot USB-CDC board host SDK (the PI Plus path): the
// per-port command packets over several cycles (the SDK keeps every motor's slot between
// cycles), 0xB0 packets per motor model over a grid of values with the models of
// config/examples/hightorque.json, the SDK's motor table, state packets decoded, and the admin
// packets and acknowledged commands of its start-up.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hightorque_conformance.hpp"
#include "vector_file.hpp"

namespace robotd::hightorque::conformance {
namespace {

using nlohmann::json;
using robotd::conformance::hex_bytes;
using robotd::conformance::load_json_lines;

constexpr std::size_t kPayloadAt = kBoardHeaderSize;
constexpr double kTwoPi = 6.283185307179586;

using ScalingById = std::array<MotorScaling, kMaxBlockMotorId + 1>;

/// A port's motors with the example config's scaling of their models.
struct Port {
  ScalingById scaling{};
  int highest = 0;
  std::string missing_model;
};

Port port_of(const json& motors) {
  Port port;
  for (const json& motor : motors) {
    const int id = motor.at("id");
    const std::string model = motor.at("model");
    const auto found = example_models().find(model);
    if (found == example_models().end()) {
      port.missing_model = model;
    } else {
      port.scaling.at(static_cast<std::size_t>(id)) = found->second;
    }
    port.highest = std::max(port.highest, id);
  }
  return port;
}

struct SlotForm {
  BoardCommand command;
  std::vector<std::string> fields;  // the command's JSON keys in slot order
};

std::optional<SlotForm> slot_form(const std::string& mode) {
  static const std::map<std::string, SlotForm, std::less<>> forms{
      {"position", {BoardCommand::kPosition, {"position"}}},
      {"velocity", {BoardCommand::kVelocity, {"velocity"}}},
      {"torque", {BoardCommand::kTorque, {"torque"}}},
      {"voltage", {BoardCommand::kVoltage, {"voltage"}}},
      {"current", {BoardCommand::kCurrent, {"current"}}},
      {"pos_vel_kp_kd", {BoardCommand::kPositionVelocityKpKd, {"position", "velocity", "kp", "kd"}}},
      {"pos_vel_tqe", {BoardCommand::kPositionVelocityTorqueMax, {"position", "velocity", "torque"}}},
      {"pos_vel_tqe_kp_kd",
       {BoardCommand::kPositionVelocityTorqueKpKdV1, {"position", "velocity", "torque", "kp", "kd"}}},
      {"pos_vel_tqe_kp_kd2",
       {BoardCommand::kPositionVelocityTorqueKpKd, {"position", "velocity", "torque", "kp", "kd"}}},
  };
  const auto found = forms.find(mode);
  return found == forms.end() ? std::nullopt : std::optional<SlotForm>(found->second);
}

BlockSlot slot_of(const json& command) {
  BlockSlot slot;
  slot.motor = command.at("motor");
  slot.command.mode = Mode::kMit;
  slot.command.position_rad = command.at("position");
  slot.command.velocity_rad_s = command.at("velocity");
  slot.command.torque_nm = command.at("torque");
  slot.command.kp = command.at("kp");
  slot.command.kd = command.at("kd");
  slot.command.voltage_q_v = command.value("voltage", 0.0);
  slot.command.current_q_a = command.value("current", 0.0);
  return slot;
}

/// Counts the SDK would compute in exact arithmetic: beyond ±32767 its cast wraps.
double ideal_counts(const std::string& field, double value, const MotorScaling& scaling) {
  if (field == "position") return value / kTwoPi * 1e4;
  if (field == "velocity") return value / kTwoPi * 4e3;
  if (field == "torque") return (value - scaling.torque_offset_nm) / scaling.torque_per_unit;
  if (field == "voltage" || field == "current") return value * 10.0;
  return 0.0;  // gains saturate at ±32700 in the SDK too
}

/// Compares a packet; a payload field where robotd saturated a value the SDK wrapped is the
/// documented difference. `latest` holds each motor's last command (for the wrap check).
void judge_packet(std::string_view group, const std::string& what, const Bytes& expected, const Bytes& actual,
                  const SlotForm& form, const std::map<int, json>& latest, const Port& port) {
  const std::string detail = "vendor [" + hex(expected) + "]\nrobotd [" + hex(actual) + "]";
  if (expected == actual) {
    verdict(group, Outcome::passed, what);
    return;
  }
  const bool same_header = expected.size() == actual.size() && expected.size() >= kPayloadAt &&
                           std::equal(expected.begin(), expected.begin() + 4, actual.begin());
  if (!same_header) {
    verdict(group, Outcome::failed, what, detail);
    return;
  }
  const Bytes payload(actual.begin() + kPayloadAt, actual.end());
  const bool robotd_crcs_hold = actual[4] == board_crc8(std::span(actual).subspan(1, 3)) &&
                                int16_at(actual, 5) == static_cast<std::int16_t>(board_crc16(payload));
  for (std::size_t at = kPayloadAt; at + 1 < expected.size(); at += 2) {
    const std::int16_t vendor_value = int16_at(expected, at);
    const std::int16_t robotd_value = int16_at(actual, at);
    if (vendor_value == robotd_value) continue;
    const std::size_t field = (at - kPayloadAt) / 2;
    const int motor = static_cast<int>(field / form.fields.size()) + 1;
    const std::string& name = form.fields[field % form.fields.size()];
    const auto command = latest.find(motor);
    const double ideal = command == latest.end() ? 0.0
                                                 : ideal_counts(name, command->second.at(name).get<double>(),
                                                                port.scaling.at(static_cast<std::size_t>(motor)));
    const bool wrapped =
        std::abs(ideal) >= 32767.0 && std::abs(robotd_value) == 32767 && (ideal > 0) == (robotd_value > 0);
    if (!wrapped) {
      std::string why = detail;
      why += "\nfirst difference: motor " + std::to_string(motor) + " " + name;
      verdict(group, Outcome::failed, what, why);
      return;
    }
  }
  verdict(group, robotd_crcs_hold ? Outcome::deliberate_difference : Outcome::failed, what, detail, "board-int16-wrap");
}

/// Per-motor timeouts (the SDK's set_motorout): robotd's caller keeps each motor's timeout and
/// hands the codec all of them, as the SDK's buffer keeps them.
void judge_timeouts(std::string_view group, const json& vector) {
  const Port port = port_of(vector.at("motors"));
  std::vector<std::uint16_t> timeouts(static_cast<std::size_t>(port.highest), 0);
  int step_number = 0;
  for (const json& step : vector.at("steps")) {
    const std::string what =
        "timeout on motors " + vector.at("motors").dump() + ", cycle " + std::to_string(++step_number);
    for (const json& command : step.at("commands")) {
      timeouts.at(command.at("motor").get<std::size_t>() - 1) = command.at("timeout_ms").get<std::uint16_t>();
    }
    std::array<std::uint8_t, kBoardHeaderSize + kMaxBoardPayload> packet{};
    const Bytes robotd(packet.begin(), packet.begin() + encode_board_timeouts(timeouts, packet));
    const Bytes expected = hex_bytes(step.at("packet").get<std::string>());
    verdict(group, expected == robotd ? Outcome::passed : Outcome::failed, what,
            "vendor [" + hex(expected) + "]\nrobotd [" + hex(robotd) + "]");
  }
}

/// robotd does not encode 0xAD (differences.json "board-pos-vel-acc"): its slot buffer refuses it.
void judge_refused_pos_vel_acc(std::string_view group, const json& vector) {
  const Port port = port_of(vector.at("motors"));
  BoardSlotBuffer buffer(port.highest);
  int step_number = 0;
  for (const json& step : vector.at("steps")) {
    const std::string what =
        "pos_vel_acc on motors " + vector.at("motors").dump() + ", cycle " + std::to_string(++step_number);
    std::vector<BlockSlot> slots;
    for (const json& command : step.at("commands")) slots.push_back(slot_of(command));
    const bool refused = buffer.update(BoardCommand::kPositionVelocityAcceleration, slots, port.scaling).empty();
    verdict(group, refused ? Outcome::deliberate_difference : Outcome::failed, what, "robotd encoded a 0xAD payload",
            "board-pos-vel-acc");
  }
}

TEST(HighTorqueBoard, CommandPacketsKeepEveryMotorsSlotLikeTheSdk) {
  constexpr std::string_view kGroup = "board packets";
  for (const json& vector : load_json_lines("board_packets.jsonl")) {
    const std::string mode = vector.at("mode");
    if (mode == "timeout") {
      judge_timeouts(kGroup, vector);
      continue;
    }
    if (mode == "pos_vel_acc") {
      judge_refused_pos_vel_acc(kGroup, vector);
      continue;
    }
    const Port port = port_of(vector.at("motors"));
    BoardSlotBuffer buffer(port.highest);
    std::map<int, json> latest;
    int step_number = 0;
    for (const json& step : vector.at("steps")) {
      const std::string step_mode = step.value("mode", mode);
      const std::string what =
          mode + " on motors " + vector.at("motors").dump() + ", cycle " + std::to_string(++step_number);
      const std::optional<SlotForm> form = slot_form(step_mode);
      if (!form) {
        verdict(kGroup, Outcome::failed, what, "no slot form for " + step_mode);
        continue;
      }
      if (!port.missing_model.empty()) {
        verdict(kGroup, Outcome::failed, what, "config/examples/hightorque.json has no model " + port.missing_model);
        continue;
      }
      std::vector<BlockSlot> slots;
      for (const json& command : step.at("commands")) {
        slots.push_back(slot_of(command));
        latest[command.at("motor").get<int>()] = command;
      }
      const std::span<const std::uint8_t> payload = buffer.update(form->command, slots, port.scaling);
      std::array<std::uint8_t, kBoardHeaderSize + kMaxBoardPayload> packet{};
      const std::size_t size = encode_board_frame(form->command, payload, packet);
      judge_packet(kGroup, what, hex_bytes(step.at("packet").get<std::string>()),
                   Bytes(packet.begin(), packet.begin() + size), *form, latest, port);
    }
  }
}

TEST(HighTorqueBoard, EveryModelEncodesLikeTheSdkWithTheExampleConfig) {
  constexpr std::string_view kGroup = "board scaling";
  const SlotForm form = *slot_form("pos_vel_tqe_kp_kd2");
  for (const json& vector : load_json_lines("board_scaling.jsonl")) {
    const std::string model = vector.at("model");
    const json motors = json::array({{{"id", 1}, {"model", model}}});
    const Port port = port_of(motors);
    const std::string what = model + " " + vector.at("command").dump();
    if (!port.missing_model.empty()) {
      verdict(kGroup, Outcome::failed, what, "config/examples/hightorque.json has no model " + model);
      continue;
    }
    BoardSlotBuffer buffer(1);
    const std::array<BlockSlot, 1> slots{slot_of(vector.at("command"))};
    const std::span<const std::uint8_t> payload = buffer.update(form.command, slots, port.scaling);
    std::array<std::uint8_t, kBoardHeaderSize + kMaxBoardPayload> packet{};
    const std::size_t size = encode_board_frame(form.command, payload, packet);
    judge_packet(kGroup, what, hex_bytes(vector.at("packet").get<std::string>()),
                 Bytes(packet.begin(), packet.begin() + size), form, {{1, vector.at("command")}}, port);
  }
}

TEST(HighTorqueBoard, TheExampleConfigCarriesTheSdksMotorTable) {
  constexpr std::string_view kGroup = "board models";
  for (const json& vector : load_json_lines("board_models.jsonl")) {
    const std::string model = vector.at("model");
    const auto found = example_models().find(model);
    if (found == example_models().end()) {
      verdict(kGroup, Outcome::failed, model, "config/examples/hightorque.json has no model " + model);
      continue;
    }
    const MotorScaling& config = found->second;
    // The SDK's constants are read back through its float conversions: equal to 1e-6.
    const auto close = [](double a, double b) { return std::abs(a - b) <= 1e-6 * std::abs(b); };
    const bool same = close(config.torque_per_unit, vector.at("torque_per_unit")) &&
                      std::abs(config.torque_offset_nm - vector.at("torque_offset_nm").get<double>()) <= 1e-7 &&
                      close(config.gain_factor, vector.at("gain_factor"));
    verdict(kGroup, same ? Outcome::passed : Outcome::failed, model,
            "vendor " + vector.dump() + "\nconfig torque_per_unit " + std::to_string(config.torque_per_unit) +
                " torque_offset_nm " + std::to_string(config.torque_offset_nm) + " gain_factor " +
                std::to_string(config.gain_factor));
  }
}

TEST(HighTorqueBoard, StatePacketsDecodeLikeTheSdk) {
  constexpr std::string_view kGroup = "board replies";
  for (const json& vector : load_json_lines("board_replies.jsonl")) {
    const Bytes packet = hex_bytes(vector.at("packet").get<std::string>());
    const std::string what = "motors " + vector.at("motors").dump() + " packet [" + hex(packet) + "]";
    const Port port = port_of(vector.at("motors"));
    std::map<int, BoardMotorState> decoded;
    std::map<int, FirmwareVersion> versions;
    BoardFrameSplitter splitter;
    std::span<const std::uint8_t> rest(packet);
    while (!rest.empty()) {
      rest = rest.subspan(splitter.feed(rest));
      BoardFrame frame;
      while (splitter.next(frame)) {
        std::array<BoardMotorState, kMaxBlockMotorId> states{};
        const std::size_t count = decode_board_states(frame.command, frame.bytes(), port.scaling, states);
        for (std::size_t i = 0; i < count; ++i) decoded[states[i].motor] = states[i];
        std::array<FirmwareVersion, kMaxBlockMotorId> read{};
        if (frame.command == BoardCommand::kVersion) {
          const std::size_t read_count = decode_board_versions(frame.bytes(), read);
          for (std::size_t i = 0; i < read_count; ++i) versions[read[i].motor] = read[i];
        }
      }
    }
    std::string detail;
    for (const json& vendor : vector.at("vendor")) {
      const int id = vendor.at("id");
      const bool vendor_updated = vendor.at("position").get<double>() != 12345.0;
      const auto state = decoded.find(id);
      if (state == decoded.end()) {
        if (vendor_updated) detail += "motor " + std::to_string(id) + ": robotd read nothing; ";
      } else if (!vendor_updated || state->second.mode != vendor.at("mode").get<int>() ||
                 state->second.fault != vendor.at("fault").get<int>() ||
                 !same_float(state->second.position_rad, vendor.at("position")) ||
                 !same_float(state->second.velocity_rad_s, vendor.at("velocity")) ||
                 !same_float(state->second.torque_nm, vendor.at("torque"))) {
        detail += "motor " + std::to_string(id) + ": vendor " + vendor.dump() + " robotd position " +
                  std::to_string(state->second.position_rad) + " velocity " +
                  std::to_string(state->second.velocity_rad_s) + " torque " + std::to_string(state->second.torque_nm) +
                  "; ";
      }
      const json& v = vendor.at("version");
      const auto version = versions.find(id);
      const bool vendor_version = v[0] != 0 || v[1] != 0 || v[2] != 0;
      if (vendor_version != (version != versions.end()) ||
          (vendor_version &&
           (version->second.major != v[0] || version->second.minor != v[1] || version->second.patch != v[2]))) {
        detail += "motor " + std::to_string(id) + ": version differs; ";
      }
    }
    verdict(kGroup, detail.empty() ? Outcome::passed : Outcome::failed, what, detail);
  }
}

// The recorded start-up ran a port of 3 motors whose firmware gives function version 5.
constexpr int kRecordedMotorCount = 3;
constexpr BoardFunction kRecordedFunction = BoardFunction::kV5;

/// The admin packet robotd sends for an SDK call; nullopt where robotd has none.
std::optional<Bytes> admin_packet(const std::string& call, int motor_count) {
  static const std::map<std::string, std::pair<BoardCommand, int>, std::less<>> admin{
      {"stop", {BoardCommand::kStop, kBroadcastId}},
      {"reset", {BoardCommand::kReboot, kBroadcastId}},
      {"state", {BoardCommand::kMotorState, kBroadcastId}},
      {"state2", {BoardCommand::kMotorState2, kBroadcastId}},
      {"version", {BoardCommand::kVersion, kBroadcastId}},
      {"set_reset_zero", {BoardCommand::kResetZero, kBroadcastId}},
      {"set_reset_zero 2", {BoardCommand::kResetZero, 2}},
      {"set_conf_write", {BoardCommand::kSave, 2}},
      {"set_conf_load", {BoardCommand::kReloadConfig, kBroadcastId}},
      {"runzero", {BoardCommand::kRunToZero, kBroadcastId}},
      {"fdcan reset", {BoardCommand::kFdcanReset, 0}},
      {"set_fun_v", {BoardCommand::kSetFunctionVersion, static_cast<int>(kRecordedFunction)}},
      {"set_motor_num", {BoardCommand::kSetMotorCount, kRecordedMotorCount}},
  };
  std::array<std::uint8_t, kBoardHeaderSize + kMaxBoardPayload> packet{};
  std::size_t size = 0;
  if (const auto found = admin.find(call); found != admin.end()) {
    size = encode_board_admin(found->second.first, found->second.second, packet);
  } else if (call.rfind("timeout ", 0) == 0) {
    size = encode_board_timeout(static_cast<std::uint16_t>(std::stoi(call.substr(8))), motor_count, packet);
  } else {
    return std::nullopt;
  }
  return Bytes(packet.begin(), packet.begin() + size);
}

void judge_admin(std::string_view group, const std::string& what, const json& packets, int motor_count,
                 const std::string& call) {
  const std::optional<Bytes> robotd = admin_packet(call, motor_count);
  if (!robotd) {
    verdict(group, Outcome::not_implemented, what);
    return;
  }
  for (const json& packet : packets) {
    const Bytes expected = hex_bytes(packet.get<std::string>());
    if (expected != *robotd) {
      verdict(group, Outcome::failed, what, "vendor [" + hex(expected) + "]\nrobotd [" + hex(*robotd) + "]");
      return;
    }
  }
  verdict(group, Outcome::passed, what);
}

TEST(HighTorqueBoard, AdminPacketsMatchTheSdk) {
  for (const json& vector : load_json_lines("board_admin_packets.jsonl")) {
    const std::string call = vector.at("call");
    judge_admin("board admin packets", call, vector.at("packets"), static_cast<int>(vector.at("motors").size()), call);
  }
}

/// The SDK repeats 0x05 until the board names a firmware of 2.0 or later (its result: the
/// version × 10) and 0x0C until the board echoes the function version sent: robotd's driver
/// stops after the same answer.
void judge_answered_start_up(std::string_view group, const std::string& what, const json& vector, BoardCommand command,
                             std::size_t host_packets) {
  std::size_t answers = 0;
  int result = -1;
  for (const json& line : vector.at("transcript")) {
    const std::string text = line;
    if (text.rfind("board ", 0) != 0) continue;
    ++answers;
    const Bytes packet = hex_bytes(text.substr(6));
    const std::span<const std::uint8_t> payload = std::span(packet).subspan(kPayloadAt);
    if (command == BoardCommand::kSetMotorCount) {
      const std::optional<BoardFirmware> firmware = decode_board_firmware(payload);
      if (firmware && firmware->major >= 2) {
        result = firmware->tenths();
        break;
      }
    } else if (!payload.empty() && payload[0] == static_cast<std::uint8_t>(kRecordedFunction)) {
      result = 0;
      break;
    }
  }
  const bool same = answers == host_packets && result == vector.at("result").get<int>();
  verdict(group, same ? Outcome::passed : Outcome::failed, what,
          "the SDK sent " + std::to_string(host_packets) + " packet(s) and got " + vector.at("result").dump() +
              "; robotd would stop after answer " + std::to_string(answers) + " with " + std::to_string(result));
}

/// The SDK sends an acknowledged command again until every motor it names has answered: robotd's
/// driver does the same with the ids it decodes from the board's answers, so it must stop after
/// the same answer.
void judge_acknowledgements(std::string_view group, const std::string& what, const json& vector,
                            std::size_t host_packets) {
  const Bytes first_host = hex_bytes(vector.at("transcript").at(0).get<std::string>().substr(5));
  const auto command = static_cast<BoardCommand>(first_host.at(1));
  if (command == BoardCommand::kSetMotorCount || command == BoardCommand::kSetFunctionVersion) {
    judge_answered_start_up(group, what, vector, command, host_packets);
    return;
  }
  std::set<int> named;
  if (first_host.at(kPayloadAt) == kBroadcastId) {
    for (const json& motor : vector.at("motors")) named.insert(motor.at("id").get<int>());
  } else {
    named.insert(first_host.at(kPayloadAt));
  }
  std::set<int> acknowledged;
  std::size_t answers = 0;
  for (const json& line : vector.at("transcript")) {
    const std::string text = line;
    if (text.rfind("board ", 0) != 0) continue;
    ++answers;
    const Bytes packet = hex_bytes(text.substr(6));
    std::array<CommandResult, kMaxBlockMotorId> results{};
    const std::size_t count = decode_board_acknowledgements(command, std::span(packet).subspan(kPayloadAt), results);
    for (std::size_t i = 0; i < count; ++i) acknowledged.insert(results[i].motor);
    if (std::includes(acknowledged.begin(), acknowledged.end(), named.begin(), named.end())) break;
  }
  const bool same = answers == host_packets && vector.at("result").get<int>() == 0;
  verdict(group, same ? Outcome::passed : Outcome::failed, what,
          "the SDK sent " + std::to_string(host_packets) + " packet(s); robotd would stop after answer " +
              std::to_string(answers));
}

TEST(HighTorqueBoard, StartUpCommandsMatchTheSdk) {
  constexpr std::string_view kGroup = "board start-up";
  for (const json& vector : load_json_lines("board_start_up.jsonl")) {
    const std::string call = vector.at("call");
    json host = json::array();
    for (const json& line : vector.at("transcript")) {
      const std::string text = line;
      if (text.rfind("host ", 0) == 0) host.push_back(text.substr(5));
    }
    judge_admin(kGroup, call + ": what the host sends", host, static_cast<int>(vector.at("motors").size()), call);
    judge_acknowledgements(kGroup, call + ": acknowledged after as many packets as the SDK sent", vector, host.size());
  }
}

}  // namespace
}  // namespace robotd::hightorque::conformance
