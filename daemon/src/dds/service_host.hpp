// Serves robotd's DDS services (/request_control, /release_control, /get_available_motors,
// /reset_zero, /estop, /list_devices, /device_call). One thread waits on every request
// reader; requests that can take long (reset_zero, device_call) run on their own worker
// thread so they never hold up the others. Every request is held to the field limits
// (field_limits.hpp) before its handler sees it, and counted per service.
#pragma once

#include <atomic>
#include <list>
#include <memory>
#include <mutex>

#include "app/throttled_log.hpp"
#include "dds/surface_counters.hpp"
#include "robotd/driver/named_thread.hpp"
#include "service/device_services.hpp"
#include "service/session_service.hpp"
#include "wire/service.hpp"

namespace robotd::dds {

class ServiceHost {
 public:
  static Result<std::unique_ptr<ServiceHost>> create(const wire::Participant& participant,
                                                     service::SessionService& sessions,
                                                     service::DeviceServices& devices, SurfaceCounterSet& counters);
  ServiceHost(const ServiceHost&) = delete;
  ServiceHost& operator=(const ServiceHost&) = delete;
  ~ServiceHost();

  void start();
  void stop();

 private:
  template <class Req, class Resp>
  struct Service {
    std::unique_ptr<wire::ServiceServer<Req, Resp>> server;
    ServiceCounterSet* counters = nullptr;
  };

  ServiceHost(const wire::Participant& participant, service::SessionService& sessions,
              service::DeviceServices& devices);
  Result<void> create_servers(SurfaceCounterSet& counters);
  void run();
  /// The refusal for a request with a field beyond its limit, counted and logged; nullopt if none.
  template <class Req, class Resp>
  std::optional<Resp> refuse_oversized(const Service<Req, Resp>& service, const Req& request);
  template <class Req, class Resp>
  void reply(const Service<Req, Resp>& service, const wire::RequestId& id, const Resp& response, bool refused);
  template <class Req, class Resp, class Handler>
  void serve(Service<Req, Resp>& service, Handler handler);
  template <class Req, class Resp, class Handler>
  void serve_on_worker(Service<Req, Resp>& service, Handler handler);
  EstopResponse estop(EstopRequest& request);
  void reap_workers(bool all);

  const wire::Participant& participant_;
  service::SessionService& sessions_;
  service::DeviceServices& devices_;

  Service<RequestControlRequest, RequestControlResponse> request_control_;
  Service<ReleaseControlRequest, ReleaseControlResponse> release_control_;
  Service<GetAvailableMotorsRequest, GetAvailableMotorsResponse> get_available_motors_;
  Service<ResetZeroRequest, ResetZeroResponse> reset_zero_;
  Service<EstopRequest, EstopResponse> estop_;
  Service<ListDevicesRequest, ListDevicesResponse> list_devices_;
  Service<DeviceCallRequest, DeviceCallResponse> device_call_;

  wire::Entity waitset_;
  dds_entity_t stop_condition_ = 0;
  std::atomic<bool> stopping_{false};
  driver::NamedThread thread_;
  app::ThrottledLog log_;

  struct Worker {
    driver::NamedThread thread;
    std::shared_ptr<std::atomic<bool>> done;
  };
  std::mutex workers_mutex_;
  std::list<Worker> workers_;
};

}  // namespace robotd::dds
