#include "dds/command_intake.hpp"

#include <spdlog/spdlog.h>

#include "app/log_text.hpp"
#include "dds/field_limits.hpp"
#include "robotd/limits.hpp"
#include "rt/monotonic_clock.hpp"
#include "session/session_ids.hpp"
#include "wire/qos.hpp"
#include "wire/topics.hpp"

namespace robotd::dds {
namespace {

// Deep enough that bursts from several sessions at 1 kHz are not lost before intake runs.
constexpr int kCommandHistoryDepth = 64;

}  // namespace

CommandIntake::CommandIntake(const wire::Participant& participant, std::vector<device::Device*> devices,
                             service::SessionService& sessions, SurfaceCounterSet& surface)
    : participant_(participant),
      devices_(std::move(devices)),
      sessions_(sessions),
      surface_(surface),
      sequence_(devices_.size(), 0) {
  for (std::size_t i = 0; i < devices_.size(); ++i) {
    counters_.push_back(std::make_unique<service::CommandCounterSet>());
    working_.push_back(std::make_unique<device::CommandSnapshot>());
  }
}

CommandIntake::~CommandIntake() { stop(); }

Result<void> CommandIntake::start() {
  auto qos = wire::reliable_qos(kCommandHistoryDepth);
  auto reader = wire::TopicReader<ControlCommand>::create(participant_, wire::kControlCommandTopic, qos.get());
  if (!reader) return reader.error();
  reader_ = std::make_unique<wire::TopicReader<ControlCommand>>(std::move(reader.value()));
  waitset_ = wire::Entity(dds_create_waitset(participant_.handle()));
  dds_waitset_attach(waitset_.get(), dds_create_readcondition(reader_->handle(), DDS_ANY_STATE), 0);
  stop_condition_ = dds_create_guardcondition(participant_.handle());
  dds_waitset_attach(waitset_.get(), stop_condition_, 0);
  thread_ = std::thread([this] { run(); });
  return {};
}

void CommandIntake::stop() {
  if (!thread_.joinable()) return;
  stopping_.store(true);
  dds_set_guardcondition(stop_condition_, true);
  thread_.join();
}

void CommandIntake::run() {
  pthread_setname_np(pthread_self(), "cmd-intake");
  while (!stopping_.load()) {
    dds_waitset_wait(waitset_.get(), nullptr, 0, DDS_MSECS(100));
    reader_->take_each([this](ControlCommand&& command, const dds_sample_info_t& /*info*/) {
      handle(command, rt::monotonic_now_ns());
    });
  }
}

template <class MakeDetail>
void CommandIntake::reject(std::size_t device, control::Rejection reason, MakeDetail make_detail) {
  counters_[device]->count_rejection(reason);
  const std::string& name = devices_[device]->model().name;
  log_.warn(name + "/" + control::to_string(reason), [&] {
    return "rejected command on '" + name + "' (" + control::to_string(reason) + "): " + make_detail();
  });
}

std::size_t CommandIntake::counting_device(const ControlCommand& command) const {
  if (command.device.size() > limits::kDeviceNameBytes) return devices_.size();
  const auto named = sessions_.resolve_device(command.device);
  return named ? named.value() : devices_.size();
}

void CommandIntake::handle(const ControlCommand& command, std::int64_t now_ns) {
  const std::optional<Oversize> oversize = find_oversize(command);
  const auto session = sessions_.authorize(command.uuid);
  // Who sent it, for a log line: its session's public id, never a uuid that works.
  const auto sender = [&] {
    return session ? "session " + session->session_id : "uuid " + session::redacted_uuid(command.uuid);
  };
  if (!session || oversize) {
    // Counted against its session's device, else the device it names, else the only device;
    // with none of those no device's counters can hold it, and the surface's do.
    const std::size_t device = session ? session->device : counting_device(command);
    if (device == devices_.size()) {
      surface_.commands_unattributed.fetch_add(1, std::memory_order_relaxed);
      log_.warn("unattributed", [&] {
        return "rejected command: " + sender() + " is no active session and the command names no known device ('" +
               app::log_text(command.device) + "')" + (oversize ? "; " + oversize->describe() : "");
      });
      return;
    }
    counters_[device]->received.fetch_add(1, std::memory_order_relaxed);
    if (oversize) {
      reject(device, control::Rejection::kMalformed, [&] { return oversize->describe() + " [" + sender() + "]"; });
    } else {
      reject(device, control::Rejection::kUnknownSession, [&] {
        return std::string(sessions_.is_session_id(command.uuid)
                               ? "this is a session's public id, not its uuid (only the uuid request_control "
                                 "granted commands)"
                               : "no active session has this uuid (request_control first; sessions end on timeout)") +
               " [" + sender() + "]";
      });
    }
    return;
  }

  const std::size_t device_index = session->device;
  device::Device& device = *devices_[device_index];
  service::CommandCounterSet& counters = *counters_[device_index];
  counters.received.fetch_add(1, std::memory_order_relaxed);

  const DeviceState state = device.channel().device_state.load(std::memory_order_acquire);
  if (state == DeviceState::kEstop) {
    reject(device_index, control::Rejection::kEstop,
           [&] { return "device is e-stopped; reset the e-stop first [" + sender() + "]"; });
    return;
  }
  if (state != DeviceState::kRunning) {
    reject(device_index, control::Rejection::kFault,
           [&] { return "device is " + std::string(to_string(state)) + ", not RUNNING [" + sender() + "]"; });
    return;
  }

  const control::SessionView view{device.model().name, session->mode, session->motors};
  const control::Verdict verdict = control::validate_command(command, view, device.model(), validated_);
  if (verdict.rejection) {
    reject(device_index, *verdict.rejection, [&] { return app::log_text(verdict.detail) + " [" + sender() + "]"; });
    return;
  }

  device::CommandSnapshot& snapshot = *working_[device_index];
  const std::uint64_t sequence = ++sequence_[device_index];
  for (std::size_t i = 0; i < validated_.count; ++i) {
    const control::JointTargetUpdate& update = validated_.joints[i];
    device::JointTarget& target = snapshot.joints[update.joint];
    target.generation = session->generation;
    target.sequence = sequence;
    target.received_ns = now_ns;
    target.sent_ns = command.sent_steady_ns;
    target.update = update;
  }
  snapshot.slots[session->slot] = device::SlotActivity{session->generation, now_ns};
  device.channel().commands.write_buffer() = snapshot;
  device.channel().commands.publish();

  counters.accepted.fetch_add(1, std::memory_order_relaxed);
  if (validated_.clamped) counters.clamped.fetch_add(1, std::memory_order_relaxed);
  sessions_.note_command(command.uuid, now_ns);
}

}  // namespace robotd::dds
