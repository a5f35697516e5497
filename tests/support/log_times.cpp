#include "log_times.hpp"

#include <algorithm>
#include <ctime>
#include <iomanip>
#include <sstream>

namespace robotd::testing {
namespace {

/// A line's "[2026-11-22 04:58:20.123]" prefix as a time point.
std::optional<WallTime> line_stamp(std::string_view line) {
  if (line.size() < 25 || line[0] != '[' || line[24] != ']') return std::nullopt;
  std::tm parts{};
  std::istringstream text{std::string(line.substr(1, 19))};
  text >> std::get_time(&parts, "%Y-%m-%d %H:%M:%S");
  if (text.fail()) return std::nullopt;
  parts.tm_isdst = -1;
  const std::time_t seconds = std::mktime(&parts);
  if (seconds == -1) return std::nullopt;
  int milliseconds = 0;
  for (const char digit : line.substr(21, 3)) {
    if (digit < '0' || digit > '9') return std::nullopt;
    milliseconds = milliseconds * 10 + (digit - '0');
  }
  return std::chrono::system_clock::from_time_t(seconds) + std::chrono::milliseconds(milliseconds);
}

}  // namespace

std::optional<WallTime> logged_at(const std::string& log, std::string_view needle, WallTime after) {
  // The stamp drops the sub-millisecond part: a line from the same millisecond as `after` counts.
  const WallTime earliest = std::chrono::floor<std::chrono::milliseconds>(after);
  std::size_t start = 0;
  while (start < log.size()) {
    std::size_t end = log.find('\n', start);
    if (end == std::string::npos) end = log.size();
    const std::string_view line(log.data() + start, end - start);
    if (line.find(needle) != std::string_view::npos) {
      const auto stamp = line_stamp(line);
      if (stamp && *stamp >= earliest) return stamp;
    }
    start = end + 1;
  }
  return std::nullopt;
}

double milliseconds_between(WallTime from, WallTime to) {
  return std::max(0.0, std::chrono::duration<double, std::milli>(to - from).count());
}

}  // namespace robotd::testing
