#include "dispatch_scope.hpp"

#include "errors.hpp"

namespace robotd::c {
namespace {
thread_local const Client* dispatching = nullptr;
}  // namespace

DispatchScope::DispatchScope(const Client* client) noexcept : outer_(dispatching) { dispatching = client; }

DispatchScope::~DispatchScope() { dispatching = outer_; }

void forbid_in_own_callback(const Client* client) {
  if (client != nullptr && client == dispatching) {
    fail(ROBOTD_INVALID_ARGUMENT,
         "called from a callback of the same client: it would wait for the client's dispatch thread, which is "
         "running that callback");
  }
}

}  // namespace robotd::c
