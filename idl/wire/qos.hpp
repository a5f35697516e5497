// QoS profiles, chosen to match ROS 2 defaults so rmw_cyclonedds nodes interoperate:
// reliable, volatile, keep-last; session status is transient-local so late joiners see who
// holds what. Every profile pins XCDR1, the only representation rmw_cyclonedds accepts.
#pragma once

#include <memory>

#include <dds/dds.h>

namespace robotd::wire {

struct QosDeleter {
  void operator()(dds_qos_t* qos) const { dds_delete_qos(qos); }
};
using QosPtr = std::unique_ptr<dds_qos_t, QosDeleter>;

QosPtr reliable_qos(int depth);         // ROS default profile: reliable, volatile, keep last `depth`
QosPtr transient_local_qos(int depth);  // reliable, transient local, keep last `depth`
QosPtr service_qos();                   // ROS services default: reliable, volatile, keep last 10

/// Requests a service server holds before it has taken them. Beyond that Cyclone stops taking
/// samples off the network (all of them, on that participant) until the server catches up: the
/// writers are held back by reliable flow control instead of losing requests.
inline constexpr int kPendingRequestsPerService = 4096;
/// A service server's request reader: reliable, volatile, keep all (up to
/// kPendingRequestsPerService), so a burst of requests is answered, not overwritten.
QosPtr service_request_reader_qos();

}  // namespace robotd::wire
