// Sessions: requesting control, what robotd granted, releasing.
#include <algorithm>
#include <string>

#include "arguments.hpp"
#include "errors.hpp"
#include "handles.hpp"
#include "robotd/limits.hpp"

using robotd::c::array_argument;
using robotd::c::behavior_argument;
using robotd::c::client_handle;
using robotd::c::fail;
using robotd::c::guarded;
using robotd::c::low_rate_action_argument;
using robotd::c::mode_argument;
using robotd::c::require;
using robotd::c::require_joint_count;
using robotd::c::session_handle;
using robotd::c::take;
using robotd::c::text_argument;

namespace {

robotd::SessionRequest to_session_request(const robotd_session_request& request) {
  require_joint_count(request.motor_count, "request->motor_count");
  if (request.motor_ids == nullptr && request.motor_count > 0) {
    fail(ROBOTD_INVALID_ARGUMENT, "request->motor_ids is NULL with motor_count " + std::to_string(request.motor_count) +
                                      ": expected that many motor ids, or motor_count 0 for every motor");
  }
  if (request.motor_count == 0 && (request.default_kp != nullptr || request.default_kd != nullptr)) {
    fail(ROBOTD_INVALID_ARGUMENT,
         "request->default_kp/default_kd given with motor_count 0: expected motor_ids and motor_count "
         "saying which motors (and so how many gains) they are for");
  }
  robotd::SessionRequest converted;
  converted.device = text_argument(request.device, "request->device", ROBOTD_NAME_CAPACITY);
  converted.motor_ids = array_argument(request.motor_ids, request.motor_count);
  converted.mode = mode_argument(request.mode, "request->mode");
  converted.on_timeout = behavior_argument(request.on_timeout, "request->on_timeout");
  converted.timeout = std::chrono::milliseconds(request.timeout_ms);
  converted.default_kp = array_argument(request.default_kp, request.motor_count);
  converted.default_kd = array_argument(request.default_kd, request.motor_count);
  converted.on_release = behavior_argument(request.on_release, "request->on_release");
  converted.policy_name =
      text_argument(request.policy_name, "request->policy_name", robotd::limits::kPolicyNameBytes + 1);
  converted.policy_file_name =
      text_argument(request.policy_file_name, "request->policy_file_name", robotd::limits::kPolicyFileNameBytes + 1);
  converted.closed_loop = request.closed_loop;
  converted.min_command_success_rate = request.min_command_success_rate;
  converted.on_low_success_rate = low_rate_action_argument(request.on_low_success_rate, "request->on_low_success_rate");
  return converted;
}

}  // namespace

extern "C" {

robotd_status robotd_session_request_init(robotd_session_request* request) {
  return guarded("robotd_session_request_init", [&] {
    auto& out = require(request, "request", "a robotd_session_request to fill");
    const robotd::SessionRequest defaults;
    out = robotd_session_request{};
    out.mode = static_cast<robotd_control_mode>(defaults.mode);
    out.on_timeout = static_cast<robotd_behavior>(defaults.on_timeout);
    out.timeout_ms = static_cast<int32_t>(defaults.timeout.count());
    out.on_release = static_cast<robotd_behavior>(defaults.on_release);
    out.on_low_success_rate = static_cast<robotd_low_rate_action>(defaults.on_low_success_rate);
  });
}

robotd_status robotd_request_control(robotd_client* client, const robotd_session_request* request,
                                     robotd_session** session) {
  return guarded("robotd_request_control", [&] {
    auto& handle = client_handle(client);
    const auto converted = to_session_request(require(request, "request", "a robotd_session_request"));
    auto& out = require(session, "session", "a robotd_session* to store the new session in");
    out = new robotd_session{take(handle.client->request_control(converted)), converted.on_release};
  });
}

robotd_status robotd_session_uuid(const robotd_session* session, const char** uuid) {
  return guarded("robotd_session_uuid", [&] {
    const auto& handle = session_handle(session);
    require(uuid, "uuid", "a const char* to store the uuid in") = handle.session.uuid().c_str();
  });
}

robotd_status robotd_session_id(const robotd_session* session, const char** session_id) {
  return guarded("robotd_session_id", [&] {
    const auto& handle = session_handle(session);
    require(session_id, "session_id", "a const char* to store the public id in") = handle.session.session_id().c_str();
  });
}

robotd_status robotd_session_device(const robotd_session* session, const char** device) {
  return guarded("robotd_session_device", [&] {
    const auto& handle = session_handle(session);
    require(device, "device", "a const char* to store the device name in") = handle.session.device().c_str();
  });
}

robotd_status robotd_session_motor_ids(const robotd_session* session, int32_t* motor_ids, size_t capacity,
                                       size_t* count) {
  return guarded("robotd_session_motor_ids", [&] {
    const auto& ids = session_handle(session).session.motor_ids();
    auto& out_count = require(count, "count", "a size_t to store the number of motors in");
    if (motor_ids == nullptr && capacity > 0) {
      fail(ROBOTD_INVALID_ARGUMENT,
           "motor_ids is NULL with capacity " + std::to_string(capacity) + ": expected an array of capacity int32_t");
    }
    std::copy_n(ids.begin(), std::min(ids.size(), capacity), motor_ids);
    out_count = ids.size();
    if (ids.size() > capacity) {
      fail(ROBOTD_BUFFER_TOO_SMALL,
           "the session has " + std::to_string(ids.size()) + " motors; the array holds " + std::to_string(capacity));
    }
  });
}

robotd_status robotd_session_mode(const robotd_session* session, robotd_control_mode* mode) {
  return guarded("robotd_session_mode", [&] {
    const auto& handle = session_handle(session);
    require(mode, "mode", "a robotd_control_mode to store the mode in") =
        static_cast<robotd_control_mode>(handle.session.mode());
  });
}

robotd_status robotd_session_timeout_behavior(const robotd_session* session, robotd_behavior* behavior) {
  return guarded("robotd_session_timeout_behavior", [&] {
    const auto& handle = session_handle(session);
    require(behavior, "behavior", "a robotd_behavior to store the behavior in") =
        static_cast<robotd_behavior>(handle.session.applied_timeout_behavior());
  });
}

robotd_status robotd_release(robotd_session* session, robotd_behavior behavior) {
  return guarded("robotd_release", [&] {
    auto& handle = session_handle(session);
    (void)take(handle.session.release(behavior_argument(behavior, "behavior")));
  });
}

robotd_status robotd_release_by_uuid(robotd_client* client, const char* uuid, robotd_behavior behavior) {
  return guarded("robotd_release_by_uuid", [&] {
    auto& handle = client_handle(client);
    require(uuid, "uuid", "a session uuid");
    const std::string text = text_argument(uuid, "uuid", ROBOTD_UUID_CAPACITY);
    (void)take(handle.client->release_control(text, behavior_argument(behavior, "behavior")));
  });
}

void robotd_session_free(robotd_session* session) {
  if (session == nullptr) return;
  // Released here, not by ~Session, so that a failure (robotd gone) is recorded for
  // robotd_last_error(), and nothing can throw.
  (void)guarded("robotd_session_free", [&] {
    if (session->session.active()) (void)take(session->session.release(session->on_release));
  });
  delete session;
}

}  // extern "C"
