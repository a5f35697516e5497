// What a Client and its Sessions share: the DDS participant, the service clients, the command
// writer and the dispatch thread.
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <string_view>

#include "dispatcher.hpp"
#include "permitted.hpp"
#include "robotd/client/options.hpp"
#include "robotd/client/subscription.hpp"
#include "robotd/messages.hpp"
#include "wire/service.hpp"
#include "wire/topic_io.hpp"

namespace robotd::detail {

class ClientCore {
 public:
  static Result<std::shared_ptr<ClientCore>> create(const ClientOptions& options);

  template <class T>
  Subscription subscribe(std::string_view topic, const dds_qos_t* qos, std::function<void(const T&)> callback) {
    auto reader = wire::TopicReader<T>::create(participant, topic, qos);
    if (!reader) return Subscription();
    auto owned = std::make_shared<wire::TopicReader<T>>(std::move(reader.value()));
    const std::uint64_t id = dispatcher->add(
        owned->handle(),
        [raw = owned.get(), callback = std::move(callback)] {
          raw->take_each([&](T&& value, const dds_sample_info_t& /*info*/) { callback(value); });
        },
        owned);
    return Subscription([dispatcher = dispatcher, id] { dispatcher->remove(id); });
  }

  /// Waits until the command writer has matched a subscriber (robotd's command reader), at most
  /// `timeout`. Commands written before discovery matched the two are not delivered.
  void await_command_subscriber(std::chrono::milliseconds timeout) const;

  ClientOptions options;
  wire::Participant participant;
  Permitted<wire::ServiceClient<RequestControlRequest, RequestControlResponse>> request_control;
  Permitted<wire::ServiceClient<ReleaseControlRequest, ReleaseControlResponse>> release_control;
  Permitted<wire::ServiceClient<GetAvailableMotorsRequest, GetAvailableMotorsResponse>> available_motors;
  Permitted<wire::ServiceClient<ResetZeroRequest, ResetZeroResponse>> reset_zero;
  Permitted<wire::ServiceClient<EstopRequest, EstopResponse>> estop;
  Permitted<wire::ServiceClient<ListDevicesRequest, ListDevicesResponse>> list_devices;
  Permitted<wire::ServiceClient<DeviceCallRequest, DeviceCallResponse>> device_call;
  Permitted<wire::TopicWriter<ControlCommand>> commands;
  std::shared_ptr<Dispatcher> dispatcher;

 private:
  ClientCore(ClientOptions client_options, wire::Participant client_participant)
      : options(std::move(client_options)), participant(std::move(client_participant)) {}
};

}  // namespace robotd::detail
