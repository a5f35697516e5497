// Text from the network (a node name, a device name, a uuid, a DDS layer message) made fit for
// one log line: bounded, so a megabyte-long name cannot flood the log, and escaped, so control
// characters cannot forge or garble lines.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace robotd::app {

inline constexpr std::size_t kLogTextBytes = 80;

/// At most `max_bytes` bytes of `text`, then "…(<n> bytes)" when it was longer; every byte
/// that is not printable ASCII written as \xNN (and a backslash as \\).
std::string log_text(std::string_view text, std::size_t max_bytes = kLogTextBytes);

}  // namespace robotd::app
