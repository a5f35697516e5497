#include "dds/service_host.hpp"

#include "dds/field_limits.hpp"

namespace robotd::dds {
namespace {

constexpr std::size_t kMaxWorkers = 16;

// A refusal with `message`; a service without success and message (list_devices) refuses with
// its empty reply.
template <class Resp>
Resp refusal(const std::string& message) {
  Resp response{};
  if constexpr (requires { response.message; }) {
    response.success = false;
    response.message = message;
  }
  return response;
}

template <class Resp>
bool is_refusal(const Resp& response) {
  if constexpr (requires { response.success; }) {
    return !response.success;
  } else {
    return false;
  }
}

}  // namespace

Result<std::unique_ptr<ServiceHost>> ServiceHost::create(const wire::Participant& participant,
                                                         service::SessionService& sessions,
                                                         service::DeviceServices& devices,
                                                         SurfaceCounterSet& counters) {
  std::unique_ptr<ServiceHost> host(new ServiceHost(participant, sessions, devices));
  if (auto created = host->create_servers(counters); !created) return created.error();
  return host;
}

ServiceHost::ServiceHost(const wire::Participant& participant, service::SessionService& sessions,
                         service::DeviceServices& devices)
    : participant_(participant), sessions_(sessions), devices_(devices) {}

ServiceHost::~ServiceHost() { stop(); }

Result<void> ServiceHost::create_servers(SurfaceCounterSet& counters) {
  const auto make = [&](const char* name, auto& service) -> Result<void> {
    using Server = std::remove_reference_t<decltype(*service.server)>;
    auto server = Server::create(participant_, name);
    if (!server) return server.error();
    service.server = std::move(server.value());
    service.counters = &counters.add_service(name);
    return {};
  };
  for (const auto& result :
       {make("request_control", request_control_), make("release_control", release_control_),
        make("get_available_motors", get_available_motors_), make("reset_zero", reset_zero_), make("estop", estop_),
        make("list_devices", list_devices_), make("device_call", device_call_)}) {
    if (!result) return result;
  }
  waitset_ = wire::Entity(dds_create_waitset(participant_.handle()));
  for (dds_entity_t reader : {request_control_.server->request_reader(), release_control_.server->request_reader(),
                              get_available_motors_.server->request_reader(), reset_zero_.server->request_reader(),
                              estop_.server->request_reader(), list_devices_.server->request_reader(),
                              device_call_.server->request_reader()}) {
    dds_waitset_attach(waitset_.get(), dds_create_readcondition(reader, DDS_ANY_STATE), 0);
  }
  stop_condition_ = dds_create_guardcondition(participant_.handle());
  dds_waitset_attach(waitset_.get(), stop_condition_, 0);
  return {};
}

void ServiceHost::start() {
  thread_ = driver::NamedThread("services", [this] { run(); });
}

void ServiceHost::stop() {
  if (thread_.joinable()) {
    stopping_.store(true);
    dds_set_guardcondition(stop_condition_, true);
    thread_.join();
  }
  reap_workers(true);
}

template <class Req, class Resp>
std::optional<Resp> ServiceHost::refuse_oversized(const Service<Req, Resp>& service, const Req& request) {
  const std::optional<Oversize> oversize = find_oversize(request);
  if (!oversize) return std::nullopt;
  service.counters->oversized.fetch_add(1, std::memory_order_relaxed);
  const std::string& name = service.server->name();
  log_.warn(name + "/oversized", "/" + name + " refused a request: " + oversize->describe());
  return refusal<Resp>(oversize->describe());
}

template <class Req, class Resp>
void ServiceHost::reply(const Service<Req, Resp>& service, const wire::RequestId& id, const Resp& response,
                        bool refused) {
  if (refused) service.counters->refused.fetch_add(1, std::memory_order_relaxed);
  if (auto sent = service.server->reply(id, response); !sent) {
    const std::string& name = service.server->name();
    log_.warn(name + "/reply", "/" + name + ": " + sent.error().message);
  }
}

template <class Req, class Resp, class Handler>
void ServiceHost::serve(Service<Req, Resp>& service, Handler handler) {
  service.server->take_requests([&](const wire::RequestId& id, Req&& request) {
    service.counters->requests.fetch_add(1, std::memory_order_relaxed);
    if (auto refused = refuse_oversized(service, request)) {
      reply(service, id, *refused, true);
      return;
    }
    const Resp response = handler(request);
    reply(service, id, response, is_refusal(response));
  });
}

template <class Req, class Resp, class Handler>
void ServiceHost::serve_on_worker(Service<Req, Resp>& service, Handler handler) {
  service.server->take_requests([&](const wire::RequestId& id, Req&& request) {
    service.counters->requests.fetch_add(1, std::memory_order_relaxed);
    if (auto refused = refuse_oversized(service, request)) {
      reply(service, id, *refused, true);
      return;
    }
    const std::lock_guard lock(workers_mutex_);
    if (workers_.size() >= kMaxWorkers) {
      reply(service, id,
            refusal<Resp>("robotd is busy with " + std::to_string(kMaxWorkers) + " long requests; retry shortly"),
            true);
      return;
    }
    auto done = std::make_shared<std::atomic<bool>>(false);
    workers_.push_back(Worker{driver::NamedThread("service-call",
                                                  [this, &service, handler, id, request = std::move(request), done] {
                                                    const Resp response = handler(request);
                                                    reply(service, id, response, is_refusal(response));
                                                    done->store(true);
                                                  }),
                              done});
  });
}

EstopResponse ServiceHost::estop(EstopRequest& request) {
  // An e-stop is never refused for its words: an over-long node_name or reason is cut to its limit.
  const std::optional<Oversize> cut = cut_to_limits(request);
  if (cut) {
    estop_.counters->oversized.fetch_add(1, std::memory_order_relaxed);
    log_.warn("estop/oversized", "/estop: " + cut->describe() + "; cut to the limit");
  }
  EstopResponse response = devices_.estop(request);
  if (cut) response.message += " (" + cut->describe() + "; cut to the limit)";
  return response;
}

void ServiceHost::reap_workers(bool all) {
  const std::lock_guard lock(workers_mutex_);
  for (auto it = workers_.begin(); it != workers_.end();) {
    if (all || it->done->load()) {
      it->thread.join();
      it = workers_.erase(it);
    } else {
      ++it;
    }
  }
}

void ServiceHost::run() {
  while (!stopping_.load()) {
    dds_waitset_wait(waitset_.get(), nullptr, 0, DDS_MSECS(200));
    serve(request_control_, [this](const RequestControlRequest& r) { return sessions_.request_control(r); });
    serve(release_control_, [this](const ReleaseControlRequest& r) { return sessions_.release_control(r); });
    serve(get_available_motors_, [this](const GetAvailableMotorsRequest& r) { return sessions_.available_motors(r); });
    serve(estop_, [this](EstopRequest& r) { return estop(r); });
    serve(list_devices_, [this](const ListDevicesRequest& r) { return devices_.list_devices(r); });
    serve_on_worker(reset_zero_, [this](const ResetZeroRequest& r) { return devices_.reset_zero(r); });
    serve_on_worker(device_call_, [this](const DeviceCallRequest& r) { return devices_.device_call(r); });
    reap_workers(false);
  }
}

}  // namespace robotd::dds
