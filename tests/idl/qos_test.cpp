// robotd's QoS profiles: what rmw_cyclonedds uses for the same ROS profiles, XCDR1 pinned, and
// transient local really replaying `depth` samples to a late joiner.
#include "wire/qos.hpp"

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "robotd/messages.hpp"
#include "wire/participant.hpp"
#include "wire/topic_io.hpp"
#include "wire_test_support.hpp"

namespace robotd::wire {
namespace {

void expect_reliable_keep_last(const dds_qos_t* qos, int depth) {
  dds_reliability_kind_t reliability{};
  dds_duration_t max_blocking = 0;
  ASSERT_TRUE(dds_qget_reliability(qos, &reliability, &max_blocking));
  EXPECT_EQ(reliability, DDS_RELIABILITY_RELIABLE);
  dds_history_kind_t history{};
  int32_t history_depth = 0;
  ASSERT_TRUE(dds_qget_history(qos, &history, &history_depth));
  EXPECT_EQ(history, DDS_HISTORY_KEEP_LAST);
  EXPECT_EQ(history_depth, depth);
  uint32_t count = 0;
  dds_data_representation_id_t* representations = nullptr;
  ASSERT_TRUE(dds_qget_data_representation(qos, &count, &representations));
  ASSERT_EQ(count, 1u);
  EXPECT_EQ(representations[0], DDS_DATA_REPRESENTATION_XCDR1);
  dds_free(representations);
}

dds_durability_kind_t durability_of(const dds_qos_t* qos) {
  dds_durability_kind_t durability = DDS_DURABILITY_VOLATILE;
  dds_qget_durability(qos, &durability);
  return durability;
}

TEST(Qos, ReliableIsTheRosDefaultProfile) {
  const QosPtr qos = reliable_qos(10);
  expect_reliable_keep_last(qos.get(), 10);
  EXPECT_EQ(durability_of(qos.get()), DDS_DURABILITY_VOLATILE);
}

TEST(Qos, ServiceIsTheRosServicesProfile) {
  const QosPtr qos = service_qos();
  expect_reliable_keep_last(qos.get(), 10);
  EXPECT_EQ(durability_of(qos.get()), DDS_DURABILITY_VOLATILE);
}

TEST(Qos, AServersRequestReaderKeepsEveryRequestUpToItsPendingLimit) {
  const QosPtr qos = service_request_reader_qos();
  dds_reliability_kind_t reliability{};
  ASSERT_TRUE(dds_qget_reliability(qos.get(), &reliability, nullptr));
  EXPECT_EQ(reliability, DDS_RELIABILITY_RELIABLE);
  EXPECT_EQ(durability_of(qos.get()), DDS_DURABILITY_VOLATILE);
  dds_history_kind_t history{};
  ASSERT_TRUE(dds_qget_history(qos.get(), &history, nullptr));
  EXPECT_EQ(history, DDS_HISTORY_KEEP_ALL);
  int32_t max_samples = 0;
  ASSERT_TRUE(dds_qget_resource_limits(qos.get(), &max_samples, nullptr, nullptr));
  EXPECT_EQ(max_samples, kPendingRequestsPerService);
}

TEST(Qos, TransientLocalKeepsItsDepthForLateJoiners) {
  const QosPtr qos = transient_local_qos(3);
  expect_reliable_keep_last(qos.get(), 3);
  EXPECT_EQ(durability_of(qos.get()), DDS_DURABILITY_TRANSIENT_LOCAL);
  // Late joiners get the durability-service history, so it must hold `depth` samples too.
  dds_history_kind_t history{};
  int32_t depth = 0;
  ASSERT_TRUE(dds_qget_durability_service(qos.get(), nullptr, &history, &depth, nullptr, nullptr, nullptr));
  EXPECT_EQ(history, DDS_HISTORY_KEEP_LAST);
  EXPECT_EQ(depth, 3);
}

TEST(Qos, LateJoinerGetsTheLastDepthSamples) {
  const testing::PrivateDomain domain;
  auto participant = Participant::create(domain.settings());
  ASSERT_TRUE(participant) << participant.error().message;
  auto writer =
      TopicWriter<ResetZeroResponse>::create(participant.value(), "rt/late_joiner", transient_local_qos(3).get());
  ASSERT_TRUE(writer) << writer.error().message;
  for (const char* message : {"one", "two", "three", "four"}) {
    ASSERT_TRUE(writer.value().write(ResetZeroResponse{true, message}));
  }

  auto reader =
      TopicReader<ResetZeroResponse>::create(participant.value(), "rt/late_joiner", transient_local_qos(3).get());
  ASSERT_TRUE(reader) << reader.error().message;
  std::vector<std::string> received;
  testing::wait_until(
      [&] {
        reader.value().take_each(
            [&](ResetZeroResponse&& sample, const dds_sample_info_t&) { received.push_back(sample.message); });
        return received.size() >= 3;
      },
      std::chrono::seconds(2));
  EXPECT_EQ(received, (std::vector<std::string>{"two", "three", "four"}));
}

}  // namespace
}  // namespace robotd::wire
