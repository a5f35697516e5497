// A listening unix socket at a path, for the CAN stand-in bus and simulators' control channels.
#pragma once

#include <string>

#include "robotd/result.hpp"

namespace robotd::transport {

/// A non-blocking, close-on-exec listening socket of `type` (SOCK_SEQPACKET, SOCK_STREAM) at
/// `path`, replacing a stale socket file (one left by a killed process). Errors name the path.
Result<int> listen_unix_socket(const std::string& path, int type, int backlog);

}  // namespace robotd::transport
