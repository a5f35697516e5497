#include "recording_sink.hpp"

#include "message_json.hpp"
#include "recording/record_codec.hpp"

namespace robotctl {
namespace {

using recording::RecordKind;

std::size_t count_index(RecordKind kind) { return static_cast<std::size_t>(kind) - 1; }

}  // namespace

RecordingSink::RecordingSink(recording::RecordingWriter writer, const recording::Description& description,
                             bool keep_unknown_devices, std::string only_device)
    : keep_unknown_devices_(keep_unknown_devices), only_device_(std::move(only_device)), writer_(std::move(writer)) {
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
  const auto device = device_index(command.device.empty() ? only_device_ : command.device);
  if (!device && !keep_unknown_devices_) return;
  const recording::ControlCommandRecord record{
      device.value_or(recording::kUnknownDevice),
      command.header.stamp.to_ns(),
      recording::session_tag(command.uuid),
      {command.motor_ids, command.positions, command.velocities, command.kp, command.kd, command.torques}};
  const std::lock_guard lock(mutex_);
  append(RecordKind::kControlCommand, recording::encode(record));
}

void RecordingSink::add(const robotd::DeviceStatus& status) {
  if (!device_index(status.device)) return;
  const std::string json_text = compact_text(to_json(status));
  const std::lock_guard lock(mutex_);
  append(RecordKind::kDeviceStatus, json_text);
}

void RecordingSink::add(const robotd::SessionStatus& status) {
  const std::string json_text = compact_text(to_json(status));
  const std::lock_guard lock(mutex_);
  append(RecordKind::kSessionStatus, json_text);
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
