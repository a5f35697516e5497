#include "dds/service_host.hpp"

#include <spdlog/spdlog.h>

namespace robotd::dds {
namespace {

constexpr std::size_t kMaxWorkers = 16;

template <class Server>
Result<void> make_server(const wire::Participant& participant, const char* name, Server& out) {
  auto server = std::remove_reference_t<decltype(*out)>::create(participant, name);
  if (!server) return server.error();
  out = std::move(server.value());
  return {};
}

}  // namespace

Result<std::unique_ptr<ServiceHost>> ServiceHost::create(const wire::Participant& participant,
                                                         service::SessionService& sessions,
                                                         service::DeviceServices& devices) {
  std::unique_ptr<ServiceHost> host(new ServiceHost(participant, sessions, devices));
  if (auto created = host->create_servers(); !created) return created.error();
  return host;
}

ServiceHost::ServiceHost(const wire::Participant& participant, service::SessionService& sessions,
                         service::DeviceServices& devices)
    : participant_(participant), sessions_(sessions), devices_(devices) {}

ServiceHost::~ServiceHost() { stop(); }

Result<void> ServiceHost::create_servers() {
  for (const auto& result :
       {make_server(participant_, "request_control", request_control_),
        make_server(participant_, "release_control", release_control_),
        make_server(participant_, "get_available_motors", get_available_motors_),
        make_server(participant_, "reset_zero", reset_zero_), make_server(participant_, "estop", estop_),
        make_server(participant_, "list_devices", list_devices_),
        make_server(participant_, "device_call", device_call_)}) {
    if (!result) return result;
  }
  waitset_ = wire::Entity(dds_create_waitset(participant_.handle()));
  for (dds_entity_t reader :
       {request_control_->request_reader(), release_control_->request_reader(), get_available_motors_->request_reader(),
        reset_zero_->request_reader(), estop_->request_reader(), list_devices_->request_reader(),
        device_call_->request_reader()}) {
    dds_waitset_attach(waitset_.get(), dds_create_readcondition(reader, DDS_ANY_STATE), 0);
  }
  stop_condition_ = dds_create_guardcondition(participant_.handle());
  dds_waitset_attach(waitset_.get(), stop_condition_, 0);
  return {};
}

void ServiceHost::start() {
  thread_ = std::thread([this] { run(); });
}

void ServiceHost::stop() {
  if (thread_.joinable()) {
    stopping_.store(true);
    dds_set_guardcondition(stop_condition_, true);
    thread_.join();
  }
  reap_workers(true);
}

template <class Req, class Resp, class Handler>
void ServiceHost::serve(wire::ServiceServer<Req, Resp>& server, Handler handler) {
  server.take_requests([&](const wire::RequestId& id, Req&& request) {
    const Resp response = handler(request);
    if (auto sent = server.reply(id, response); !sent) spdlog::warn("/{}: {}", server.name(), sent.error().message);
  });
}

template <class Req, class Resp, class Handler>
void ServiceHost::serve_on_worker(wire::ServiceServer<Req, Resp>& server, Handler handler) {
  server.take_requests([&](const wire::RequestId& id, Req&& request) {
    const std::lock_guard lock(workers_mutex_);
    if (workers_.size() >= kMaxWorkers) {
      Resp busy;
      busy.message = "robotd is busy with " + std::to_string(kMaxWorkers) + " long requests; retry shortly";
      (void)server.reply(id, busy);
      return;
    }
    auto done = std::make_shared<std::atomic<bool>>(false);
    workers_.push_back(Worker{std::thread([&server, handler, id, request = std::move(request), done] {
                                const Resp response = handler(request);
                                if (auto sent = server.reply(id, response); !sent) {
                                  spdlog::warn("/{}: {}", server.name(), sent.error().message);
                                }
                                done->store(true);
                              }),
                              done});
  });
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
  pthread_setname_np(pthread_self(), "services");
  while (!stopping_.load()) {
    dds_waitset_wait(waitset_.get(), nullptr, 0, DDS_MSECS(200));
    serve(*request_control_, [this](const RequestControlRequest& r) { return sessions_.request_control(r); });
    serve(*release_control_, [this](const ReleaseControlRequest& r) { return sessions_.release_control(r); });
    serve(*get_available_motors_, [this](const GetAvailableMotorsRequest& r) { return sessions_.available_motors(r); });
    serve(*estop_, [this](const EstopRequest& r) { return devices_.estop(r); });
    serve(*list_devices_, [this](const ListDevicesRequest& r) { return devices_.list_devices(r); });
    serve_on_worker(*reset_zero_, [this](const ResetZeroRequest& r) { return devices_.reset_zero(r); });
    serve_on_worker(*device_call_, [this](const DeviceCallRequest& r) { return devices_.device_call(r); });
    reap_workers(false);
  }
}

}  // namespace robotd::dds
