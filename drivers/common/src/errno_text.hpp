// What an errno value means, for the transports' error messages.
#pragma once

#include <string>
#include <system_error>

namespace robotd::transport {

inline std::string errno_text(int error) { return std::generic_category().message(error); }

}  // namespace robotd::transport
