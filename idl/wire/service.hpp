// ROS 2 services over plain DDS, framed the rmw_cyclonedds way: requests on
// "rq/<name>Request", replies on "rr/<name>Reply", each sample starting with the 16-byte
// header (client_guid, sequence_number). The server echoes the header; the client keeps
// only replies carrying its own guid and sequence number.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>

#include "robotd/result.hpp"
#include "wire/qos.hpp"
#include "wire/topic_io.hpp"
#include "wire/topics.hpp"

namespace robotd::wire {

struct RequestId {
  std::uint64_t client_guid = 0;
  std::int64_t sequence_number = 0;
  dds_instance_handle_t publication = 0;  // the requesting writer, to find its reply reader
};

namespace detail {
/// Waits up to `timeout` for `reply_writer` to match a reader in the participant that owns
/// `request_publication` (seen by `request_reader`), so a reply is not written into the void.
void wait_for_reply_reader(dds_entity_t request_reader, dds_entity_t reply_writer,
                           dds_instance_handle_t request_publication, std::chrono::milliseconds timeout);
}  // namespace detail

template <class Request, class Response>
class ServiceServer {
 public:
  static Result<std::unique_ptr<ServiceServer>> create(const Participant& participant, std::string_view service) {
    auto request_qos = service_request_reader_qos();
    auto reply_qos = service_qos();
    auto request_topic_entity = create_topic<Request>(participant, request_topic(service));
    if (!request_topic_entity) return request_topic_entity.error();
    auto reply_topic_entity = create_topic<Response>(participant, reply_topic(service));
    if (!reply_topic_entity) return reply_topic_entity.error();
    const dds_entity_t reader =
        dds_create_reader(participant.handle(), request_topic_entity.value().get(), request_qos.get(), nullptr);
    if (reader < 0) return dds_failure("create a service request reader", request_topic(service), reader);
    const dds_entity_t writer =
        dds_create_writer(participant.handle(), reply_topic_entity.value().get(), reply_qos.get(), nullptr);
    if (writer < 0) return dds_failure("create a service reply writer", reply_topic(service), writer);
    return std::unique_ptr<ServiceServer>(
        new ServiceServer(std::string(service), std::move(request_topic_entity.value()),
                          std::move(reply_topic_entity.value()), Entity(reader), Entity(writer)));
  }

  const std::string& name() const { return name_; }
  dds_entity_t request_reader() const { return reader_.get(); }

  /// Takes every pending request and calls on_request(const RequestId&, Request&&).
  template <class OnRequest>
  void take_requests(OnRequest&& on_request) {
    constexpr int kBatch = 8;
    while (true) {
      std::array<void*, kBatch> samples{};
      std::array<dds_sample_info_t, kBatch> infos{};
      const dds_return_t count = dds_take(reader_.get(), samples.data(), infos.data(), kBatch, kBatch);
      if (count <= 0) return;
      for (int i = 0; i < count; ++i) {
        const auto index = static_cast<std::size_t>(i);
        if (!infos[index].valid_data) continue;
        const auto& c = *static_cast<const typename Wire<Request>::C*>(samples[index]);
        on_request(RequestId{c.client_guid, c.sequence_number, infos[index].publication_handle},
                   Wire<Request>::from_c(c));
      }
      dds_return_loan(reader_.get(), samples.data(), count);
      if (count < kBatch) return;
    }
  }

  /// Sends the reply to `id`. Safe to call from any thread.
  Result<void> reply(const RequestId& id, const Response& response) {
    detail::wait_for_reply_reader(reader_.get(), writer_.get(), id.publication, std::chrono::milliseconds(100));
    typename Wire<Response>::C sample{};
    CArena arena;
    Wire<Response>::to_c(response, sample, arena);
    sample.client_guid = id.client_guid;
    sample.sequence_number = id.sequence_number;
    const dds_return_t rc = dds_write(writer_.get(), &sample);
    if (rc < 0) return make_error(ErrorCode::kTransport, dds_error(("reply on " + name_).c_str(), rc));
    return {};
  }

 private:
  ServiceServer(std::string name, Entity request_topic, Entity reply_topic, Entity reader, Entity writer)
      : name_(std::move(name)),
        request_topic_(std::move(request_topic)),
        reply_topic_(std::move(reply_topic)),
        reader_(std::move(reader)),
        writer_(std::move(writer)) {}

  std::string name_;
  Entity request_topic_;
  Entity reply_topic_;
  Entity reader_;
  Entity writer_;
};

template <class Request, class Response>
class ServiceClient {
 public:
  static Result<std::unique_ptr<ServiceClient>> create(const Participant& participant, std::string_view service) {
    auto qos = service_qos();
    auto request_topic_entity = create_topic<Request>(participant, request_topic(service));
    if (!request_topic_entity) return request_topic_entity.error();
    auto reply_topic_entity = create_topic<Response>(participant, reply_topic(service));
    if (!reply_topic_entity) return reply_topic_entity.error();
    const dds_entity_t writer =
        dds_create_writer(participant.handle(), request_topic_entity.value().get(), qos.get(), nullptr);
    if (writer < 0) return dds_failure("create a service request writer", request_topic(service), writer);
    // Every client of the service reads the one reply topic. This reader stores only the replies
    // to this client, so other clients' replies never push its own out of its keep-last history.
    auto guid = std::make_unique<std::uint64_t>(0);
    dds_get_instance_handle(writer, guid.get());
    dds_set_topic_filter_and_arg(reply_topic_entity.value().get(), &is_reply_to, guid.get());
    const dds_entity_t reader =
        dds_create_reader(participant.handle(), reply_topic_entity.value().get(), qos.get(), nullptr);
    if (reader < 0) return dds_failure("create a service reply reader", reply_topic(service), reader);
    return std::unique_ptr<ServiceClient>(
        new ServiceClient(participant.handle(), std::string(service), std::move(request_topic_entity.value()),
                          std::move(reply_topic_entity.value()), Entity(writer), Entity(reader), std::move(guid)));
  }

  /// Sends `request` and waits for its reply. Never waits longer than `timeout` in total.
  Result<Response> call(const Request& request, std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    return call_until(request, deadline, deadline, timeout, timeout);
  }

  /// For slow operations: gives up after `discovery_timeout` if no robotd serves this service,
  /// else waits up to `reply_timeout` for the reply once the request is sent.
  Result<Response> call(const Request& request, std::chrono::milliseconds discovery_timeout,
                        std::chrono::milliseconds reply_timeout) {
    const auto now = std::chrono::steady_clock::now();
    return call_until(request, now + discovery_timeout, std::chrono::steady_clock::time_point::max(), discovery_timeout,
                      reply_timeout);
  }

 private:
  /// `reply_deadline` max() means: `reply_timeout` from when the request is sent.
  Result<Response> call_until(const Request& request, std::chrono::steady_clock::time_point match_deadline,
                              std::chrono::steady_clock::time_point reply_deadline,
                              std::chrono::milliseconds discovery_timeout, std::chrono::milliseconds reply_timeout) {
    const std::lock_guard lock(mutex_);
    if (!wait_until_matched(match_deadline)) {
      return make_error(ErrorCode::kNotAvailable, "no robotd answers /" + name_ + " on this DDS domain within " +
                                                      std::to_string(discovery_timeout.count()) +
                                                      " ms: is robotd running, with the same domain id and "
                                                      "network interface?");
    }
    typename Wire<Request>::C sample{};
    CArena arena;
    Wire<Request>::to_c(request, sample, arena);
    sample.client_guid = *guid_;
    sample.sequence_number = ++sequence_;
    const dds_return_t rc = dds_write(writer_.get(), &sample);
    if (rc < 0) return make_error(ErrorCode::kTransport, dds_error(("send a /" + name_ + " request").c_str(), rc));
    if (reply_deadline == std::chrono::steady_clock::time_point::max()) {
      reply_deadline = std::chrono::steady_clock::now() + reply_timeout;
    }
    return wait_for_reply(sample.sequence_number, reply_deadline, reply_timeout);
  }

  ServiceClient(dds_entity_t participant, std::string name, Entity request_topic, Entity reply_topic, Entity writer,
                Entity reader, std::unique_ptr<std::uint64_t> guid)
      : guid_(std::move(guid)),
        name_(std::move(name)),
        request_topic_(std::move(request_topic)),
        reply_topic_(std::move(reply_topic)),
        writer_(std::move(writer)),
        reader_(std::move(reader)),
        waitset_(dds_create_waitset(participant)) {
    condition_ = dds_create_readcondition(reader_.get(), DDS_ANY_STATE);
    dds_waitset_attach(waitset_.get(), condition_, 0);
  }

  static bool is_reply_to(const void* sample, void* guid) {
    return static_cast<const typename Wire<Response>::C*>(sample)->client_guid == *static_cast<std::uint64_t*>(guid);
  }

  bool wait_until_matched(std::chrono::steady_clock::time_point deadline) const {
    while (true) {
      dds_publication_matched_status_t writer_status{};
      dds_subscription_matched_status_t reader_status{};
      dds_get_publication_matched_status(writer_.get(), &writer_status);
      dds_get_subscription_matched_status(reader_.get(), &reader_status);
      if (writer_status.current_count > 0 && reader_status.current_count > 0) return true;
      if (std::chrono::steady_clock::now() >= deadline) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  }

  Result<Response> wait_for_reply(std::int64_t sequence, std::chrono::steady_clock::time_point deadline,
                                  std::chrono::milliseconds timeout) {
    while (true) {
      std::array<void*, 4> samples{};
      std::array<dds_sample_info_t, 4> infos{};
      const dds_return_t count = dds_take(reader_.get(), samples.data(), infos.data(), 4, 4);
      for (int i = 0; i < count; ++i) {
        const auto index = static_cast<std::size_t>(i);
        const auto& c = *static_cast<const typename Wire<Response>::C*>(samples[index]);
        if (infos[index].valid_data && c.client_guid == *guid_ && c.sequence_number == sequence) {
          Response response = Wire<Response>::from_c(c);
          dds_return_loan(reader_.get(), samples.data(), count);
          return response;
        }
      }
      if (count > 0) {
        dds_return_loan(reader_.get(), samples.data(), count);
        continue;
      }
      const auto now = std::chrono::steady_clock::now();
      if (now >= deadline) {
        return make_error(ErrorCode::kTimeout,
                          "robotd did not answer /" + name_ + " within " + std::to_string(timeout.count()) + " ms");
      }
      const auto left = std::chrono::duration_cast<std::chrono::nanoseconds>(deadline - now).count();
      dds_waitset_wait(waitset_.get(), nullptr, 0, left);
    }
  }

  // On the heap, and declared before the entities so that it outlives them: the reply topic's
  // filter holds its address.
  std::unique_ptr<std::uint64_t> guid_;
  std::mutex mutex_;
  std::string name_;
  Entity request_topic_;
  Entity reply_topic_;
  Entity writer_;
  Entity reader_;
  Entity waitset_;
  dds_entity_t condition_ = 0;
  std::int64_t sequence_ = 0;
};

}  // namespace robotd::wire
