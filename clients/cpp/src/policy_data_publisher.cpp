#include "robotd/client/policy_data_publisher.hpp"

#include <chrono>

#include "client_core.hpp"
#include "policy_data_publisher_impl.hpp"

namespace robotd {
namespace {

Time now() {
  return Time::from_ns(
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch())
          .count());
}

}  // namespace

PolicyDataPublisher::PolicyDataPublisher(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
PolicyDataPublisher::PolicyDataPublisher(PolicyDataPublisher&&) noexcept = default;
PolicyDataPublisher& PolicyDataPublisher::operator=(PolicyDataPublisher&&) noexcept = default;
PolicyDataPublisher::~PolicyDataPublisher() = default;

Result<void> PolicyDataPublisher::publish(const PolicyData& data) {
  if (data.header.stamp.sec != 0 || data.header.stamp.nanosec != 0) return impl_->writer.write(data);
  PolicyData stamped = data;
  stamped.header.stamp = now();
  return impl_->writer.write(stamped);
}

Result<void> PolicyDataPublisher::publish(const std::string& data_type, const std::vector<double>& values) {
  PolicyData data;
  data.header.stamp = now();
  data.data_type = data_type;
  data.data = values;
  return impl_->writer.write(data);
}

int PolicyDataPublisher::matched_subscribers() const { return impl_->writer.matched_readers(); }

}  // namespace robotd
