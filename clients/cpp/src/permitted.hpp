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

  /// The endpoint, or why it does not exist.
  Result<Endpoint*> get() const {
    if (endpoint_) return endpoint_.get();
    return denied_;
  }

 private:
  std::unique_ptr<Endpoint> endpoint_;
  Error denied_;
};

}  // namespace robotd::detail
