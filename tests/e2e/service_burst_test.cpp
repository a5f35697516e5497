// A burst of service requests from one client with ROS 2's default service QoS (a reliable,
// volatile, keep-last-10 request writer): robotd answers every one of them
// (docs/dds-interface.md, "Bursts of requests"). The client is the Cyclone C API, as under
// rmw_cyclonedds: it writes its requests back to back without waiting for a reply.
#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <set>
#include <thread>

#include <dds/dds.h>
#include <gtest/gtest.h>

#include "robotd_fixture.hpp"
#include "robotd_msgs.h"
#include "wire/entity.hpp"
#include "wire/participant.hpp"
#include "wire/qos.hpp"
#include "wire/topics.hpp"

namespace robotd::testing {
namespace {

using namespace std::chrono_literals;

constexpr std::size_t kBurst = 1000;
constexpr std::uint64_t kGuid = 0x5eed;

// A raw /request_control client: the request writer as rmw_cyclonedds makes it; the reply reader
// keeps every reply, so that what the test counts is what robotd answered.
class RawRequestControlClient {
 public:
  explicit RawRequestControlClient(int domain) {
    wire::DdsSettings settings;
    settings.domain_id = domain;
    auto created = wire::Participant::create(settings);
    EXPECT_TRUE(created) << created.error().message;
    participant_.emplace(std::move(created.value()));
    const dds_entity_t p = participant_->handle();
    request_topic_ = wire::Entity(dds_create_topic(p, &robotd_msgs_srv_dds__RequestControl_Request__desc,
                                                   wire::request_topic("request_control").c_str(), nullptr, nullptr));
    reply_topic_ = wire::Entity(dds_create_topic(p, &robotd_msgs_srv_dds__RequestControl_Response__desc,
                                                 wire::reply_topic("request_control").c_str(), nullptr, nullptr));
    const auto writer_qos = wire::service_qos();  // reliable, volatile, keep last 10
    writer_ = wire::Entity(dds_create_writer(p, request_topic_.get(), writer_qos.get(), nullptr));
    const auto reader_qos = wire::service_qos();
    dds_qset_history(reader_qos.get(), DDS_HISTORY_KEEP_ALL, 0);
    reader_ = wire::Entity(dds_create_reader(p, reply_topic_.get(), reader_qos.get(), nullptr));
  }

  bool wait_matched(std::chrono::milliseconds timeout) const {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
      dds_publication_matched_status_t writer_status{};
      dds_subscription_matched_status_t reader_status{};
      dds_get_publication_matched_status(writer_.get(), &writer_status);
      dds_get_subscription_matched_status(reader_.get(), &reader_status);
      if (writer_status.current_count > 0 && reader_status.current_count > 0) return true;
      std::this_thread::sleep_for(5ms);
    }
    return false;
  }

  /// A request robotd refuses (motor 99 does not exist), so the burst changes nothing.
  bool send(std::int64_t sequence) const {
    std::int32_t no_such_motor = 99;
    robotd_msgs_srv_dds__RequestControl_Request_ request{};
    request.client_guid = kGuid;
    request.sequence_number = sequence;
    request.node_name = const_cast<char*>("burst");
    request.device = const_cast<char*>("arm");
    request.motor_ids._length = request.motor_ids._maximum = 1;
    request.motor_ids._buffer = &no_such_motor;
    request.timeout_ms = 1000;
    return dds_write(writer_.get(), &request) == DDS_RETCODE_OK;
  }

  /// Takes replies until `count` distinct sequence numbers have been answered or `timeout` passes.
  std::set<std::int64_t> take_replies(std::size_t count, std::chrono::milliseconds timeout) const {
    std::set<std::int64_t> answered;
    const wire::Entity waitset(dds_create_waitset(participant_->handle()));
    dds_waitset_attach(waitset.get(), dds_create_readcondition(reader_.get(), DDS_ANY_STATE), 0);
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (answered.size() < count && std::chrono::steady_clock::now() < deadline) {
      std::array<void*, 64> samples{};
      std::array<dds_sample_info_t, 64> infos{};
      const dds_return_t n = dds_take(reader_.get(), samples.data(), infos.data(), samples.size(), samples.size());
      for (dds_return_t i = 0; i < n; ++i) {
        const auto index = static_cast<std::size_t>(i);
        const auto& reply = *static_cast<const robotd_msgs_srv_dds__RequestControl_Response_*>(samples[index]);
        if (infos[index].valid_data && reply.client_guid == kGuid) answered.insert(reply.sequence_number);
      }
      if (n > 0) {
        dds_return_loan(reader_.get(), samples.data(), n);
      } else {
        dds_waitset_wait(waitset.get(), nullptr, 0, DDS_MSECS(100));
      }
    }
    return answered;
  }

 private:
  std::optional<wire::Participant> participant_;
  wire::Entity request_topic_;
  wire::Entity reply_topic_;
  wire::Entity writer_;
  wire::Entity reader_;
};

class ServiceBurstTest : public RobotdTest {};

TEST_F(ServiceBurstTest, EveryRequestOfABackToBackBurstIsAnswered) {
  start_robotd();
  RawRequestControlClient raw(domain_.id());
  ASSERT_TRUE(raw.wait_matched(10s));
  // The first reply tells that robotd's reader has matched this writer too (discovery is not
  // symmetric in time): requests written before that survive only as far as the writer's own
  // keep-last-10 history reaches.
  ASSERT_TRUE(raw.send(0));
  ASSERT_EQ(raw.take_replies(1, 10s).size(), 1U) << "no reply to the first request";

  const auto t0 = std::chrono::steady_clock::now();
  for (std::int64_t sequence = 1; sequence <= static_cast<std::int64_t>(kBurst); ++sequence) {
    ASSERT_TRUE(raw.send(sequence));
  }
  const auto written = std::chrono::steady_clock::now();
  const std::set<std::int64_t> answered = raw.take_replies(kBurst, 30s);
  const auto done = std::chrono::steady_clock::now();
  std::printf(
      "[ measured ] %zu requests written back to back in %.1f ms; %zu answered, the last %.1f ms after the "
      "first was written\n",
      kBurst, std::chrono::duration<double, std::milli>(written - t0).count(), answered.size(),
      std::chrono::duration<double, std::milli>(done - t0).count());
  EXPECT_EQ(answered.size(), kBurst);
  if (!answered.empty()) {
    EXPECT_EQ(*answered.begin(), 1);
    EXPECT_EQ(*answered.rbegin(), static_cast<std::int64_t>(kBurst));
  }
  // robotd's own count: every request of the burst taken (and refused: motor 99), none more.
  auto status = client().session_status(3s);
  for (int i = 0; i < 50 && status && status.value().surface.services.at(0).requests < kBurst + 1; ++i) {
    std::this_thread::sleep_for(50ms);
    status = client().session_status(3s);
  }
  ASSERT_TRUE(status);
  const ServiceCounters& request_control = status.value().surface.services.at(0);
  EXPECT_EQ(request_control.service, "request_control");
  EXPECT_EQ(request_control.requests, kBurst + 1);
  EXPECT_EQ(request_control.refused, kBurst + 1);
}

// Every client of a service reads every reply on its one reply topic. Many clients calling at
// once must still each get their own reply, however many others' replies arrive meanwhile.
TEST_F(ServiceBurstTest, SixteenClientsCallingAtOnceEachGetEveryReply) {
  start_robotd();
  constexpr int kClients = 16;
  constexpr int kCalls = 300;
  std::vector<Client> clients;
  clients.reserve(kClients);
  for (int c = 0; c < kClients; ++c) clients.push_back(make_client("caller_" + std::to_string(c)));
  for (auto& client : clients) ASSERT_TRUE(client.available_motors("arm"));  // every one connected

  std::atomic<int> answered{0};
  std::atomic<int> failed{0};
  std::vector<std::thread> callers;
  callers.reserve(kClients);
  const auto t0 = std::chrono::steady_clock::now();
  for (auto& client : clients) {
    callers.emplace_back([&client, &answered, &failed] {
      for (int call = 0; call < kCalls; ++call) {
        if (client.available_motors("arm")) {
          ++answered;
        } else {
          ++failed;
        }
      }
    });
  }
  for (auto& caller : callers) caller.join();
  std::printf("[ measured ] %d clients x %d calls at once: %d answered, %d failed, in %.0f ms\n", kClients, kCalls,
              answered.load(), failed.load(),
              std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  EXPECT_EQ(answered.load(), kClients * kCalls);
  EXPECT_EQ(failed.load(), 0);
}

}  // namespace
}  // namespace robotd::testing
