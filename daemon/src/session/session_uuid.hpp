#pragma once

#include <string>
#include <string_view>

namespace robotd::session {

/// A random (version 4) RFC 4122 uuid: 122 bits from the kernel's CSPRNG, formatted 8-4-4-4-12
/// in lowercase hex. The uuid is the session's capability: whoever holds it commands the
/// session's motors, so logs show only redacted_uuid().
std::string random_session_uuid();

/// The first 8 characters of `uuid` and "…": enough to tell sessions apart in a log and find
/// them in `robotctl sessions`, far too little to command with. A command's uuid comes from
/// the network, so anything but letters, digits and '-' is shown as '?'.
std::string redacted_uuid(std::string_view uuid);

}  // namespace robotd::session
