#include "session/session_table.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace robotd::session {
namespace {

constexpr std::int64_t kNsPerMs = 1'000'000;

Error refused(std::string message) { return make_error(ErrorCode::kRefused, std::move(message)); }

std::string id_list(const std::vector<std::int32_t>& ids) {
  std::string out;
  for (const auto id : ids) out += (out.empty() ? "" : ", ") + std::to_string(id);
  return out;
}

Result<void> check_gains(const std::vector<float>& gains, const char* name, std::size_t motor_count,
                         const std::vector<std::int32_t>& motor_ids, const control::DeviceModel& model, bool is_kp) {
  if (gains.empty()) return {};
  if (gains.size() != motor_count) {
    return refused(std::string(name) + " has " + std::to_string(gains.size()) + " values for " +
                   std::to_string(motor_count) + " motors (give none or one per motor)");
  }
  for (std::size_t i = 0; i < gains.size(); ++i) {
    const auto joint = static_cast<std::size_t>(motor_ids[i]);
    const double max = is_kp ? model.limits[joint].kp_max : model.limits[joint].kd_max;
    if (!std::isfinite(gains[i]) || gains[i] < 0 || gains[i] > max) {
      std::ostringstream text;
      text << name << " " << gains[i] << " for motor " << joint << " is outside 0.." << max;
      return refused(text.str());
    }
  }
  return {};
}

// The fallback a session is told it gets must be what its joints get: DAMPING with a kd of 0
// lets the joint go, and so does a KEEP hold with a kp of 0 on an impedance joint.
Result<void> check_fallback_gains(const RequestControlRequest& request, const std::vector<std::int32_t>& motor_ids,
                                  const control::DeviceModel& model) {
  const Behavior applied = control::applied_behavior(request.default_behavior, model.behaviors);
  const bool damping = applied == Behavior::kDamping;
  const bool impedance_hold = applied == Behavior::kKeep && model.supports_torque;
  const auto& gains = damping ? request.default_kd : request.default_kp;
  if ((!damping && !impedance_hold) || gains.empty()) return {};
  for (std::size_t i = 0; i < gains.size(); ++i) {
    if (gains[i] > 0) continue;
    return refused(std::string(damping ? "default_kd" : "default_kp") + " 0 for motor " + std::to_string(motor_ids[i]) +
                   (damping ? " would make its DAMPING fallback let the joint go"
                            : " would make its KEEP fallback hold with no stiffness") +
                   "; give a gain > 0, leave " + (damping ? "default_kd" : "default_kp") +
                   " empty for the joint's default, or ask for " + (damping ? "ZERO_TORQUE_MODE" : "DAMPING_MODE"));
  }
  return {};
}

}  // namespace

std::int64_t SessionRecord::time_left_ms(std::int64_t now_ns) const {
  const std::int64_t left = timeout_ms - (now_ns - last_command_ns) / kNsPerMs;
  return std::max<std::int64_t>(left, 0);
}

SessionTable::SessionTable(std::vector<const control::DeviceModel*> devices, SessionLimits limits)
    : devices_(std::move(devices)), limits_(limits), sessions_(devices_.size()) {}

std::optional<std::size_t> SessionTable::find_device(std::string_view name) const {
  if (name.empty()) return devices_.size() == 1 ? std::optional<std::size_t>(0) : std::nullopt;
  for (std::size_t i = 0; i < devices_.size(); ++i) {
    if (devices_[i]->name == name) return i;
  }
  return std::nullopt;
}

Result<std::size_t> SessionTable::resolve_device(std::string_view name) const {
  if (auto found = find_device(name)) return *found;
  std::string known;
  for (const auto* device : devices_) known += (known.empty() ? "'" : ", '") + device->name + "'";
  if (name.empty()) return refused("no device named: this robotd serves " + known + "; say which one");
  return refused("unknown device '" + std::string(name) + "' (this robotd serves " + known + ")");
}

Result<void> SessionTable::check_request(const RequestControlRequest& request,
                                         const control::DeviceModel& model) const {
  if (!is_valid(request.control_mode)) {
    return refused("control_mode " + std::to_string(static_cast<int>(request.control_mode)) +
                   " is not one of POSITION_MODE=0, TORQUE_MODE=1, MIXED_MODE=2");
  }
  if (!is_valid(request.default_behavior)) {
    return refused("default_behavior " + std::to_string(static_cast<int>(request.default_behavior)) +
                   " is not one of KEEP_MODE=0, DAMPING_MODE=1, ZERO_TORQUE_MODE=2");
  }
  // Written as a negation so that NaN is refused too.
  if (!(request.min_command_success_rate >= 0 && request.min_command_success_rate <= 1)) {
    return refused("min_command_success_rate " + std::to_string(request.min_command_success_rate) +
                   " is outside 0..1 (the least fraction of ticks answered in time; 0 = no minimum)");
  }
  if (!is_valid(request.on_low_success_rate)) {
    return refused("on_low_success_rate " + std::to_string(static_cast<int>(request.on_low_success_rate)) +
                   " is not one of LOW_RATE_WARN=0, LOW_RATE_FALLBACK=1");
  }
  if (!model.read_only_reason.empty()) {
    return refused("device '" + model.name + "' (" + model.driver + ") takes no commands: " + model.read_only_reason);
  }
  if (request.control_mode != ControlMode::kPosition && !model.supports_torque) {
    return refused("device '" + model.name + "' (" + model.driver + ") supports only POSITION mode, not " +
                   std::string(to_string(request.control_mode)));
  }
  if (request.timeout_ms < limits_.min_timeout_ms || request.timeout_ms > limits_.max_timeout_ms) {
    return refused("timeout_ms " + std::to_string(request.timeout_ms) + " is outside " +
                   std::to_string(limits_.min_timeout_ms) + ".." + std::to_string(limits_.max_timeout_ms));
  }
  control::MotorSet seen;
  for (const auto id : request.motor_ids) {
    if (id < 0 || static_cast<std::size_t>(id) >= model.joint_count()) {
      return refused("motor id " + std::to_string(id) + " does not exist on device '" + model.name + "' (valid: 0.." +
                     std::to_string(model.joint_count() - 1) + ")");
    }
    if (seen.test(static_cast<std::size_t>(id))) return refused("motor id " + std::to_string(id) + " appears twice");
    seen.set(static_cast<std::size_t>(id));
  }
  return {};
}

std::string SessionTable::describe_holders(const DeviceSessions& sessions, const control::MotorSet& wanted,
                                           std::int64_t now_ns) const {
  std::string text;
  for (const auto& slot : sessions.slots) {
    if (!slot || (slot->motors & wanted).none()) continue;
    std::vector<std::int32_t> overlap;
    for (const auto id : slot->motor_ids) {
      if (wanted.test(static_cast<std::size_t>(id))) overlap.push_back(id);
    }
    text += (text.empty() ? "" : "; ") + std::string("motor(s) ") + id_list(overlap) + " held by node '" +
            slot->node_name + "' (session " + slot->session_id + ", " + std::to_string(slot->time_left_ms(now_ns)) +
            " ms left unless it keeps commanding; timeout " + std::to_string(slot->timeout_ms) + " ms)";
  }
  return text;
}

Result<SessionRecord> SessionTable::grant(const RequestControlRequest& request, std::string uuid,
                                          std::string session_id, std::int64_t now_ns, std::int64_t wall_ns) {
  auto device_index = resolve_device(request.device);
  if (!device_index) return device_index.error();
  const control::DeviceModel& model = *devices_[device_index.value()];
  if (auto valid = check_request(request, model); !valid) return valid.error();

  std::vector<std::int32_t> motor_ids = request.motor_ids;
  if (motor_ids.empty()) {
    for (std::size_t i = 0; i < model.joint_count(); ++i) motor_ids.push_back(static_cast<std::int32_t>(i));
  }
  if (auto kp = check_gains(request.default_kp, "default_kp", motor_ids.size(), motor_ids, model, true); !kp) {
    return kp.error();
  }
  if (auto kd = check_gains(request.default_kd, "default_kd", motor_ids.size(), motor_ids, model, false); !kd) {
    return kd.error();
  }
  if (auto truthful = check_fallback_gains(request, motor_ids, model); !truthful) return truthful.error();

  control::MotorSet wanted;
  for (const auto id : motor_ids) wanted.set(static_cast<std::size_t>(id));
  DeviceSessions& sessions = sessions_[device_index.value()];
  if (const std::string holders = describe_holders(sessions, wanted, now_ns); !holders.empty()) {
    return refused("device '" + model.name + "': " + holders);
  }
  const auto free_slot =
      std::find_if(sessions.slots.begin(), sessions.slots.end(), [](const auto& slot) { return !slot.has_value(); });
  if (free_slot == sessions.slots.end()) {
    return refused("device '" + model.name + "' already has " + std::to_string(kMaxSessionsPerDevice) +
                   " sessions; release one first");
  }

  SessionRecord record;
  record.uuid = std::move(uuid);
  record.session_id = std::move(session_id);
  record.node_name = request.node_name.empty() ? "(unnamed)" : request.node_name;
  record.device_index = device_index.value();
  record.device = model.name;
  record.slot = static_cast<std::uint8_t>(free_slot - sessions.slots.begin());
  record.generation = sessions.next_generation++;
  record.motors = wanted;
  record.motor_ids = std::move(motor_ids);
  record.mode = request.control_mode;
  record.requested_behavior = request.default_behavior;
  record.applied_behavior = control::applied_behavior(request.default_behavior, model.behaviors);
  record.timeout_ms = request.timeout_ms;
  record.default_kp = request.default_kp;
  record.default_kd = request.default_kd;
  record.policy_name = request.policy_name;
  record.policy_file_name = request.policy_file_name;
  record.min_command_success_rate = request.min_command_success_rate;
  record.on_low_success_rate = request.on_low_success_rate;
  record.granted_ns = now_ns;
  record.granted_wall_ns = wall_ns;
  record.last_command_ns = now_ns;
  *free_slot = record;
  return record;
}

Result<SessionRecord> SessionTable::release(std::string_view uuid) {
  for (auto& sessions : sessions_) {
    for (auto& slot : sessions.slots) {
      if (slot && slot->uuid == uuid) {
        SessionRecord record = std::move(*slot);
        slot.reset();
        return record;
      }
    }
  }
  if (const SessionRecord* named = find_by_id(uuid)) {
    return refused("'" + named->session_id + "' is the public id of a session of node '" + named->node_name + "' on '" +
                   named->device +
                   "', not a uuid: only the uuid granted to its holder releases it. A session you do not hold ends "
                   "when its holder releases it or stops commanding it (timeout); the e-stop stops its motors at once");
  }
  return refused("no active session has uuid '" + std::string(uuid) + "' (it may have timed out or been released)");
}

std::optional<SessionRecord> SessionTable::end(std::size_t device, std::uint8_t slot, std::uint32_t generation) {
  if (device >= sessions_.size() || slot >= kMaxSessionsPerDevice) return std::nullopt;
  auto& entry = sessions_[device].slots[slot];
  if (!entry || entry->generation != generation) return std::nullopt;
  SessionRecord record = std::move(*entry);
  entry.reset();
  return record;
}

SessionRecord* SessionTable::find(std::string_view uuid) {
  for (auto& sessions : sessions_) {
    for (auto& slot : sessions.slots) {
      if (slot && slot->uuid == uuid) return &*slot;
    }
  }
  return nullptr;
}

const SessionRecord* SessionTable::find_by_id(std::string_view session_id) const {
  for (const auto& sessions : sessions_) {
    for (const auto& slot : sessions.slots) {
      if (slot && slot->session_id == session_id) return &*slot;
    }
  }
  return nullptr;
}

bool SessionTable::any_active(std::size_t device) const {
  const auto& slots = sessions_[device].slots;
  return std::any_of(slots.begin(), slots.end(), [](const auto& slot) { return slot.has_value(); });
}

std::string SessionTable::holders(std::size_t device, std::int64_t now_ns) const {
  return describe_holders(sessions_[device], control::MotorSet().set(), now_ns);
}

bool SessionTable::any_active() const {
  for (std::size_t i = 0; i < sessions_.size(); ++i) {
    if (any_active(i)) return true;
  }
  return false;
}

std::vector<std::int32_t> SessionTable::idle_motors(std::size_t device) const {
  control::MotorSet held;
  for (const auto& slot : sessions_[device].slots) {
    if (slot) held |= slot->motors;
  }
  std::vector<std::int32_t> idle;
  for (std::size_t i = 0; i < devices_[device]->joint_count(); ++i) {
    if (!held.test(i)) idle.push_back(static_cast<std::int32_t>(i));
  }
  return idle;
}

std::vector<SessionRecord> SessionTable::sessions() const {
  std::vector<SessionRecord> out;
  for (const auto& sessions : sessions_) {
    std::vector<SessionRecord> device_sessions;
    for (const auto& slot : sessions.slots) {
      if (slot) device_sessions.push_back(*slot);
    }
    std::sort(device_sessions.begin(), device_sessions.end(),
              [](const SessionRecord& a, const SessionRecord& b) { return a.granted_ns < b.granted_ns; });
    out.insert(out.end(), device_sessions.begin(), device_sessions.end());
  }
  return out;
}

}  // namespace robotd::session
