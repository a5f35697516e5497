// Callbacks for robotd's state topics.
#include <functional>
#include <memory>
#include <string>

#include "conversions.hpp"
#include "dispatch_scope.hpp"
#include "errors.hpp"
#include "handles.hpp"

using robotd::c::client_handle;
using robotd::c::DispatchScope;
using robotd::c::fail;
using robotd::c::forbid_in_own_callback;
using robotd::c::guarded;
using robotd::c::require;
using robotd::c::to_c;

namespace {

// Calls `callback` with each message as its C struct. Only the client's dispatch thread uses
// the struct, so one per subscription serves every sample without allocating.
template <class CStruct, class Message>
std::function<void(const Message&)> c_callback(const robotd::Client* owner, void (*callback)(const CStruct*, void*),
                                               void* user_data) {
  auto converted = std::make_shared<CStruct>();
  return [owner, callback, user_data, converted](const Message& message) {
    const DispatchScope scope(owner);
    to_c(message, *converted);
    callback(converted.get(), user_data);
  };
}

// The client to subscribe with, once the arguments are checked.
template <class Callback>
robotd_client& subscribing_client(robotd_client* client, Callback callback, robotd_subscription** subscription) {
  auto& handle = client_handle(client);
  if (callback == nullptr) fail(ROBOTD_INVALID_ARGUMENT, "callback is NULL: expected a function to call");
  require(subscription, "subscription", "a robotd_subscription* to store the new subscription in");
  forbid_in_own_callback(handle.client.get());
  return handle;
}

robotd_subscription* adopt(const robotd_client& handle, robotd::Subscription subscription, const char* topic) {
  if (!subscription.active()) {
    fail(ROBOTD_TRANSPORT, std::string("cannot subscribe to ") + topic +
                               ": DDS could not create the reader, or DDS Security does not permit it");
  }
  return new robotd_subscription{handle.client, std::move(subscription)};
}

}  // namespace

extern "C" {

robotd_status robotd_subscribe_joint_states(robotd_client* client, robotd_joint_state_callback callback,
                                            void* user_data, robotd_subscription** subscription) {
  return guarded("robotd_subscribe_joint_states", [&] {
    const auto& handle = subscribing_client(client, callback, subscription);
    *subscription = adopt(handle,
                          handle.client->on_joint_states(c_callback<robotd_joint_state, robotd::JointState>(
                              handle.client.get(), callback, user_data)),
                          "/joint_states");
  });
}

robotd_status robotd_subscribe_device_status(robotd_client* client, robotd_device_status_callback callback,
                                             void* user_data, robotd_subscription** subscription) {
  return guarded("robotd_subscribe_device_status", [&] {
    const auto& handle = subscribing_client(client, callback, subscription);
    *subscription = adopt(handle,
                          handle.client->on_device_status(c_callback<robotd_device_status, robotd::DeviceStatus>(
                              handle.client.get(), callback, user_data)),
                          "/device_status");
  });
}

robotd_status robotd_unsubscribe(robotd_subscription* subscription) {
  return guarded("robotd_unsubscribe", [&] {
    if (subscription == nullptr) return;
    forbid_in_own_callback(subscription->client.get());
    delete subscription;  // ~Subscription waits for a running callback
  });
}

}  // extern "C"
