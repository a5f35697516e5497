#include "client_core.hpp"

#include <thread>

#include "wire/qos.hpp"
#include "wire/topics.hpp"

namespace robotd::detail {
namespace {

// An endpoint DDS Security does not permit is kept as its error; any other failure is fatal.
template <class Endpoint>
Result<void> keep_denial(const Error& error, Permitted<Endpoint>& out) {
  if (error.code != ErrorCode::kNotPermitted) return error;
  out = Permitted<Endpoint>(error);
  return {};
}

template <class Client>
Result<void> make_client(const wire::Participant& participant, const char* service, Permitted<Client>& out) {
  auto created = Client::create(participant, service);
  if (!created) return keep_denial(created.error(), out);
  out = Permitted<Client>(std::move(created.value()));
  return {};
}

constexpr int kCommandHistoryDepth = 8;

}  // namespace

Result<std::shared_ptr<ClientCore>> ClientCore::create(const ClientOptions& options) {
  wire::DdsSettings settings;
  settings.domain_id = options.domain_id;
  settings.network_interface = options.network_interface;
  settings.multicast = options.multicast;
  settings.peers = options.peers;
  settings.cyclonedds_xml = options.cyclonedds_xml;
  settings.security = options.security;
  auto participant = wire::Participant::create(settings);
  if (!participant) return participant.error();

  std::shared_ptr<ClientCore> core(new ClientCore(options, std::move(participant.value())));
  for (const auto& result : {make_client(core->participant, "request_control", core->request_control),
                             make_client(core->participant, "release_control", core->release_control),
                             make_client(core->participant, "get_available_motors", core->available_motors),
                             make_client(core->participant, "reset_zero", core->reset_zero),
                             make_client(core->participant, "estop", core->estop),
                             make_client(core->participant, "list_devices", core->list_devices),
                             make_client(core->participant, "device_call", core->device_call)}) {
    if (!result) return result.error();
  }
  const auto qos = wire::reliable_qos(kCommandHistoryDepth);
  auto commands = wire::TopicWriter<ControlCommand>::create(core->participant, wire::kControlCommandTopic, qos.get());
  if (commands) {
    core->commands = Permitted(std::make_unique<wire::TopicWriter<ControlCommand>>(std::move(commands.value())));
  } else if (auto kept = keep_denial(commands.error(), core->commands); !kept) {
    return kept.error();
  }
  core->dispatcher = std::make_shared<Dispatcher>(core->participant);
  return core;
}

void ClientCore::await_command_subscriber(std::chrono::milliseconds timeout) const {
  const auto* writer = commands.get();
  if (writer == nullptr) return;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (writer->matched_readers() == 0 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

}  // namespace robotd::detail
