// The report ports' packets (§5.1 "real" 30003, §5.2 "normal" 30001, §5.3 "rich" 30002, §5.4
// "realtime" 30000): the size-prefixed stream, each kind's layout, and the SDK's sanity checks.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "wire_fields.hpp"
#include "xarm_codec.hpp"

namespace robotd::xarm {
namespace {

constexpr std::size_t kSizeBytes = 4;
constexpr std::size_t kMinReportBytes = 8;

struct KindInfo {
  ReportKind kind;
  std::string_view name;
  std::uint16_t port;
  std::size_t short_size;  // real without F/T, normal on older firmware, realtime per the doc
  std::size_t long_size;   // real with F/T, normal, realtime per the SDK
};

constexpr auto kKinds = std::to_array<KindInfo>({
    {ReportKind::kReal, "real", 30003, 87, 135},
    {ReportKind::kNormal, "normal", 30001, 133, 145},
    {ReportKind::kRealtime, "realtime", 30000, 784, 804},
    // Rich packets grow with the firmware (the SDK reads up to 587 bytes); 245 is the layout
    // every firmware sends, and any longer packet is accepted.
    {ReportKind::kRich, "rich", 30002, 245, 245},
});

const KindInfo& info(ReportKind kind) {
  return *std::find_if(kKinds.begin(), kKinds.end(), [kind](const KindInfo& entry) { return entry.kind == kind; });
}

// Offsets shared by real and normal (§5.1, §5.2).
namespace basic {
constexpr std::size_t kStateMode = 4;
constexpr std::size_t kPosition = 7;
constexpr std::size_t kForceTorqueFiltered = 87;  // real, 135 bytes
constexpr std::size_t kForceTorqueRaw = 111;
// Normal, from here in order: masks, codes, TCP offset, payload, sensitivities, gravity direction.
constexpr std::size_t kBrakeMask = 87;
}  // namespace basic

// §5.3: after the normal report's 145 bytes.
namespace rich {
constexpr std::size_t kDeviceType = 145;  // then axes, master id, slave id, motor tid, motor fid
constexpr std::size_t kFirmware = 151;
constexpr std::size_t kFirmwareBytes = 30;
constexpr std::size_t kTcpLimits = 181;  // 5 f, then the joints' 5 f, then rotation jerk and acc
constexpr std::size_t kServos = 229;     // 8 × (status, code)
constexpr std::uint8_t kMasterId = 0xAA;
constexpr std::uint8_t kSlaveId = 0x55;
}  // namespace rich

// §5.4.
namespace realtime {
constexpr std::size_t kTimestamp = 4;
constexpr std::size_t kStateMode = 12;
constexpr std::size_t kTargetPosition = 32;
constexpr std::size_t kTargetVelocity = 60;
constexpr std::size_t kPosition = 116;
constexpr std::size_t kVelocity = 144;
constexpr std::size_t kTorque = 228;
constexpr std::size_t kTcpPose = 472;
constexpr std::size_t kForceTorqueRaw = 688;
constexpr std::size_t kForceTorqueFiltered = 712;
}  // namespace realtime

constexpr int kStateLimit = 10;  // the SDK drops packets with state ≥ 10 or mode ≥ 12
constexpr int kModeLimit = 12;
constexpr std::uint8_t kNibble = 0x0F;

/// A reader from `offset`; empty past the end (parse_report checks sizes first).
ByteReader reader_at(ByteView packet, std::size_t offset) {
  return ByteReader(offset <= packet.size() ? packet.subspan(offset) : ByteView{});
}

std::array<double, 6> read_wrench(ByteReader reader) {
  std::array<double, 6> wrench{};
  for (double& value : wrench) value = read_f32(reader);
  return wrench;
}

/// Writes `field` into the zero-filled packet at `offset`.
void put(Bytes& packet, std::size_t offset, const ByteWriter& field) {
  std::copy(field.data().begin(), field.data().end(), packet.begin() + static_cast<std::ptrdiff_t>(offset));
}

ByteWriter joints_field(const JointValues& values) {
  ByteWriter field;
  write_joints(field, values);
  return field;
}

ByteWriter wrench_field(const std::array<double, 6>& wrench) {
  ByteWriter field;
  for (const double value : wrench) field.f32_le(value);
  return field;
}

std::uint8_t state_mode_byte(const Report& report) {
  return static_cast<std::uint8_t>(((report.mode & kNibble) << 4) | (report.state & kNibble));
}

/// state_mode, cmd_num, joints, pose, effort: offsets 4..86 of real and normal.
ByteWriter basic_head(const Report& report) {
  ByteWriter head;
  head.u8(state_mode_byte(report)).u16_be(report.cmd_num);
  write_joints(head, report.position_rad);
  write_pose(head, report.tcp_pose);
  write_joints(head, report.effort);
  return head;
}

/// Offsets 87..144 of normal: masks, codes and settings.
ByteWriter normal_tail(const Report& report) {
  ByteWriter tail;
  tail.u8(report.brake_mask)
      .u8(report.enable_mask)
      .u8(static_cast<std::uint8_t>(report.error_code))
      .u8(static_cast<std::uint8_t>(report.warning_code));
  write_pose(tail, report.tcp_offset);
  tail.f32_le(report.payload_kg);
  for (const double axis : report.payload_centre_m) tail.f32_le(axis * kMmPerM);
  tail.u8(static_cast<std::uint8_t>(report.collision_sensitivity))
      .u8(static_cast<std::uint8_t>(report.teach_sensitivity));
  for (const double axis : report.gravity_direction) tail.f32_le(axis);
  return tail;
}

/// Five floats: jerk, min acc, max acc, min speed, max speed; `scale` wire units per robotd unit.
MotionLimits read_limits(ByteReader& reader, double scale) {
  MotionLimits limits;
  for (double* value : {&limits.jerk, &limits.min_acc, &limits.max_acc, &limits.min_speed, &limits.max_speed}) {
    *value = read_f32(reader) / scale;
  }
  return limits;
}

void write_limits(ByteWriter& writer, const MotionLimits& limits, double scale) {
  for (const double value : {limits.jerk, limits.min_acc, limits.max_acc, limits.min_speed, limits.max_speed}) {
    writer.f32_le(value * scale);
  }
}

RichFields read_rich(ByteView packet) {
  RichFields fields;
  ByteReader ids = reader_at(packet, rich::kDeviceType);
  fields.device_type = ids.u8().value_or(0);
  fields.axes = ids.u8().value_or(0);
  const ByteView firmware = packet.subspan(rich::kFirmware, rich::kFirmwareBytes);
  for (const std::uint8_t byte : firmware) {
    if (byte == 0) break;
    fields.firmware.push_back(byte >= 0x20 && byte < 0x7F ? static_cast<char>(byte) : '?');
  }
  ByteReader limits = reader_at(packet, rich::kTcpLimits);
  fields.tcp = read_limits(limits, kMmPerM);
  fields.joint = read_limits(limits, 1.0);
  fields.rotation_jerk = read_f32(limits);
  fields.rotation_max_acc = read_f32(limits);
  ByteReader servos = reader_at(packet, rich::kServos);
  for (ServoStatus& servo : fields.servos) {
    servo.state = servos.u8().value_or(0);
    servo.error = servos.u8().value_or(0);
  }
  return fields;
}

/// Offsets 145..244 of rich.
ByteWriter rich_tail(const RichFields& fields) {
  ByteWriter tail;
  tail.u8(static_cast<std::uint8_t>(fields.device_type))
      .u8(static_cast<std::uint8_t>(fields.axes))
      .u8(rich::kMasterId)
      .u8(rich::kSlaveId)
      .u8(0)
      .u8(0);
  Bytes firmware(rich::kFirmwareBytes, 0);
  std::copy_n(fields.firmware.begin(), std::min(fields.firmware.size(), rich::kFirmwareBytes), firmware.begin());
  tail.bytes(firmware);
  write_limits(tail, fields.tcp, kMmPerM);
  write_limits(tail, fields.joint, 1.0);
  tail.f32_le(fields.rotation_jerk).f32_le(fields.rotation_max_acc);
  for (const ServoStatus& servo : fields.servos) {
    tail.u8(static_cast<std::uint8_t>(servo.state)).u8(static_cast<std::uint8_t>(servo.error));
  }
  return tail;
}

}  // namespace

std::string_view report_kind_name(ReportKind kind) { return info(kind).name; }

std::optional<ReportKind> parse_report_kind(std::string_view name) {
  const auto found =
      std::find_if(kKinds.begin(), kKinds.end(), [name](const KindInfo& entry) { return entry.name == name; });
  if (found == kKinds.end()) return std::nullopt;
  return found->kind;
}

std::uint16_t default_report_port(ReportKind kind) { return info(kind).port; }

void ReportSplitter::append(ByteView bytes) {
  if (broken_) return;  // nothing after a lost framing can be trusted until clear()
  buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
}

Result<std::optional<Bytes>> ReportSplitter::next() {
  if (broken_) return make_error(ErrorCode::kInvalidArgument, *broken_);
  ByteReader reader(buffer_);
  const auto size = reader.u32_be();
  if (!size) return std::optional<Bytes>{};
  if (*size < kMinReportBytes || *size > kMaxReportBytes) {
    broken_ = "report size field " + std::to_string(*size) + " is outside " + std::to_string(kMinReportBytes) + ".." +
              std::to_string(kMaxReportBytes) + ": the report stream lost its framing (reconnect)";
    buffer_.clear();
    return make_error(ErrorCode::kInvalidArgument, *broken_);
  }
  if (buffer_.size() < *size) return std::optional<Bytes>{};
  const auto packet_end = buffer_.begin() + static_cast<std::ptrdiff_t>(*size);
  Bytes packet(buffer_.begin(), packet_end);
  buffer_.erase(buffer_.begin(), packet_end);
  return std::optional<Bytes>(std::move(packet));
}

void ReportSplitter::clear() {
  buffer_.clear();
  broken_.reset();
}

Result<Report> parse_report(ByteView packet, ReportKind kind) {
  const KindInfo& kind_info = info(kind);
  const std::string what = std::string(kind_info.name) + " report";
  ByteReader size_reader(packet);
  const auto size = size_reader.u32_be();
  if (!size) return size_error(what, "byte", packet.size(), kSizeBytes, true);
  if (*size != packet.size()) {
    return make_error(ErrorCode::kInvalidArgument, what + " size field says " + std::to_string(*size) +
                                                       " bytes but the packet has " + std::to_string(packet.size()));
  }
  if (kind == ReportKind::kRich && packet.size() < kind_info.short_size) {
    return size_error(what, "byte", packet.size(), kind_info.short_size, true);
  }
  if (kind != ReportKind::kRich && packet.size() != kind_info.short_size && packet.size() != kind_info.long_size) {
    return make_error(ErrorCode::kInvalidArgument, what + " has " + std::to_string(packet.size()) +
                                                       " bytes, expected " + std::to_string(kind_info.short_size) +
                                                       " or " + std::to_string(kind_info.long_size));
  }

  Report report;
  const bool is_realtime = kind == ReportKind::kRealtime;
  ByteReader head = reader_at(packet, is_realtime ? realtime::kStateMode : basic::kStateMode);
  const std::uint8_t state_mode = head.u8().value_or(0);
  report.state = state_mode & kNibble;
  report.mode = state_mode >> 4;
  if (report.state >= kStateLimit || report.mode >= kModeLimit) {
    return make_error(ErrorCode::kInvalidArgument, what + " has state " + std::to_string(report.state) + " and mode " +
                                                       std::to_string(report.mode) +
                                                       ", expected a state below 10 and a mode below 12");
  }
  report.cmd_num = head.u16_be().value_or(0);

  if (is_realtime) {
    report.timestamp_us = reader_at(packet, realtime::kTimestamp).u64_be().value_or(0);
    report.has_timestamp = true;
    ByteReader target_position = reader_at(packet, realtime::kTargetPosition);
    report.target_position_rad = read_joints(target_position);
    ByteReader target_velocity = reader_at(packet, realtime::kTargetVelocity);
    report.target_velocity_rad_s = read_joints(target_velocity);
    report.has_targets = true;
    ByteReader position = reader_at(packet, realtime::kPosition);
    report.position_rad = read_joints(position);
    ByteReader velocity = reader_at(packet, realtime::kVelocity);
    report.velocity_rad_s = read_joints(velocity);
    report.has_velocity = true;
    ByteReader torque = reader_at(packet, realtime::kTorque);
    report.effort = read_joints(torque);
    ByteReader pose = reader_at(packet, realtime::kTcpPose);
    report.tcp_pose = read_pose(pose);
    report.force_torque = read_wrench(reader_at(packet, realtime::kForceTorqueFiltered));
    report.has_force_torque = true;
    return report;
  }

  ByteReader body = reader_at(packet, basic::kPosition);
  report.position_rad = read_joints(body);
  report.tcp_pose = read_pose(body);
  report.effort = read_joints(body);
  if (kind == ReportKind::kReal && packet.size() == kind_info.long_size) {
    report.force_torque = read_wrench(reader_at(packet, basic::kForceTorqueFiltered));
    report.has_force_torque = true;
  }
  if (kind == ReportKind::kNormal || kind == ReportKind::kRich) {
    ByteReader tail = reader_at(packet, basic::kBrakeMask);
    report.brake_mask = tail.u8().value_or(0);
    report.enable_mask = tail.u8().value_or(0);
    report.error_code = tail.u8().value_or(0);
    report.warning_code = tail.u8().value_or(0);
    report.has_codes = true;
    report.tcp_offset = read_pose(tail);
    report.payload_kg = read_f32(tail);
    for (double& axis : report.payload_centre_m) axis = read_f32(tail) / kMmPerM;
    report.collision_sensitivity = tail.u8().value_or(0);
    report.teach_sensitivity = tail.u8().value_or(0);
    report.has_settings = true;
    if (packet.size() >= info(ReportKind::kNormal).long_size) {  // older firmware's 133 bytes end before it
      for (double& axis : report.gravity_direction) axis = read_f32(tail);
      report.has_gravity_direction = true;
    }
  }
  if (kind == ReportKind::kRich) {
    report.rich = read_rich(packet);
    report.has_rich = true;
  }
  return report;
}

Bytes encode_report(const Report& report, ReportKind kind, bool with_force_torque) {
  const KindInfo& kind_info = info(kind);
  const bool long_real = kind == ReportKind::kReal && with_force_torque;
  // Fields Report does not model (target accelerations, currents, TCP speeds …) go out as zeros.
  const std::size_t size = kind == ReportKind::kNormal || long_real ? kind_info.long_size : kind_info.short_size;
  const bool with_settings = kind == ReportKind::kNormal || kind == ReportKind::kRich;
  Bytes packet(size, 0);
  put(packet, 0, ByteWriter().u32_be(static_cast<std::uint32_t>(size)));

  if (kind == ReportKind::kRealtime) {
    put(packet, realtime::kTimestamp,
        ByteWriter().u64_be(report.timestamp_us).u8(state_mode_byte(report)).u16_be(report.cmd_num));
    put(packet, realtime::kTargetPosition, joints_field(report.target_position_rad));
    put(packet, realtime::kTargetVelocity, joints_field(report.target_velocity_rad_s));
    put(packet, realtime::kPosition, joints_field(report.position_rad));
    put(packet, realtime::kVelocity, joints_field(report.velocity_rad_s));
    put(packet, realtime::kTorque, joints_field(report.effort));
    ByteWriter pose;
    write_pose(pose, report.tcp_pose);
    put(packet, realtime::kTcpPose, pose);
    // A simulated sensor has no noise: raw and filtered wrench are the same.
    put(packet, realtime::kForceTorqueRaw, wrench_field(report.force_torque));
    put(packet, realtime::kForceTorqueFiltered, wrench_field(report.force_torque));
    return packet;
  }

  put(packet, basic::kStateMode, basic_head(report));
  if (long_real) {
    put(packet, basic::kForceTorqueFiltered, wrench_field(report.force_torque));
    put(packet, basic::kForceTorqueRaw, wrench_field(report.force_torque));
  }
  if (with_settings) put(packet, basic::kBrakeMask, normal_tail(report));
  if (kind == ReportKind::kRich) put(packet, rich::kDeviceType, rich_tail(report.rich));
  return packet;
}

}  // namespace robotd::xarm
