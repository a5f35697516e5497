#include "tick_link.hpp"

#include <algorithm>
#include <thread>

#include "wire/qos.hpp"
#include "wire/topics.hpp"

namespace robotd::detail {
namespace {

// A controller wants only the newest state (robotd's writer keeps last 1 likewise).
constexpr int kTickDepth = 1;
// /device_status carries every device's samples: deep enough to keep this device's among them.
constexpr int kDeviceStatusDepth = 16;

std::string ms_text(std::chrono::milliseconds duration) { return std::to_string(duration.count()) + " ms"; }

}  // namespace

Result<std::unique_ptr<TickLink>> TickLink::create(std::shared_ptr<ClientCore> core, std::string device,
                                                   std::string session_id) {
  const auto qos = wire::transient_local_qos(1);  // the current sessions at once, then each change
  auto statuses = wire::TopicReader<SessionStatus>::create(core->participant, wire::kSessionStatusTopic, qos.get());
  if (!statuses) return statuses.error();
  return std::unique_ptr<TickLink>(
      new TickLink(std::move(core), std::move(device), std::move(session_id), std::move(statuses.value())));
}

TickLink::TickLink(std::shared_ptr<ClientCore> core, std::string device, std::string session_id,
                   wire::TopicReader<SessionStatus> statuses)
    : core_(std::move(core)),
      device_(std::move(device)),
      session_id_(std::move(session_id)),
      statuses_(std::move(statuses)),
      waitset_(dds_create_waitset(core_->participant.handle())) {
  attach(statuses_.handle());
}

TickLink::~TickLink() = default;

void TickLink::attach(dds_entity_t reader) {
  // The condition is the reader's child: it goes with the reader.
  dds_waitset_attach(waitset_.get(), dds_create_readcondition(reader, DDS_ANY_STATE), 0);
}

Result<void> TickLink::open_ticks(std::chrono::milliseconds match_timeout) {
  if (ticks_ == nullptr) {
    const auto qos = wire::reliable_qos(kTickDepth);
    auto reader = wire::TopicReader<TickState>::create(core_->participant, wire::tick_state_topic(device_), qos.get());
    if (!reader) return reader.error();
    ticks_ = std::make_unique<wire::TopicReader<TickState>>(std::move(reader.value()));
    attach(ticks_->handle());
  }
  const auto deadline = std::chrono::steady_clock::now() + match_timeout;
  while (ticks_->matched_writers() == 0 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return {};
}

void TickLink::drain() {
  if (ticks_ != nullptr) {
    ticks_->take_each([this](TickState&& state, const dds_sample_info_t& /*info*/) {
      if (!newest_tick_ || state.tick > newest_tick_->tick) newest_tick_ = std::move(state);
    });
  }
  statuses_.take_each([this](SessionStatus&& status, const dds_sample_info_t& /*info*/) {
    const auto mine = std::ranges::find(status.sessions, session_id_, &SessionInfo::uuid);
    if (mine != status.sessions.end()) {
      info_ = std::move(*mine);
      listed_ = true;
    } else if (listed_ || statuses_taken_ > 0) {
      ended_ = true;
    }
    ++statuses_taken_;
  });
  if (device_statuses_ != nullptr) {
    device_statuses_->take_each([this](DeviceStatus&& status, const dds_sample_info_t& /*info*/) {
      if (status.device == device_ && status.loop.period_ns > 0) {
        device_phase_ = TickPhase{status.loop.tick_deadline_steady_ns, status.loop.period_ns};
      }
    });
  }
}

bool TickLink::wait_until(std::chrono::steady_clock::time_point deadline) {
  const auto left = deadline - std::chrono::steady_clock::now();
  if (left <= std::chrono::steady_clock::duration::zero()) return false;
  dds_waitset_wait(waitset_.get(), nullptr, 0, std::chrono::duration_cast<std::chrono::nanoseconds>(left).count());
  return true;
}

Error TickLink::ended_error() const {
  return make_error(ErrorCode::kRefused, "session " + session_id_ + " on '" + device_ +
                                             "' has ended: robotd no longer lists it in /session_status (it timed "
                                             "out, fell back, or was released or e-stopped)");
}

Result<TickState> TickLink::next_tick(std::chrono::milliseconds timeout) {
  if (ticks_ == nullptr) {
    // Discovery: the first call may take up to the service timeout more than `timeout`.
    if (auto opened = open_ticks(core_->options.service_timeout); !opened) return opened.error();
  }
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  do {
    drain();
    if (ended_) return ended_error();
    if (newest_tick_ && newest_tick_->tick > last_returned_tick_) {
      last_returned_tick_ = newest_tick_->tick;
      return *newest_tick_;
    }
  } while (wait_until(deadline));
  return make_error(ErrorCode::kTimeout, "no TickState of '" + device_ + "' newer than tick " +
                                             std::to_string(last_returned_tick_) + " within " + ms_text(timeout) +
                                             " (" + wire::tick_state_topic(device_) + " has " +
                                             std::to_string(ticks_->matched_writers()) + " matched writer(s))");
}

Result<SessionInfo> TickLink::info(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  do {
    drain();
    if (ended_) return ended_error();
    if (info_) return *info_;
  } while (wait_until(deadline));
  return make_error(ErrorCode::kTimeout,
                    "no /session_status listing session " + session_id_ + " within " + ms_text(timeout));
}

Result<TickPhase> TickLink::phase(std::chrono::milliseconds timeout) {
  if (ticks_ == nullptr && device_statuses_ == nullptr) {
    const auto qos = wire::reliable_qos(kDeviceStatusDepth);
    auto reader = wire::TopicReader<DeviceStatus>::create(core_->participant, wire::kDeviceStatusTopic, qos.get());
    if (!reader) return reader.error();
    device_statuses_ = std::make_unique<wire::TopicReader<DeviceStatus>>(std::move(reader.value()));
    attach(device_statuses_->handle());
  }
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  do {
    drain();
    if (newest_tick_ && newest_tick_->period_ns > 0) {
      return TickPhase{newest_tick_->deadline_steady_ns, newest_tick_->period_ns};
    }
    if (device_phase_.known()) return device_phase_;
  } while (wait_until(deadline));
  return make_error(ErrorCode::kTimeout, "no tick phase of '" + device_ + "' within " + ms_text(timeout) +
                                             ": neither a TickState nor a /device_status with loop.period_ns");
}

}  // namespace robotd::detail
