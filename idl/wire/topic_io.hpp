// Typed DDS writers and readers over robotd's C++ messages.
#pragma once

#include <array>
#include <string>
#include <string_view>

#include "robotd/result.hpp"
#include "wire/entity.hpp"
#include "wire/participant.hpp"
#include "wire/wire_types.hpp"

namespace robotd::wire {

/// Creates the topic `name` carrying T on `participant`.
template <class T>
Result<Entity> create_topic(const Participant& participant, std::string_view name) {
  const std::string topic_name(name);
  const dds_entity_t topic =
      dds_create_topic(participant.handle(), &Wire<T>::descriptor(), topic_name.c_str(), nullptr, nullptr);
  if (topic < 0) return dds_failure("create a DDS topic", topic_name, topic);
  return Entity(topic);
}

template <class T>
class TopicWriter {
 public:
  static Result<TopicWriter> create(const Participant& participant, std::string_view name, const dds_qos_t* qos) {
    auto topic = create_topic<T>(participant, name);
    if (!topic) return topic.error();
    const dds_entity_t writer = dds_create_writer(participant.handle(), topic.value().get(), qos, nullptr);
    if (writer < 0) return dds_failure("create a DDS writer", name, writer);
    return TopicWriter(std::move(topic.value()), Entity(writer));
  }

  Result<void> write(const T& value) const {
    typename Wire<T>::C sample{};
    CArena arena;
    Wire<T>::to_c(value, sample, arena);
    const dds_return_t rc = dds_write(writer_.get(), &sample);
    if (rc < 0) return make_error(ErrorCode::kTransport, dds_error("write a DDS sample", rc));
    return {};
  }

  int matched_readers() const {
    dds_publication_matched_status_t status{};
    dds_get_publication_matched_status(writer_.get(), &status);
    return static_cast<int>(status.current_count);
  }

  /// Blocks until every matched reliable reader has acknowledged what was written.
  void wait_for_acks(dds_duration_t timeout) const { dds_wait_for_acks(writer_.get(), timeout); }

  dds_entity_t handle() const { return writer_.get(); }

 private:
  TopicWriter(Entity topic, Entity writer) : topic_(std::move(topic)), writer_(std::move(writer)) {}
  Entity topic_;
  Entity writer_;
};

template <class T>
class TopicReader {
 public:
  /// With `filter`, Cyclone calls it for each arriving sample on its receive thread; a sample it
  /// refuses is acknowledged and dropped before it takes a place in the reader's history.
  static Result<TopicReader> create(const Participant& participant, std::string_view name, const dds_qos_t* qos,
                                    const dds_topic_filter* filter = nullptr) {
    auto topic = create_topic<T>(participant, name);
    if (!topic) return topic.error();
    // The topic entity is this reader's own, so the filter is set before the reader exists.
    if (filter != nullptr) {
      if (const dds_return_t rc = dds_set_topic_filter_extended(topic.value().get(), filter); rc < 0) {
        return dds_failure("set a DDS topic filter", name, rc);
      }
    }
    const dds_entity_t reader = dds_create_reader(participant.handle(), topic.value().get(), qos, nullptr);
    if (reader < 0) return dds_failure("create a DDS reader", name, reader);
    return TopicReader(std::move(topic.value()), Entity(reader));
  }

  /// Takes every available sample and calls on_sample(T&&, const dds_sample_info_t&) for each
  /// one carrying data. Returns how many were delivered.
  template <class OnSample>
  std::size_t take_each(OnSample&& on_sample) const {
    constexpr int kBatch = 16;
    std::size_t delivered = 0;
    while (true) {
      std::array<void*, kBatch> samples{};
      std::array<dds_sample_info_t, kBatch> infos{};
      const dds_return_t count = dds_take(reader_.get(), samples.data(), infos.data(), kBatch, kBatch);
      if (count <= 0) return delivered;
      for (int i = 0; i < count; ++i) {
        const auto index = static_cast<std::size_t>(i);
        if (!infos[index].valid_data) continue;
        on_sample(Wire<T>::from_c(*static_cast<const typename Wire<T>::C*>(samples[index])), infos[index]);
        ++delivered;
      }
      dds_return_loan(reader_.get(), samples.data(), count);
      if (count < kBatch) return delivered;
    }
  }

  int matched_writers() const {
    dds_subscription_matched_status_t status{};
    dds_get_subscription_matched_status(reader_.get(), &status);
    return static_cast<int>(status.current_count);
  }

  dds_entity_t handle() const { return reader_.get(); }

 private:
  TopicReader(Entity topic, Entity reader) : topic_(std::move(topic)), reader_(std::move(reader)) {}
  Entity topic_;
  Entity reader_;
};

}  // namespace robotd::wire
