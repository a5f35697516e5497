#pragma once

#include <string>

namespace robotd::session {

/// 128 random bits from the kernel's CSPRNG, formatted 8-4-4-4-12 in lowercase hex. The uuid
/// is the session's capability: whoever holds it commands the session's motors.
std::string random_session_uuid();

}  // namespace robotd::session
