// Small conversions from values to the text robotctl prints.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "robotd/messages.hpp"

namespace robotctl {

/// `value` with `decimals` digits after the point: fixed(0.5, 2) == "0.50".
std::string fixed(double value, int decimals);
/// Ids with runs collapsed: {0, 1, 2, 3, 5} -> "0-3,5".
std::string id_ranges(const std::vector<std::int32_t>& ids);
std::string join(const std::vector<std::string>& parts, std::string_view separator);
std::string lowercase(std::string_view text);
/// "yes" / "no".
std::string yes_no(bool value);
/// Seconds since the epoch with microseconds: "1700000000.123456".
std::string stamp_text(const robotd::Time& stamp);

}  // namespace robotctl
