#include "tick_peer.hpp"

#include <stdexcept>

#include "wire/qos.hpp"
#include "wire/topics.hpp"

namespace robotd::testing {
namespace {

template <class T>
T created(Result<T>&& result) {
  if (!result) throw std::runtime_error(result.error().message);
  return std::move(result).value();
}

wire::DdsSettings settings_of(const TestDomain& domain) {
  wire::DdsSettings settings;
  settings.domain_id = domain.id();
  return settings;
}

template <class T>
std::unique_ptr<wire::TopicWriter<T>> writer(const wire::Participant& participant, std::string_view topic,
                                             const wire::QosPtr& qos) {
  return std::make_unique<wire::TopicWriter<T>>(created(wire::TopicWriter<T>::create(participant, topic, qos.get())));
}

}  // namespace

TickPeer::TickPeer() : participant_(created(wire::Participant::create(settings_of(domain_)))) {
  request_control_ = created(
      wire::ServiceServer<RequestControlRequest, RequestControlResponse>::create(participant_, "request_control"));
  release_control_ = created(
      wire::ServiceServer<ReleaseControlRequest, ReleaseControlResponse>::create(participant_, "release_control"));
  ticks_ = writer<TickState>(participant_, wire::tick_state_topic(kPeerDevice), wire::reliable_qos(1));
  statuses_ = writer<SessionStatus>(participant_, wire::kSessionStatusTopic, wire::transient_local_qos(1));
  device_statuses_ = writer<DeviceStatus>(participant_, wire::kDeviceStatusTopic, wire::reliable_qos(10));
  commands_ = std::make_unique<wire::TopicReader<ControlCommand>>(created(wire::TopicReader<ControlCommand>::create(
      participant_, wire::kControlCommandTopic, wire::reliable_qos(1000).get())));
  server_ = std::jthread([this](const std::stop_token& stop) {
    while (!stop.stop_requested()) {
      request_control_->take_requests([this](const wire::RequestId& id, RequestControlRequest&& request) {
        RequestControlResponse granted;
        granted.success = true;
        granted.uuid = "uuid-of-" + request.node_name;
        granted.session_id = std::string(kPeerSessionId);
        granted.device = std::string(kPeerDevice);
        granted.motor_ids = {0, 1, 2, 3, 4, 5};
        granted.applied_behavior = request.default_behavior;
        (void)request_control_->reply(id, granted);
      });
      release_control_->take_requests([this](const wire::RequestId& id, ReleaseControlRequest&& /*request*/) {
        (void)release_control_->reply(id, ReleaseControlResponse{true, "released"});
      });
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  });
}

TickPeer::~TickPeer() {
  server_.request_stop();
  server_.join();
}

ClientOptions TickPeer::client_options() const {
  ClientOptions options;
  options.domain_id = domain_.id();
  options.node_name = "tick_client";
  options.service_timeout = std::chrono::seconds(10);
  return options;
}

TickState TickPeer::tick_state(std::uint64_t tick) {
  TickState state;
  state.header.frame_id = std::string(kPeerDevice);
  state.tick = tick;
  state.period_ns = kPeerPeriodNs;
  state.deadline_steady_ns = static_cast<std::int64_t>(tick) * kPeerPeriodNs;
  state.state = DeviceState::kRunning;
  for (int j = 0; j < 6; ++j) {
    state.position.push_back(static_cast<double>(tick) / 1000.0 + j);
    state.velocity.push_back(0.0);
    state.effort.push_back(0.0);
  }
  return state;
}

void TickPeer::write_tick(std::uint64_t tick) const { (void)ticks_->write(tick_state(tick)); }

void TickPeer::write_session_status(bool listed, std::uint64_t ticks_in_time) const {
  SessionStatus status;
  status.state = listed ? "active" : "idle";
  if (listed) {
    SessionInfo info;
    info.uuid = std::string(kPeerSessionId);
    info.device = std::string(kPeerDevice);
    info.closed_loop = ticks_in_time > 0;
    info.ticks_to_answer = ticks_in_time;
    info.ticks_answered_in_time = ticks_in_time;
    info.command_success_rate = ticks_in_time > 0 ? 1.0F : 0.0F;
    status.sessions.push_back(info);
    status.active_uuids.push_back(info.uuid);
  }
  (void)statuses_->write(status);
}

void TickPeer::write_device_status(std::int64_t tick_deadline_steady_ns, std::int64_t period_ns) const {
  DeviceStatus status;
  status.device = std::string(kPeerDevice);
  status.state = DeviceState::kRunning;
  status.loop.tick_deadline_steady_ns = tick_deadline_steady_ns;
  status.loop.period_ns = period_ns;
  (void)device_statuses_->write(status);
}

std::optional<ControlCommand> TickPeer::next_command(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (received_.empty() && std::chrono::steady_clock::now() < deadline) {
    commands_->take_each([this](ControlCommand&& command, const dds_sample_info_t& /*info*/) {
      received_.push_back(std::move(command));
    });
    if (received_.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  if (received_.empty()) return std::nullopt;
  ControlCommand first = std::move(received_.front());
  received_.erase(received_.begin());
  return first;
}

bool TickPeer::await_tick_reader(std::chrono::milliseconds timeout) const {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (ticks_->matched_readers() == 0) {
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

}  // namespace robotd::testing
