#include "wire/qos.hpp"

namespace robotd::wire {
namespace {

QosPtr base_qos(int depth) {
  QosPtr qos(dds_create_qos());
  dds_qset_reliability(qos.get(), DDS_RELIABILITY_RELIABLE, DDS_MSECS(100));
  dds_qset_history(qos.get(), DDS_HISTORY_KEEP_LAST, depth);
  const dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
  dds_qset_data_representation(qos.get(), 1, &xcdr1);
  return qos;
}

}  // namespace

QosPtr reliable_qos(int depth) { return base_qos(depth); }

QosPtr transient_local_qos(int depth) {
  QosPtr qos = base_qos(depth);
  dds_qset_durability(qos.get(), DDS_DURABILITY_TRANSIENT_LOCAL);
  // What a late joiner gets is the durability-service history (Cyclone's default: the last
  // sample only), not the writer's history; rmw_cyclonedds sets both to the same depth.
  dds_qset_durability_service(qos.get(), 0, DDS_HISTORY_KEEP_LAST, depth, DDS_LENGTH_UNLIMITED, DDS_LENGTH_UNLIMITED,
                              DDS_LENGTH_UNLIMITED);
  return qos;
}

QosPtr service_qos() { return base_qos(10); }

QosPtr service_request_reader_qos() {
  QosPtr qos = base_qos(10);
  dds_qset_history(qos.get(), DDS_HISTORY_KEEP_ALL, 0);
  dds_qset_resource_limits(qos.get(), kPendingRequestsPerService, DDS_LENGTH_UNLIMITED, DDS_LENGTH_UNLIMITED);
  return qos;
}

}  // namespace robotd::wire
