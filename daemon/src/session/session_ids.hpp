// A session's two names. The uuid is its capability: whoever holds it commands and releases
// the session's motors, so only the client it was granted to learns it, and logs never show
// it. The public id names the session to everyone else (/session_status, refusals, logs);
// it is drawn on its own, so it tells nothing about the uuid.
#pragma once

#include <string>
#include <string_view>

namespace robotd::session {

/// A random (version 4) RFC 4122 uuid: 122 bits from the kernel's CSPRNG, formatted 8-4-4-4-12
/// in lowercase hex.
std::string random_session_uuid();

/// A public session id: 8 lowercase hex digits (32 random bits), e.g. "3f2a9c1e". The caller
/// draws again while it equals a live session's id.
std::string random_session_id();

/// A uuid that is no active session's, for a log line: its first 8 characters and "…",
/// anything but letters, digits and '-' shown as '?'. (An active session is logged by its
/// public id instead.)
std::string redacted_uuid(std::string_view uuid);

}  // namespace robotd::session
