#include "dds/command_intake.hpp"

#include <spdlog/spdlog.h>

#include "rt/monotonic_clock.hpp"
#include "rt/realtime_thread.hpp"
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
    : participant_(participant), gate_(std::move(devices), sessions, surface) {}

CommandIntake::~CommandIntake() {
  stop();
  reader_.reset();  // first: until the reader is gone, Cyclone may call admits() on this object
}

Result<void> CommandIntake::start(int fifo_priority) {
  auto qos = wire::reliable_qos(kCommandHistoryDepth);
  const dds_topic_filter filter{.mode = DDS_TOPIC_FILTER_SAMPLE_ARG, .f = {.sample_arg = &admits}, .arg = this};
  auto reader = wire::TopicReader<ControlCommand>::create(participant_, wire::kControlCommandTopic, qos.get(), &filter);
  if (!reader) return reader.error();
  reader_ = std::make_unique<wire::TopicReader<ControlCommand>>(std::move(reader.value()));
  waitset_ = wire::Entity(dds_create_waitset(participant_.handle()));
  dds_waitset_attach(waitset_.get(), dds_create_readcondition(reader_->handle(), DDS_ANY_STATE), 0);
  stop_condition_ = dds_create_guardcondition(participant_.handle());
  dds_waitset_attach(waitset_.get(), stop_condition_, 0);
  thread_ = driver::NamedThread("cmd-intake", [this, fifo_priority] {
    (void)rt::run_current_thread_fifo(fifo_priority);
    run();
  });
  return {};
}

void CommandIntake::stop() {
  if (!thread_.joinable()) return;
  stopping_.store(true);
  dds_set_guardcondition(stop_condition_, true);
  thread_.join();
}

void CommandIntake::run() {
  while (!stopping_.load()) {
    dds_waitset_wait(waitset_.get(), nullptr, 0, DDS_MSECS(100));
    reader_->take_each([this](ControlCommand&& command, const dds_sample_info_t& /*info*/) {
      gate_.handle(command, rt::monotonic_now_ns());
    });
  }
}

bool CommandIntake::admits(const void* sample, void* intake) {
  const auto& command = *static_cast<const wire::Wire<ControlCommand>::C*>(sample);
  auto& self = *static_cast<CommandIntake*>(intake);
  try {
    return self.gate_.admit(command.uuid != nullptr ? command.uuid : "",
                            command.device != nullptr ? command.device : "");
  } catch (const std::exception&) {
    return false;  // counted before the log line that failed; no exception may reach Cyclone
  }
}

}  // namespace robotd::dds
