#include "dds/command_gate.hpp"

#include "app/log_text.hpp"
#include "dds/field_limits.hpp"
#include "device/command_admission.hpp"
#include "robotd/limits.hpp"
#include "session/session_ids.hpp"

namespace robotd::dds {

CommandGate::CommandGate(std::vector<device::Device*> devices, service::SessionService& sessions,
                         SurfaceCounterSet& surface)
    : devices_(std::move(devices)), sessions_(sessions), surface_(surface) {
  for (device::Device* device : devices_) {
    counters_.push_back(std::make_unique<service::CommandCounterSet>());
    mailboxes_.push_back(std::make_unique<device::CommandMailbox>(device->channel()));
    auto& keys = log_keys_.emplace_back();
    for (std::size_t reason = 0; reason < keys.size(); ++reason) {
      keys[reason] = device->model().name + "/" + control::to_string(static_cast<control::Rejection>(reason));
    }
  }
}

bool CommandGate::admit(std::string_view uuid, std::string_view device_name) {
  if (sessions_.is_active(uuid)) return true;
  reject_unknown_session(uuid, device_name);
  return false;
}

void CommandGate::reject_unknown_session(std::string_view uuid, std::string_view device_name) {
  const auto device = sessions_.find_device(device_name);
  if (!device) {
    surface_.commands_unattributed.fetch_add(1, std::memory_order_relaxed);
    log_.warn("unattributed", [&] {
      return "rejected command: uuid " + session::redacted_uuid(uuid) +
             " is no active session and the command names no known device ('" + app::log_text(device_name) + "')";
    });
    return;
  }
  counters_[*device]->received.fetch_add(1, std::memory_order_relaxed);
  if (uuid.size() > limits::kUuidBytes) {  // no uuid at all: malformed, as handle() would call it
    const Oversize oversize{"uuid", uuid.size(), limits::kUuidBytes, false};
    reject(*device, control::Rejection::kMalformed, [&] { return oversize.describe(); });
    return;
  }
  reject(*device, control::Rejection::kUnknownSession, [&] {
    return std::string(sessions_.is_session_id(uuid)
                           ? "this is a session's public id, not its uuid (only the uuid request_control granted "
                             "commands)"
                           : "no active session has this uuid (request_control first; sessions end on timeout)") +
           " [uuid " + session::redacted_uuid(uuid) + "]";
  });
}

template <class MakeDetail>
void CommandGate::reject(std::size_t device, control::Rejection reason, MakeDetail make_detail) {
  counters_[device]->count_rejection(reason);
  log_.warn(log_keys_[device][static_cast<std::size_t>(reason)], [&] {
    return "rejected command on '" + devices_[device]->model().name + "' (" + control::to_string(reason) +
           "): " + make_detail();
  });
}

const control::ValidatedCommand* CommandGate::handle(const ControlCommand& command, std::int64_t now_ns) {
  const auto session = sessions_.authorize(command.uuid);
  if (!session) {  // its session ended after admit() let it through
    reject_unknown_session(command.uuid, command.device);
    return nullptr;
  }
  // Who sent it, for a log line: its session's public id, never the uuid.
  const auto sender = [&] { return " [session " + session->session_id + "]"; };

  const std::size_t device_index = session->device;
  device::Device& device = *devices_[device_index];
  service::CommandCounterSet& counters = *counters_[device_index];
  counters.received.fetch_add(1, std::memory_order_relaxed);

  if (const std::optional<Oversize> oversize = find_oversize(command)) {
    reject(device_index, control::Rejection::kMalformed, [&] { return oversize->describe() + sender(); });
    return nullptr;
  }
  if (const std::uint64_t newest = device.channel().ticks.load(std::memory_order_acquire);
      command.answers_tick > newest) {
    reject(device_index, control::Rejection::kMalformed, [&] {
      return "answers_tick " + std::to_string(command.answers_tick) + " names a tick device '" + device.model().name +
             "' has not run (its newest is " + std::to_string(newest) +
             "): answer a TickState's tick, or send 0 for none" + sender();
    });
    return nullptr;
  }
  if (const auto refusal = device::command_refusal(device.channel())) {
    reject(device_index, refusal->reason, [&] { return refusal->detail + sender(); });
    return nullptr;
  }

  const control::SessionView view{device.model().name, session->mode, session->motors};
  const auto limits = device.limits();
  const control::Verdict verdict = control::validate_command(command, view, device.model(), *limits, validated_);
  if (verdict.rejection) {
    reject(device_index, *verdict.rejection, [&] { return app::log_text(verdict.detail) + sender(); });
    return nullptr;
  }

  mailboxes_[device_index]->post(session->slot, session->generation, validated_, now_ns, command.sent_steady_ns,
                                 command.answers_tick);

  counters.accepted.fetch_add(1, std::memory_order_relaxed);
  if (validated_.clamped) counters.clamped.fetch_add(1, std::memory_order_relaxed);
  sessions_.note_command(command.uuid, now_ns);
  return &validated_;
}

}  // namespace robotd::dds
