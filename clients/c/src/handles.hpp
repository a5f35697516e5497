// What the C API's opaque handles hold.
#pragma once

#include <memory>
#include <string_view>

#include "arguments.hpp"
#include "robotd/client.hpp"
#include "robotd/robotd.h"

struct robotd_client {
  // Shared with the client's subscriptions, which keep the DDS participant alive after
  // robotd_disconnect while their callbacks may still run.
  std::shared_ptr<robotd::Client> client;
};

struct robotd_session {
  robotd::Session session;  // holds the client's DDS participant itself
  robotd::Behavior on_release = robotd::Behavior::kKeep;
};

struct robotd_subscription {
  std::shared_ptr<robotd::Client> client;
  robotd::Subscription subscription;  // after `client`: it ends before the client can
};

namespace robotd::c {

inline robotd_client& client_handle(robotd_client* client) {
  return require(client, "client", "a client from robotd_connect");
}

template <class Session>  // robotd_session or const robotd_session
Session& session_handle(Session* session) {
  return require(session, "session", "a session from robotd_request_control");
}

}  // namespace robotd::c
