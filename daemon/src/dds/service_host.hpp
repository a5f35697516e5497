// Serves robotd's DDS services (/request_control, /release_control, /get_available_motors,
// /reset_zero, /estop, /list_devices, /device_call). One thread waits on every request
// reader; requests that can take long (reset_zero, device_call) run on their own worker
// thread so they never hold up the others.
#pragma once

#include <atomic>
#include <list>
#include <memory>
#include <mutex>
#include <thread>

#include "service/device_services.hpp"
#include "service/session_service.hpp"
#include "wire/service.hpp"

namespace robotd::dds {

class ServiceHost {
 public:
  static Result<std::unique_ptr<ServiceHost>> create(const wire::Participant& participant,
                                                     service::SessionService& sessions,
                                                     service::DeviceServices& devices);
  ServiceHost(const ServiceHost&) = delete;
  ServiceHost& operator=(const ServiceHost&) = delete;
  ~ServiceHost();

  void start();
  void stop();

 private:
  template <class Req, class Resp>
  using Server = std::unique_ptr<wire::ServiceServer<Req, Resp>>;

  ServiceHost(const wire::Participant& participant, service::SessionService& sessions,
              service::DeviceServices& devices);
  Result<void> create_servers();
  void run();
  template <class Req, class Resp, class Handler>
  void serve(wire::ServiceServer<Req, Resp>& server, Handler handler);
  template <class Req, class Resp, class Handler>
  void serve_on_worker(wire::ServiceServer<Req, Resp>& server, Handler handler);
  void reap_workers(bool all);

  const wire::Participant& participant_;
  service::SessionService& sessions_;
  service::DeviceServices& devices_;

  Server<RequestControlRequest, RequestControlResponse> request_control_;
  Server<ReleaseControlRequest, ReleaseControlResponse> release_control_;
  Server<GetAvailableMotorsRequest, GetAvailableMotorsResponse> get_available_motors_;
  Server<ResetZeroRequest, ResetZeroResponse> reset_zero_;
  Server<EstopRequest, EstopResponse> estop_;
  Server<ListDevicesRequest, ListDevicesResponse> list_devices_;
  Server<DeviceCallRequest, DeviceCallResponse> device_call_;

  wire::Entity waitset_;
  dds_entity_t stop_condition_ = 0;
  std::atomic<bool> stopping_{false};
  std::thread thread_;

  struct Worker {
    std::thread thread;
    std::shared_ptr<std::atomic<bool>> done;
  };
  std::mutex workers_mutex_;
  std::list<Worker> workers_;
};

}  // namespace robotd::dds
