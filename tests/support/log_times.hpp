// When robotd said something: the time stamps of its log lines, for tests that measure how long
// robotd took to notice or handle an event (a fault, a reconnect) to the millisecond, however
// often it publishes its status.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <string_view>

namespace robotd::testing {

using WallTime = std::chrono::system_clock::time_point;

/// The stamp of the first line of `log` that contains `needle` and was logged at or after
/// `after` (robotd's "[YYYY-mm-dd HH:MM:SS.mmm]" prefix, local time); nullopt if there is none.
std::optional<WallTime> logged_at(const std::string& log, std::string_view needle, WallTime after);

/// Milliseconds from `from` to `to`, never negative (a stamp has millisecond resolution).
double milliseconds_between(WallTime from, WallTime to);

}  // namespace robotd::testing
