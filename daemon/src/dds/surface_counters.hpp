// What robotd's DDS surface saw that no device's CommandCounters can hold: commands that name
// no active session and no known device, each service's requests and refusals, and the DDS
// layer's own messages. Bumped by the intake, service and DDS receive threads; published in
// SessionStatus.surface.
#pragma once

#include <atomic>
#include <cstdint>
#include <deque>
#include <string>

#include "robotd/messages.hpp"

namespace robotd::dds {

struct ServiceCounterSet {
  explicit ServiceCounterSet(std::string service_name) : service(std::move(service_name)) {}

  const std::string service;
  std::atomic<std::uint64_t> requests{0};
  std::atomic<std::uint64_t> refused{0};    // every reply with success = false
  std::atomic<std::uint64_t> oversized{0};  // a field beyond its limit (refused, or an e-stop's words cut)
};

class SurfaceCounterSet {
 public:
  /// The counters of one service; call before the service threads start.
  ServiceCounterSet& add_service(const std::string& name) { return services_.emplace_back(name); }

  std::atomic<std::uint64_t> commands_unattributed{0};
  std::atomic<std::uint64_t> dds_log_messages{0};

  SurfaceCounters snapshot() const {
    SurfaceCounters out;
    out.commands_unattributed = commands_unattributed.load(std::memory_order_relaxed);
    out.dds_log_messages = dds_log_messages.load(std::memory_order_relaxed);
    for (const auto& service : services_) {
      out.services.push_back(ServiceCounters{service.service, service.requests.load(std::memory_order_relaxed),
                                             service.refused.load(std::memory_order_relaxed),
                                             service.oversized.load(std::memory_order_relaxed)});
    }
    return out;
  }

 private:
  std::deque<ServiceCounterSet> services_;  // a deque keeps each set where it is as more are added
};

}  // namespace robotd::dds
