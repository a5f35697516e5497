// Publishes a policy's data stream on /policy_data (robotd_msgs/PolicyData), the PI Plus
// "policy / data stream" interface: what the policy observes and outputs, one data_type per
// sample. robotd only makes it visible (robotctl echo / record policy_data); it controls nothing.
//
//   auto publisher = client.policy_data_publisher();
//   publisher.value().publish("action", {0.1, -0.2, 0.3});
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "robotd/messages.hpp"
#include "robotd/result.hpp"

namespace robotd {

class PolicyDataPublisher {
 public:
  PolicyDataPublisher(PolicyDataPublisher&&) noexcept;
  PolicyDataPublisher& operator=(PolicyDataPublisher&&) noexcept;
  PolicyDataPublisher(const PolicyDataPublisher&) = delete;
  PolicyDataPublisher& operator=(const PolicyDataPublisher&) = delete;
  ~PolicyDataPublisher();

  /// Publishes `data`; a zero header.stamp is set to now (CLOCK_REALTIME).
  Result<void> publish(const PolicyData& data);
  /// Publishes `values` as `data_type` ("state_q", "obs", "input", "action", "output_q", ...), stamped now.
  Result<void> publish(const std::string& data_type, const std::vector<double>& values);
  /// Subscribers matched so far (DDS discovery takes a moment after creation).
  int matched_subscribers() const;

 private:
  friend class Client;
  struct Impl;
  explicit PolicyDataPublisher(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace robotd
