#include "service/session_service.hpp"

#include <limits>

#include <spdlog/spdlog.h>

#include "app/log_text.hpp"
#include "rt/monotonic_clock.hpp"
#include "service/session_events.hpp"
#include "session/session_ids.hpp"

namespace robotd::service {
namespace {

std::vector<const control::DeviceModel*> models_of(const std::vector<device::Device*>& devices) {
  std::vector<const control::DeviceModel*> models;
  models.reserve(devices.size());
  for (const auto* device : devices) models.push_back(&device->model());
  return models;
}

std::string state_refusal(DeviceState state, const std::string& device) {
  switch (state) {
    case DeviceState::kFault:
      return "device '" + device + "' is in FAULT: recover it first (robotctl call " + device + " recover)";
    case DeviceState::kEstop:
      return "device '" + device + "' is e-stopped: reset the e-stop first";
    case DeviceState::kMaintenance:
      return "device '" + device + "' is in maintenance (recover or reset_zero)";
    case DeviceState::kConnecting:
      return "device '" + device + "' has not delivered feedback yet";
    case DeviceState::kStopped:
      return "device '" + device + "' is stopping";
    case DeviceState::kRunning:
      return "";
  }
  return "";
}

void add_answers(SessionInfo& info, const device::LoopState& state, const session::SessionRecord& record) {
  const device::AnswerCounts& answers = state.answers[record.slot];
  if (answers.generation != record.generation) return;  // the loop has not started this session yet
  info.closed_loop = answers.closed_loop;
  info.ticks_to_answer = answers.to_answer;
  info.ticks_answered_in_time = answers.in_time;
  info.ticks_answered_late = answers.late;
  info.ticks_unanswered = answers.unanswered;
  info.command_success_rate = answers.success_rate;
  info.success_rate_low = answers.rate_low;
}

}  // namespace

SessionService::SessionService(std::vector<device::Device*> devices, session::SessionLimits limits,
                               std::function<void()> on_change, Clock monotonic_now_ns)
    : devices_(std::move(devices)),
      table_(models_of(devices_), limits),
      monotonic_now_ns_(monotonic_now_ns),
      maintenance_(devices_.size()),
      on_change_(std::move(on_change)) {}

RequestControlResponse SessionService::request_control(const RequestControlRequest& request) {
  RequestControlResponse response;
  {
    const std::lock_guard lock(mutex_);
    auto device_index = table_.resolve_device(request.device);
    if (!device_index) {
      response.message = device_index.error().message;
      return response;
    }
    device::Device& device = *devices_[device_index.value()];
    if (const std::string& operation = maintenance_[device_index.value()]; !operation.empty()) {
      response.message =
          "device '" + device.model().name + "' is in maintenance (" + operation + "); retry when it is done";
      return response;
    }
    // The e-stop flag first: the state the loop publishes lags it by up to a tick.
    const DeviceState state = device.channel().estop.load(std::memory_order_acquire)
                                  ? DeviceState::kEstop
                                  : device.channel().device_state.load(std::memory_order_acquire);
    if (const std::string refusal = state_refusal(state, device.model().name); !refusal.empty()) {
      response.message = refusal;
      return response;
    }
    std::string session_id = session::random_session_id();
    while (table_.find_by_id(session_id) != nullptr) session_id = session::random_session_id();
    auto granted = table_.grant(request, session::random_session_uuid(), std::move(session_id), monotonic_now_ns_(),
                                rt::realtime_now_ns());
    if (!granted) {
      response.message = granted.error().message;
      return response;
    }
    const session::SessionRecord& record = granted.value();
    if (!device.channel().post(session_start_event(record))) {
      (void)table_.release(record.uuid);
      response.message =
          "device '" + device.model().name + "' is busy (its loop has not taken the last requests); retry";
      return response;
    }
    active_.add(record.uuid);
    response.success = true;
    response.uuid = record.uuid;
    response.motor_ids = record.motor_ids;
    response.applied_behavior = record.applied_behavior;
    response.device = record.device;
    response.session_id = record.session_id;
    response.message = "granted " + std::to_string(record.motor_ids.size()) + " motor(s) of '" + record.device +
                       "' in " + std::string(to_string(record.mode)) + " mode; on timeout (" +
                       std::to_string(record.timeout_ms) + " ms) " + std::string(to_string(record.applied_behavior));
    if (record.applied_behavior != record.requested_behavior) {
      response.message +=
          " (" + std::string(to_string(record.requested_behavior)) + " is not supported by this device)";
    }
    // The policy's names are the client's text: the log shows them escaped and bounded.
    std::string logged = response.message;
    if (!record.policy_name.empty() || !record.policy_file_name.empty()) {
      response.message += "; policy '" + record.policy_name + "' from '" + record.policy_file_name + "'";
      logged +=
          "; policy '" + app::log_text(record.policy_name) + "' from '" + app::log_text(record.policy_file_name) + "'";
    }
    spdlog::info("session {} granted to node '{}': {}", record.session_id, app::log_text(record.node_name), logged);
  }
  on_change_();
  return response;
}

ReleaseControlResponse SessionService::release_control(const ReleaseControlRequest& request) {
  ReleaseControlResponse response;
  if (!is_valid(request.release_mode)) {
    response.message = "release_mode " + std::to_string(static_cast<int>(request.release_mode)) +
                       " is not one of KEEP_MODE=0, DAMPING_MODE=1, ZERO_TORQUE_MODE=2";
    return response;
  }
  {
    const std::lock_guard lock(mutex_);
    auto released = table_.release(request.uuid);
    if (!released) {
      response.message = released.error().message;
      return response;
    }
    const session::SessionRecord& record = released.value();
    active_.remove(record.uuid);
    device::Device& device = *devices_[record.device_index];
    const Behavior applied = control::applied_behavior(request.release_mode, device.model().behaviors);
    if (!device.channel().post(session_release_event(record, applied))) {
      // The loop is not draining its events; its timeout still ends the session.
      spdlog::error("device '{}': release of session {} could not be queued; it will time out instead", record.device,
                    record.session_id);
    }
    response.success = true;
    response.applied_behavior = applied;
    response.message = "released " + std::to_string(record.motor_ids.size()) + " motor(s) of '" + record.device +
                       "' with " + std::string(to_string(applied));
    spdlog::info("session {} of node '{}' released by '{}': {}", record.session_id, app::log_text(record.node_name),
                 app::log_text(request.node_name), response.message);
  }
  on_change_();
  return response;
}

GetAvailableMotorsResponse SessionService::available_motors(const GetAvailableMotorsRequest& request) {
  GetAvailableMotorsResponse response;
  const std::lock_guard lock(mutex_);
  auto device_index = table_.resolve_device(request.device);
  if (!device_index) {
    response.message = device_index.error().message;
    return response;
  }
  const control::DeviceModel& model = table_.device(device_index.value());
  response.motor_ids = table_.idle_motors(device_index.value());
  for (const auto id : response.motor_ids)
    response.motor_names.push_back(model.joint_names[static_cast<std::size_t>(id)]);
  response.success = true;
  response.message = std::to_string(response.motor_ids.size()) + " of " + std::to_string(model.joint_count()) +
                     " motors of '" + model.name + "' are idle";
  return response;
}

std::optional<SessionService::Authorization> SessionService::authorize(std::string_view uuid) {
  const std::lock_guard lock(mutex_);
  const session::SessionRecord* record = table_.find(uuid);
  if (record == nullptr) return std::nullopt;
  return Authorization{record->session_id, record->device_index, record->slot,
                       record->generation, record->mode,         record->motors};
}

bool SessionService::is_session_id(std::string_view text) const {
  const std::lock_guard lock(mutex_);
  return table_.find_by_id(text) != nullptr;
}

void SessionService::note_command(std::string_view uuid, std::int64_t now_ns) {
  const std::lock_guard lock(mutex_);
  if (session::SessionRecord* record = table_.find(uuid)) {
    record->last_command_ns = now_ns;
    ++record->commands_accepted;
  }
}

std::optional<session::SessionRecord> SessionService::session_ended(std::size_t device, std::uint8_t slot,
                                                                    std::uint32_t generation) {
  std::optional<session::SessionRecord> ended;
  {
    const std::lock_guard lock(mutex_);
    ended = table_.end(device, slot, generation);
    if (ended) active_.remove(ended->uuid);
  }
  if (ended) on_change_();
  return ended;
}

Result<void> SessionService::reserve_for_maintenance(std::size_t device, const std::string& operation) {
  const std::lock_guard lock(mutex_);
  const std::string& name = devices_[device]->model().name;
  if (!maintenance_[device].empty()) {
    return make_error(ErrorCode::kRefused, "device '" + name + "' is already in maintenance (" + maintenance_[device] +
                                               "); retry when it is done");
  }
  if (const std::string holders = table_.holders(device, monotonic_now_ns_()); !holders.empty()) {
    return make_error(ErrorCode::kRefused, operation + " is refused while a session is active on '" + name +
                                               "': " + holders + "; release it first");
  }
  maintenance_[device] = operation;
  return {};
}

void SessionService::end_maintenance(std::size_t device) {
  const std::lock_guard lock(mutex_);
  maintenance_[device].clear();
}

std::string SessionService::maintenance_operation(std::size_t device) const {
  const std::lock_guard lock(mutex_);
  return maintenance_[device];
}

bool SessionService::any_active(std::size_t device) const {
  const std::lock_guard lock(mutex_);
  return table_.any_active(device);
}

Result<std::size_t> SessionService::resolve_device(std::string_view name) const {
  const std::lock_guard lock(mutex_);
  return table_.resolve_device(name);
}

SessionStatus SessionService::status(std::int64_t now_ns) const {
  SessionStatus status;
  status.header.stamp = Time::from_ns(rt::realtime_now_ns());
  const std::lock_guard lock(mutex_);
  std::int64_t newest_policy_ns = std::numeric_limits<std::int64_t>::min();
  for (const auto& record : table_.sessions()) {
    // The PI Plus runs one policy at a time and names it here: robotd names the newest session's
    // that named one (each session's own are in its SessionInfo).
    const bool names_a_policy = !record.policy_name.empty() || !record.policy_file_name.empty();
    if (names_a_policy && record.granted_ns >= newest_policy_ns) {
      status.policy_name = record.policy_name;
      status.policy_file_name = record.policy_file_name;
      newest_policy_ns = record.granted_ns;
    }
    status.active_uuids.push_back(record.session_id);
    status.node_names.push_back(record.node_name);
    status.motor_counts.push_back(static_cast<std::int32_t>(record.motor_ids.size()));
    SessionInfo info;
    info.uuid = record.session_id;
    info.node_name = record.node_name;
    info.device = record.device;
    info.motor_ids = record.motor_ids;
    info.control_mode = record.mode;
    info.default_behavior = record.requested_behavior;
    info.applied_behavior = record.applied_behavior;
    info.timeout_ms = record.timeout_ms;
    info.time_left_ms = static_cast<std::int32_t>(record.time_left_ms(now_ns));
    info.granted_at = Time::from_ns(record.granted_wall_ns);
    info.commands_accepted = record.commands_accepted;
    info.policy_name = record.policy_name;
    info.policy_file_name = record.policy_file_name;
    info.min_command_success_rate = record.min_command_success_rate;
    info.on_low_success_rate = record.on_low_success_rate;
    if (!observers_.empty()) add_answers(info, observers_[record.device_index]->latest(), record);
    status.sessions.push_back(std::move(info));
  }
  status.state = status.sessions.empty() ? "idle" : "active";
  return status;
}

}  // namespace robotd::service
