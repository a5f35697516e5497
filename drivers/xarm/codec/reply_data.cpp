// The data after a reply's status byte (§4.1, §8), read by the driver and written by the
// simulator.
#include <algorithm>
#include <array>
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "wire_fields.hpp"
#include "xarm_codec.hpp"

namespace robotd::xarm {
namespace {

constexpr std::size_t kVersionBytes = 40;
constexpr std::size_t kRobotSnBytes = 40;
constexpr std::string_view kVersionLayout = "axis,type,robotSN,controlboxSN,vMAJ.MIN.REV";
constexpr std::size_t kServoPairsBytes = 16;
constexpr std::size_t kServoStatusByte = 1;  // the doc example's leading execution status

/// Refuses data shorter than `expected` bytes.
Result<void> check_data(std::string_view reply, ByteView data, std::size_t expected) {
  if (data.size() >= expected) return {};
  return size_error(std::string(reply) + " reply", "data byte", data.size(), expected, true);
}

std::string_view trimmed(std::string_view text) {
  const auto first = text.find_first_not_of(' ');
  if (first == std::string_view::npos) return {};
  return text.substr(first, text.find_last_not_of(' ') - first + 1);
}

/// Text NUL padded into `size` bytes, cut at `size`.
Bytes padded_text(const std::string& text, std::size_t size) {
  Bytes data(size, 0);
  std::copy_n(text.begin(), std::min(text.size(), size), data.begin());
  return data;
}

/// The text as printable ASCII, for quoting what a controller sent.
std::string printable(std::string_view text) {
  std::string out;
  for (const char c : text) out += (c >= 0x20 && c < 0x7F) ? c : '?';
  return out;
}

/// The comma-separated fields of the version text (up to its first NUL).
std::vector<std::string_view> version_fields(std::string_view text) {
  std::vector<std::string_view> fields;
  while (true) {
    const auto comma = text.find(',');
    fields.push_back(trimmed(text.substr(0, comma)));
    if (comma == std::string_view::npos) return fields;
    text.remove_prefix(comma + 1);
  }
}

Result<int> version_number(std::string_view text, const std::vector<std::string_view>& fields, std::size_t index,
                           std::string_view name) {
  const std::string_view field = index < fields.size() ? fields[index] : std::string_view{};
  if (!field.empty()) {
    int value = 0;
    const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
    if (error == std::errc{} && end == field.data() + field.size()) return value;
  }
  const std::string problem =
      field.empty() ? "has no " + std::string(name) : "has \"" + printable(field) + "\" as " + std::string(name);
  return make_error(ErrorCode::kInvalidArgument, "get_version reply \"" + printable(text) + "\" " + problem +
                                                     ": expected a number there in \"" + std::string(kVersionLayout) +
                                                     "\"");
}

}  // namespace

Result<Version> parse_version(ByteView data) {
  const std::string_view raw(reinterpret_cast<const char*>(data.data()), data.size());
  const std::string_view text = raw.substr(0, raw.find('\0'));
  const auto fields = version_fields(text);
  const auto axes = version_number(text, fields, 0, "axis count");
  if (!axes) return axes.error();
  const auto type = version_number(text, fields, 1, "device type");
  if (!type) return type.error();
  const auto field = [&fields](std::size_t index) {
    return index < fields.size() ? printable(fields[index]) : std::string();
  };
  Version version{.axes = axes.value(),
                  .type = type.value(),
                  .robot_sn = field(2),
                  .control_box_sn = field(3),
                  .firmware = field(4)};
  if (!version.firmware.empty() && (version.firmware.front() == 'v' || version.firmware.front() == 'V')) {
    version.firmware.erase(0, 1);
  }
  return version;
}

Bytes encode_version(const Version& version) {
  const std::string text = std::to_string(version.axes) + "," + std::to_string(version.type) + "," + version.robot_sn +
                           "," + version.control_box_sn + ",v" + version.firmware;
  return padded_text(text, kVersionBytes);
}

Result<SerialNumbers> parse_robot_sn(ByteView data) {
  if (auto checked = check_data("get_robot_sn", data, kRobotSnBytes); !checked) return checked.error();
  const std::string_view text(reinterpret_cast<const char*>(data.data()), kRobotSnBytes);
  const auto robot_end = std::min(text.find('\0'), text.size());
  // A robot SN that fills all 40 bytes leaves no room for the control box's.
  const std::string_view rest = text.substr(std::min(robot_end + 1, text.size()));
  return SerialNumbers{.robot_sn = printable(trimmed(text.substr(0, robot_end))),
                       .control_box_sn = printable(trimmed(rest.substr(0, rest.find('\0'))))};
}

Bytes encode_robot_sn(const SerialNumbers& serials) {
  return padded_text(serials.robot_sn + '\0' + serials.control_box_sn, kRobotSnBytes);
}

Result<int> parse_state(ByteView data) {
  if (auto checked = check_data("get_state", data, 1); !checked) return checked.error();
  return static_cast<int>(data[0]);
}

Bytes encode_state(int state) { return ByteWriter().u8(static_cast<std::uint8_t>(state)).take(); }

Result<std::uint16_t> parse_cmdnum(ByteView data) {
  if (auto checked = check_data("command count", data, 2); !checked) return checked.error();
  ByteReader reader(data);
  return reader.u16_be().value_or(0);
}

Bytes encode_cmdnum(std::uint16_t count) { return ByteWriter().u16_be(count).take(); }

Result<ErrorWarning> parse_err_code(ByteView data) {
  if (auto checked = check_data("get_err_code", data, 2); !checked) return checked.error();
  return ErrorWarning{.error = data[0], .warning = data[1]};
}

Bytes encode_err_code(const ErrorWarning& codes) {
  return ByteWriter().u8(static_cast<std::uint8_t>(codes.error)).u8(static_cast<std::uint8_t>(codes.warning)).take();
}

Result<Pose> parse_pose(ByteView data) {
  if (auto checked = check_data("pose (get_tcp_pose, get_fk)", data, kPoseBytes); !checked) return checked.error();
  ByteReader reader(data);
  return read_pose(reader);
}

Bytes encode_pose(const Pose& pose) {
  ByteWriter writer;
  write_pose(writer, pose);
  return writer.take();
}

Result<JointValues> parse_joints(ByteView data) {
  if (auto checked = check_data("get_joint_pos", data, kJointBytes); !checked) return checked.error();
  ByteReader reader(data);
  return read_joints(reader);
}

Bytes encode_joints(const JointValues& joints_rad) {
  ByteWriter writer;
  write_joints(writer, joints_rad);
  return writer.take();
}

Result<bool> parse_limit_flag(ByteView data) {
  if (auto checked = check_data("is_joint_limit", data, 1); !checked) return checked.error();
  return data[0] != 0;
}

Bytes encode_limit_flag(bool outside) { return ByteWriter().u8(outside ? 1 : 0).take(); }

Result<bool> parse_reduced_mode(ByteView data) {
  if (auto checked = check_data("get_reduced_mode", data, 1); !checked) return checked.error();
  if (data[0] > 1) {
    return make_error(ErrorCode::kInvalidArgument,
                      "get_reduced_mode reply says " + std::to_string(data[0]) + ", expected 0 (off) or 1 (on)");
  }
  return data[0] == 1;
}

Bytes encode_reduced_mode(bool on) { return ByteWriter().u8(on ? 1 : 0).take(); }

Result<std::array<ServoStatus, 8>> parse_servo_dbmsg(ByteView data) {
  if (data.size() != kServoPairsBytes && data.size() != kServoPairsBytes + kServoStatusByte) {
    return make_error(ErrorCode::kInvalidArgument, "servo_get_dbmsg reply carries " + std::to_string(data.size()) +
                                                       " data bytes, expected 16 (or 17 with a leading status byte)");
  }
  const ByteView pairs = data.last(kServoPairsBytes);
  std::array<ServoStatus, 8> servos{};
  for (std::size_t i = 0; i < servos.size(); ++i) {
    servos[i] = ServoStatus{.state = pairs[2 * i], .error = pairs[2 * i + 1]};
  }
  return servos;
}

Bytes encode_servo_dbmsg(const std::array<ServoStatus, 8>& servos) {
  ByteWriter writer;
  for (const ServoStatus& servo : servos) {
    writer.u8(static_cast<std::uint8_t>(servo.state)).u8(static_cast<std::uint8_t>(servo.error));
  }
  return writer.take();
}

}  // namespace robotd::xarm
