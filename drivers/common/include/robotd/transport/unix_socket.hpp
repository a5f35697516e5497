// A listening unix socket at a path, for the CAN stand-in bus and simulators' control channels.
#pragma once

#include <string>

#include "robotd/result.hpp"

namespace robotd::transport {

/// A non-blocking, close-on-exec listening socket of `type` (SOCK_SEQPACKET, SOCK_STREAM) at
/// `path`, replacing a stale socket file (one left by a killed process). Errors name the path.
Result<int> listen_unix_socket(const std::string& path, int type, int backlog);

/// Whether a process listens on the unix socket at `path` (stream or seqpacket), so a second
/// simulator can refuse a path the first one serves instead of taking it over.
bool unix_socket_in_use(const std::string& path);

}  // namespace robotd::transport
