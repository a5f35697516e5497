// What a PolicyDataPublisher holds: its DDS writer, and the client core that owns the participant.
#pragma once

#include <memory>

#include "client_core.hpp"
#include "robotd/client/policy_data_publisher.hpp"
#include "wire/topic_io.hpp"

namespace robotd {

struct PolicyDataPublisher::Impl {
  std::shared_ptr<detail::ClientCore> core;  // declared first: the writer goes before the participant
  wire::TopicWriter<PolicyData> writer;
};

}  // namespace robotd
