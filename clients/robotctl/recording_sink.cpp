#include "recording_sink.hpp"

#include "message_json.hpp"
#include "recording/record_codec.hpp"

namespace robotctl {
namespace {

using recording::RecordKind;

std::size_t count_index(RecordKind kind) { return static_cast<std::size_t>(kind) - 1; }

// The uuid is a session's capability (docs/security.md): a recording keeps what robotd's log
// keeps, its first 8 characters.
robotd::SessionStatus with_short_uuids(robotd::SessionStatus status) {
  for (auto& uuid : status.active_uuids) uuid = uuid.substr(0, 8);
  for (auto& session : status.sessions) session.uuid = session.uuid.substr(0, 8);
  return status;
}

}  // namespace

RecordingSink::RecordingSink(recording::RecordingWriter writer, const recording::Description& description,
                             bool keep_unknown_devices)
    : keep_unknown_devices_(keep_unknown_devices), writer_(std::move(writer)) {
  for (std::size_t i = 0; i < description.devices.size(); ++i) {
    device_indices_.emplace(description.devices[i].name, static_cast<std::uint16_t>(i));
  }
}

std::int64_t RecordingSink::now_ns() const {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start_).count();
}

std::optional<std::uint16_t> RecordingSink::device_index(const std::string& device) const {
  const auto found = device_indices_.find(device);
  if (found == device_indices_.end()) return std::nullopt;
  return found->second;
}

void RecordingSink::add(const robotd::JointState& state) {
  const auto device = device_index(state.header.frame_id);
  if (!device) return;
  const recording::JointStateRecord record{*device, state.header.stamp.to_ns(), state.position, state.velocity,
                                           state.effort};
  const std::lock_guard lock(mutex_);
  append(RecordKind::kJointState, recording::encode(record));
}

void RecordingSink::add(const robotd::ControlCommand& command) {
  const std::lock_guard lock(mutex_);
  std::string device_name = command.device;
  if (device_name.empty()) {
    const auto session = session_devices_.find(command.uuid);
    if (session != session_devices_.end()) device_name = session->second;
  }
  const auto device = device_index(device_name);
  if (!device && !keep_unknown_devices_) return;
  const recording::ControlCommandRecord record{
      device.value_or(recording::kUnknownDevice),
      command.header.stamp.to_ns(),
      recording::session_tag(command.uuid),
      {command.motor_ids, command.positions, command.velocities, command.kp, command.kd, command.torques}};
  append(RecordKind::kControlCommand, recording::encode(record));
}

void RecordingSink::add(const robotd::DeviceStatus& status) {
  if (!device_index(status.device)) return;
  const std::string json_text = compact_text(to_json(status));
  const std::lock_guard lock(mutex_);
  append(RecordKind::kDeviceStatus, json_text);
}

void RecordingSink::add(const robotd::SessionStatus& status, bool record) {
  const std::string json_text = record ? compact_text(to_json(with_short_uuids(status))) : "";
  const std::lock_guard lock(mutex_);
  for (const auto& session : status.sessions) session_devices_[session.uuid] = session.device;
  if (record) append(RecordKind::kSessionStatus, json_text);
}

void RecordingSink::append(RecordKind kind, const std::optional<std::string>& payload) {
  if (error_) return;
  if (!payload) {
    ++summary_.unrecordable;
    return;
  }
  if (auto appended = writer_.append(kind, now_ns(), *payload); !appended) {
    error_ = appended.error();
    return;
  }
  ++summary_.records.at(count_index(kind));
}

robotd::Result<void> RecordingSink::flush() {
  const std::lock_guard lock(mutex_);
  if (error_) return *error_;
  return writer_.flush();
}

robotd::Result<void> RecordingSink::finish() {
  const std::lock_guard lock(mutex_);
  if (error_) return *error_;
  const std::int64_t end_ns = now_ns();
  summary_.duration_s = static_cast<double>(end_ns) * 1e-9;
  return writer_.finish(end_ns);
}

RecordingSink::Summary RecordingSink::summary() const {
  const std::lock_guard lock(mutex_);
  Summary summary = summary_;
  summary.bytes = writer_.bytes();
  return summary;
}

}  // namespace robotctl
