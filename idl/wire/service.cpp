#include "wire/service.hpp"

#include <vector>

namespace robotd::wire {
namespace detail {
namespace {

bool participant_of_publication(dds_entity_t reader, dds_instance_handle_t publication, dds_guid_t& participant) {
  dds_builtintopic_endpoint_t* endpoint = dds_get_matched_publication_data(reader, publication);
  if (endpoint == nullptr) return false;
  participant = endpoint->participant_key;
  dds_builtintopic_free_endpoint(endpoint);
  return true;
}

bool writer_reaches(dds_entity_t writer, const dds_guid_t& participant) {
  std::vector<dds_instance_handle_t> handles(64);
  dds_return_t count = dds_get_matched_subscriptions(writer, handles.data(), handles.size());
  if (count > static_cast<dds_return_t>(handles.size())) {  // more clients than fit: fetch them all
    handles.resize(static_cast<std::size_t>(count));
    count = dds_get_matched_subscriptions(writer, handles.data(), handles.size());
  }
  for (dds_return_t i = 0; i < count && static_cast<std::size_t>(i) < handles.size(); ++i) {
    dds_builtintopic_endpoint_t* endpoint =
        dds_get_matched_subscription_data(writer, handles[static_cast<std::size_t>(i)]);
    if (endpoint == nullptr) continue;
    const bool same = std::equal(std::begin(endpoint->participant_key.v), std::end(endpoint->participant_key.v),
                                 std::begin(participant.v));
    dds_builtintopic_free_endpoint(endpoint);
    if (same) return true;
  }
  return false;
}

}  // namespace

void wait_for_reply_reader(dds_entity_t request_reader, dds_entity_t reply_writer,
                           dds_instance_handle_t request_publication, std::chrono::milliseconds timeout) {
  dds_guid_t participant{};
  if (!participant_of_publication(request_reader, request_publication, participant)) return;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!writer_reaches(reply_writer, participant) && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

}  // namespace detail
}  // namespace robotd::wire
