// A service client or writer a Client may use, or why DDS Security does not let it: a client
// whose permissions are read-only still connects and subscribes, and only the calls it may not
// make fail, each with the kNotPermitted error that kept its endpoint from being created.
#pragma once

#include <memory>
#include <utility>

#include "robotd/result.hpp"

namespace robotd::detail {

template <class Endpoint>
class Permitted {
 public:
  Permitted() = default;
  explicit Permitted(std::unique_ptr<Endpoint> endpoint) : endpoint_(std::move(endpoint)) {}
  explicit Permitted(Error denied) : denied_(std::move(denied)) {}

  /// The endpoint's call(...) for a service client, or why it may not be made.
  template <class... Args, class E = Endpoint>
  auto call(Args&&... args) const -> decltype(std::declval<E&>().call(std::forward<Args>(args)...)) {
    if (!endpoint_) return denied_;
    return endpoint_->call(std::forward<Args>(args)...);
  }
  /// The endpoint's write(...) for a topic writer, or why it may not be made.
  template <class Sample>
  Result<void> write(const Sample& sample) const {
    if (!endpoint_) return denied_;
    return endpoint_->write(sample);
  }
  /// The endpoint, or null if DDS Security does not permit it.
  const Endpoint* get() const { return endpoint_.get(); }

 private:
  std::unique_ptr<Endpoint> endpoint_;
  Error denied_;
};

}  // namespace robotd::detail
