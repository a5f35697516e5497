// Which client's callback the calling thread is running, if any. A client's dispatch thread
// runs its callbacks while holding the lock that subscribing and unsubscribing take, so those
// calls from one of its own callbacks would wait forever: they are refused instead.
#pragma once

#include "robotd/client.hpp"

namespace robotd::c {

/// Marks the calling thread as inside a callback of `client` for the scope's lifetime.
class DispatchScope {
 public:
  explicit DispatchScope(const Client* client) noexcept;
  DispatchScope(const DispatchScope&) = delete;
  DispatchScope& operator=(const DispatchScope&) = delete;
  ~DispatchScope();

 private:
  const Client* outer_;
};

/// Fails with ROBOTD_INVALID_ARGUMENT when called from a callback of `client`.
void forbid_in_own_callback(const Client* client);

}  // namespace robotd::c
