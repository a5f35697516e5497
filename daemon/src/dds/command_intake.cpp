#include "dds/command_intake.hpp"

#include <spdlog/spdlog.h>

#include "app/log_text.hpp"
#include "dds/field_limits.hpp"
#include "device/command_admission.hpp"
#include "rt/monotonic_clock.hpp"
#include "session/session_ids.hpp"
#include "wire/qos.hpp"
#include "wire/topics.hpp"

namespace robotd::dds {
namespace {

// Deep enough that bursts from several sessions at 1 kHz are not lost before intake runs. Only
// active sessions' commands take a place (admits()).
constexpr int kCommandHistoryDepth = 64;

}  // namespace

CommandIntake::CommandIntake(const wire::Participant& participant, std::vector<device::Device*> devices,
                             service::SessionService& sessions, SurfaceCounterSet& surface)
    : participant_(participant), devices_(std::move(devices)), sessions_(sessions), surface_(surface) {
  for (device::Device* device : devices_) {
    counters_.push_back(std::make_unique<service::CommandCounterSet>());
    mailboxes_.push_back(std::make_unique<device::CommandMailbox>(device->channel()));
    auto& keys = log_keys_.emplace_back();
    for (std::size_t reason = 0; reason < keys.size(); ++reason) {
      keys[reason] = device->model().name + "/" + control::to_string(static_cast<control::Rejection>(reason));
    }
  }
}

CommandIntake::~CommandIntake() {
  stop();
  reader_.reset();  // first: until the reader is gone, Cyclone may call admits() on this object
}

Result<void> CommandIntake::start() {
  auto qos = wire::reliable_qos(kCommandHistoryDepth);
  const dds_topic_filter filter{.mode = DDS_TOPIC_FILTER_SAMPLE_ARG, .f = {.sample_arg = &admits}, .arg = this};
  auto reader = wire::TopicReader<ControlCommand>::create(participant_, wire::kControlCommandTopic, qos.get(), &filter);
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

bool CommandIntake::admits(const void* sample, void* intake) {
  const auto& command = *static_cast<const wire::Wire<ControlCommand>::C*>(sample);
  auto& self = *static_cast<CommandIntake*>(intake);
  const std::string_view uuid = command.uuid != nullptr ? command.uuid : "";
  if (self.sessions_.is_active(uuid)) return true;
  try {
    self.reject_unknown_session(uuid, command.device != nullptr ? command.device : "");
  } catch (const std::exception&) {
    return false;  // counted before the log line that failed; no exception may reach Cyclone
  }
  return false;
}

void CommandIntake::reject_unknown_session(std::string_view uuid, std::string_view device_name) {
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
  reject(*device, control::Rejection::kUnknownSession, [&] {
    return std::string(sessions_.is_session_id(uuid)
                           ? "this is a session's public id, not its uuid (only the uuid request_control granted "
                             "commands)"
                           : "no active session has this uuid (request_control first; sessions end on timeout)") +
           " [uuid " + session::redacted_uuid(uuid) + "]";
  });
}

template <class MakeDetail>
void CommandIntake::reject(std::size_t device, control::Rejection reason, MakeDetail make_detail) {
  counters_[device]->count_rejection(reason);
  log_.warn(log_keys_[device][static_cast<std::size_t>(reason)], [&] {
    return "rejected command on '" + devices_[device]->model().name + "' (" + control::to_string(reason) +
           "): " + make_detail();
  });
}

void CommandIntake::handle(const ControlCommand& command, std::int64_t now_ns) {
  const auto session = sessions_.authorize(command.uuid);
  if (!session) {  // its session ended after admits() let it through
    reject_unknown_session(command.uuid, command.device);
    return;
  }
  // Who sent it, for a log line: its session's public id, never the uuid.
  const auto sender = [&] { return " [session " + session->session_id + "]"; };

  const std::size_t device_index = session->device;
  device::Device& device = *devices_[device_index];
  service::CommandCounterSet& counters = *counters_[device_index];
  counters.received.fetch_add(1, std::memory_order_relaxed);

  if (const std::optional<Oversize> oversize = find_oversize(command)) {
    reject(device_index, control::Rejection::kMalformed, [&] { return oversize->describe() + sender(); });
    return;
  }
  if (const auto refusal = device::command_refusal(device.channel())) {
    reject(device_index, refusal->reason, [&] { return refusal->detail + sender(); });
    return;
  }

  const control::SessionView view{device.model().name, session->mode, session->motors};
  const control::Verdict verdict = control::validate_command(command, view, device.model(), validated_);
  if (verdict.rejection) {
    reject(device_index, *verdict.rejection, [&] { return app::log_text(verdict.detail) + sender(); });
    return;
  }

  mailboxes_[device_index]->post(session->slot, session->generation, validated_, now_ns, command.sent_steady_ns);

  counters.accepted.fetch_add(1, std::memory_order_relaxed);
  if (validated_.clamped) counters.clamped.fetch_add(1, std::memory_order_relaxed);
  sessions_.note_command(command.uuid, now_ns);
}

}  // namespace robotd::dds
