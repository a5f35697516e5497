#include "robotd/client/client.hpp"

#include <condition_variable>
#include <mutex>
#include <optional>

#include "client_core.hpp"
#include "policy_data_publisher_impl.hpp"
#include "tick_link.hpp"
#include "wire/dds_settings.hpp"
#include "wire/qos.hpp"
#include "wire/topics.hpp"

namespace robotd {
namespace {

constexpr int kStateHistoryDepth = 10;
// As deep as robotd's own command reader: several sessions streaming at 1 kHz arrive in bursts.
constexpr int kCommandHistoryDepth = 64;

Error refused(const std::string& service, const std::string& message) {
  return make_error(ErrorCode::kRefused, "robotd refused " + service + ": " + message);
}

// Waits for the first value a subscription delivers that satisfies `accept`.
template <class T>
class FirstValue {
 public:
  void offer(const T& value) {
    const std::lock_guard lock(mutex_);
    if (!value_) {
      value_ = value;
      ready_.notify_all();
    }
  }
  std::optional<T> wait(std::chrono::milliseconds timeout) {
    std::unique_lock lock(mutex_);
    ready_.wait_for(lock, timeout, [this] { return value_.has_value(); });
    return value_;
  }

 private:
  std::mutex mutex_;
  std::condition_variable ready_;
  std::optional<T> value_;
};

}  // namespace

ClientOptions ClientOptions::from_environment() {
  const wire::DdsSettings settings = wire::dds_settings_from_environment();
  ClientOptions options;
  options.domain_id = settings.domain_id;
  options.network_interface = settings.network_interface;
  options.multicast = settings.multicast;
  options.peers = settings.peers;
  options.security = settings.security;
  return options;
}

Result<Client> Client::connect(const ClientOptions& options) {
  auto core = detail::ClientCore::create(options);
  if (!core) return core.error();
  return Client(std::move(core.value()));
}

Client::Client(std::shared_ptr<detail::ClientCore> core) : core_(std::move(core)) {}
Client::Client(Client&&) noexcept = default;
Client& Client::operator=(Client&&) noexcept = default;
Client::~Client() = default;

const ClientOptions& Client::options() const { return core_->options; }

Result<std::vector<DeviceInfo>> Client::list_devices() {
  auto response =
      core_->list_devices.call(ListDevicesRequest{core_->options.node_name}, core_->options.service_timeout);
  if (!response) return response.error();
  return std::move(response.value().devices);
}

Result<Session> Client::request_control(const SessionRequest& request) {
  RequestControlRequest wire_request;
  wire_request.node_name = core_->options.node_name;
  wire_request.device = request.device;
  wire_request.motor_ids = request.motor_ids;
  wire_request.control_mode = request.mode;
  wire_request.default_behavior = request.on_timeout;
  wire_request.timeout_ms = static_cast<std::int32_t>(request.timeout.count());
  wire_request.default_kp = request.default_kp;
  wire_request.default_kd = request.default_kd;
  wire_request.policy_name = request.policy_name;
  wire_request.policy_file_name = request.policy_file_name;
  wire_request.min_command_success_rate = request.min_command_success_rate;
  wire_request.on_low_success_rate = request.on_low_success_rate;
  auto response = core_->request_control.call(wire_request, core_->options.service_timeout);
  if (!response) return response.error();
  if (!response.value().success) return refused("/request_control", response.value().message);
  // The session's timeout runs from now: its first commands must not be lost to discovery.
  core_->await_command_subscriber(core_->options.service_timeout);
  Session session(core_, std::move(response.value()), request);
  if (request.closed_loop) {
    // Its first ticks too: the tick state reader is matched before the session is handed over.
    auto link = session.tick_link();
    if (!link) return link.error();
    if (auto opened = link.value()->open_ticks(core_->options.service_timeout); !opened) return opened.error();
  }
  return session;
}

Result<ReleaseControlResponse> Client::release_control(const std::string& uuid, Behavior release_mode) {
  auto response = core_->release_control.call(ReleaseControlRequest{core_->options.node_name, uuid, release_mode},
                                              core_->options.service_timeout);
  if (!response) return response.error();
  if (!response.value().success) return refused("/release_control", response.value().message);
  return response;
}

Result<GetAvailableMotorsResponse> Client::available_motors(const std::string& device) {
  auto response = core_->available_motors.call(GetAvailableMotorsRequest{core_->options.node_name, device},
                                               core_->options.service_timeout);
  if (!response) return response.error();
  if (!response.value().success) return refused("/get_available_motors", response.value().message);
  return response;
}

Result<EstopResponse> Client::estop(const std::string& device, const std::string& reason) {
  auto response =
      core_->estop.call(EstopRequest{core_->options.node_name, device, true, reason}, core_->options.service_timeout);
  if (!response) return response.error();
  if (!response.value().success) return refused("/estop", response.value().message);
  return response;
}

Result<EstopResponse> Client::reset_estop(const std::string& device) {
  auto response =
      core_->estop.call(EstopRequest{core_->options.node_name, device, false, ""}, core_->options.service_timeout);
  if (!response) return response.error();
  if (!response.value().success) return refused("/estop", response.value().message);
  return response;
}

Result<void> Client::reset_zero(const std::string& device, const std::vector<std::int32_t>& motor_ids,
                                std::chrono::milliseconds timeout) {
  auto response =
      core_->reset_zero.call(ResetZeroRequest{device, motor_ids, static_cast<std::int32_t>(timeout.count())},
                             core_->options.service_timeout, timeout + core_->options.service_timeout);
  if (!response) return response.error();
  if (!response.value().success) return refused("/reset_zero", response.value().message);
  return {};
}

Result<std::string> Client::device_call(const std::string& device, const std::string& op, const std::string& args_json,
                                        std::chrono::milliseconds timeout) {
  auto response =
      core_->device_call.call(DeviceCallRequest{device, op, args_json}, core_->options.service_timeout, timeout);
  if (!response) return response.error();
  if (!response.value().success) return refused("/device_call " + op, response.value().message);
  return std::move(response.value().result_json);
}

Subscription Client::on_joint_states(std::function<void(const JointState&)> callback) {
  const auto qos = wire::reliable_qos(kStateHistoryDepth);
  return core_->subscribe<JointState>(wire::kJointStatesTopic, qos.get(), std::move(callback));
}

Subscription Client::on_session_status(std::function<void(const SessionStatus&)> callback) {
  const auto qos = wire::transient_local_qos(1);
  return core_->subscribe<SessionStatus>(wire::kSessionStatusTopic, qos.get(), std::move(callback));
}

Subscription Client::on_device_status(std::function<void(const DeviceStatus&)> callback) {
  const auto qos = wire::reliable_qos(kStateHistoryDepth);
  return core_->subscribe<DeviceStatus>(wire::kDeviceStatusTopic, qos.get(), std::move(callback));
}

Subscription Client::on_imu(std::function<void(const Imu&)> callback) {
  const auto qos = wire::reliable_qos(kStateHistoryDepth);
  return core_->subscribe<Imu>(wire::kImuTopic, qos.get(), std::move(callback));
}

Subscription Client::on_end_pose(std::function<void(const PoseStamped&)> callback) {
  const auto qos = wire::reliable_qos(kStateHistoryDepth);
  return core_->subscribe<PoseStamped>(wire::kEndPoseTopic, qos.get(), std::move(callback));
}

Subscription Client::on_joy(std::function<void(const Joy&)> callback, const std::string& topic) {
  const auto qos = wire::reliable_qos(kStateHistoryDepth);
  return core_->subscribe<Joy>(wire::data_topic(topic), qos.get(), std::move(callback));
}

Subscription Client::on_policy_data(std::function<void(const PolicyData&)> callback) {
  const auto qos = wire::reliable_qos(kStateHistoryDepth);
  return core_->subscribe<PolicyData>(wire::kPolicyDataTopic, qos.get(), std::move(callback));
}

Subscription Client::on_control_commands(std::function<void(const ControlCommand&)> callback) {
  const auto qos = wire::reliable_qos(kCommandHistoryDepth);
  return core_->subscribe<ControlCommand>(wire::kControlCommandTopic, qos.get(), std::move(callback));
}

Result<JointState> Client::next_joint_state(const std::string& device, std::chrono::milliseconds timeout) {
  FirstValue<JointState> first;
  Subscription subscription = on_joint_states([&](const JointState& state) {
    if (device.empty() || state.header.frame_id == device) first.offer(state);
  });
  if (auto value = first.wait(timeout)) return std::move(*value);
  return make_error(ErrorCode::kTimeout, "no /joint_states sample" + (device.empty() ? "" : " for '" + device + "'") +
                                             " within " + std::to_string(timeout.count()) + " ms");
}

Result<DeviceStatus> Client::next_device_status(const std::string& device, std::chrono::milliseconds timeout) {
  FirstValue<DeviceStatus> first;
  Subscription subscription = on_device_status([&](const DeviceStatus& status) {
    if (device.empty() || status.device == device) first.offer(status);
  });
  if (auto value = first.wait(timeout)) return std::move(*value);
  return make_error(ErrorCode::kTimeout, "no /device_status sample" + (device.empty() ? "" : " for '" + device + "'") +
                                             " within " + std::to_string(timeout.count()) + " ms");
}

Result<SessionStatus> Client::session_status(std::chrono::milliseconds timeout) {
  FirstValue<SessionStatus> first;
  Subscription subscription = on_session_status([&](const SessionStatus& status) { first.offer(status); });
  if (auto value = first.wait(timeout)) return std::move(*value);
  return make_error(ErrorCode::kNotAvailable,
                    "no /session_status within " + std::to_string(timeout.count()) + " ms: is robotd running?");
}

Result<void> Client::publish(const ControlCommand& command) { return core_->commands.write(command); }

Result<PolicyDataPublisher> Client::policy_data_publisher() {
  const auto qos = wire::reliable_qos(kStateHistoryDepth);
  auto writer = wire::TopicWriter<PolicyData>::create(core_->participant, wire::kPolicyDataTopic, qos.get());
  if (!writer) return writer.error();
  return PolicyDataPublisher(
      std::make_unique<PolicyDataPublisher::Impl>(PolicyDataPublisher::Impl{core_, std::move(writer.value())}));
}

}  // namespace robotd
