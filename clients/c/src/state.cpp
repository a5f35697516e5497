// The next sample of robotd's state topics.
#include "arguments.hpp"
#include "conversions.hpp"
#include "dispatch_scope.hpp"
#include "errors.hpp"
#include "handles.hpp"

using robotd::c::client_handle;
using robotd::c::forbid_in_own_callback;
using robotd::c::guarded;
using robotd::c::require;
using robotd::c::take;
using robotd::c::text_argument;
using robotd::c::timeout_argument;
using robotd::c::to_c;

extern "C" {

robotd_status robotd_next_joint_state(robotd_client* client, const char* device, int32_t timeout_ms,
                                      robotd_joint_state* state) {
  return guarded("robotd_next_joint_state", [&] {
    auto& handle = client_handle(client);
    const std::string name = text_argument(device, "device", ROBOTD_NAME_CAPACITY);
    const auto timeout = timeout_argument(timeout_ms, "timeout_ms", true);
    auto& out = require(state, "state", "a robotd_joint_state to fill");
    forbid_in_own_callback(handle.client.get());
    to_c(take(handle.client->next_joint_state(name, timeout)), out);
  });
}

robotd_status robotd_next_device_status(robotd_client* client, const char* device, int32_t timeout_ms,
                                        robotd_device_status* status) {
  return guarded("robotd_next_device_status", [&] {
    auto& handle = client_handle(client);
    const std::string name = text_argument(device, "device", ROBOTD_NAME_CAPACITY);
    const auto timeout = timeout_argument(timeout_ms, "timeout_ms", true);
    auto& out = require(status, "status", "a robotd_device_status to fill");
    forbid_in_own_callback(handle.client.get());
    to_c(take(handle.client->next_device_status(name, timeout)), out);
  });
}

}  // extern "C"
