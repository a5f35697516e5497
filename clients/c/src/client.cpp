// Connecting, and the services that need no session: devices, e-stop, device operations.
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <string>

#include "arguments.hpp"
#include "client_options.hpp"
#include "conversions.hpp"
#include "errors.hpp"
#include "handles.hpp"

using robotd::c::client_handle;
using robotd::c::fail;
using robotd::c::guarded;
using robotd::c::optional_text;
using robotd::c::require;
using robotd::c::take;
using robotd::c::text_argument;
using robotd::c::timeout_argument;
using robotd::c::to_c;
using robotd::c::to_client_options;

namespace {

// A copy of `text` the caller frees with robotd_free_string.
char* allocated_copy(const std::string& text) {
  auto* copy = static_cast<char*>(std::malloc(text.size() + 1));
  if (copy == nullptr) throw std::bad_alloc();
  std::memcpy(copy, text.c_str(), text.size() + 1);
  return copy;
}

}  // namespace

extern "C" {

robotd_status robotd_connect(const robotd_client_options* options, robotd_client** client) {
  return guarded("robotd_connect", [&] {
    auto& out = require(client, "client", "a robotd_client* to store the new client in");
    const robotd::ClientOptions cpp_options =
        options == nullptr ? robotd::ClientOptions::from_environment() : to_client_options(*options);
    auto connected = take(robotd::Client::connect(cpp_options));
    out = new robotd_client{std::make_shared<robotd::Client>(std::move(connected))};
  });
}

void robotd_disconnect(robotd_client* client) { delete client; }

robotd_status robotd_list_devices(robotd_client* client, robotd_device_info* devices, size_t capacity, size_t* count) {
  return guarded("robotd_list_devices", [&] {
    auto& handle = client_handle(client);
    auto& out_count = require(count, "count", "a size_t to store the number of devices in");
    if (devices == nullptr && capacity > 0) {
      fail(ROBOTD_INVALID_ARGUMENT, "devices is NULL with capacity " + std::to_string(capacity) +
                                        ": expected an array of capacity robotd_device_info");
    }
    const auto listed = take(handle.client->list_devices());
    if (devices != nullptr) {  // NULL only with capacity 0 (checked above): a query of the count
      for (std::size_t i = 0; i < std::min(listed.size(), capacity); ++i) to_c(listed[i], devices[i]);
    }
    out_count = listed.size();
    if (listed.size() > capacity) {
      fail(ROBOTD_BUFFER_TOO_SMALL,
           "robotd drives " + std::to_string(listed.size()) + " devices; the array holds " + std::to_string(capacity));
    }
  });
}

robotd_status robotd_estop(robotd_client* client, const char* device, const char* reason) {
  return guarded("robotd_estop", [&] {
    auto& handle = client_handle(client);
    const std::string name = text_argument(device, "device", ROBOTD_NAME_CAPACITY);
    (void)take(handle.client->estop(name, optional_text(reason)));
  });
}

robotd_status robotd_estop_report(robotd_client* client, const char* device, const char* reason, char** report) {
  return guarded("robotd_estop_report", [&] {
    auto& handle = client_handle(client);
    const std::string name = text_argument(device, "device", ROBOTD_NAME_CAPACITY);
    auto& out = require(report, "report", "a char* to store robotd's answer in");
    out = allocated_copy(take(handle.client->estop(name, optional_text(reason))).message);
  });
}

robotd_status robotd_reset_estop(robotd_client* client, const char* device) {
  return guarded("robotd_reset_estop", [&] {
    auto& handle = client_handle(client);
    (void)take(handle.client->reset_estop(text_argument(device, "device", ROBOTD_NAME_CAPACITY)));
  });
}

robotd_status robotd_device_call(robotd_client* client, const char* device, const char* op, const char* args_json,
                                 int32_t timeout_ms, char** result_json) {
  return guarded("robotd_device_call", [&] {
    auto& handle = client_handle(client);
    const std::string name = text_argument(device, "device", ROBOTD_NAME_CAPACITY);
    const std::string operation = &require(op, "op", "an operation name, e.g. \"state\"");
    const std::string args = args_json == nullptr ? "{}" : args_json;
    const auto timeout = timeout_argument(timeout_ms, "timeout_ms", false);
    auto& out = require(result_json, "result_json", "a char* to store the JSON result in");
    out = allocated_copy(take(handle.client->device_call(name, operation, args, timeout)));
  });
}

void robotd_free_string(char* text) { std::free(text); }

}  // extern "C"
