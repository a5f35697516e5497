#include "text_format.hpp"

#include <array>
#include <cctype>
#include <cstdio>

namespace robotctl {

std::string fixed(double value, int decimals) {
  std::array<char, 64> text{};
  std::snprintf(text.data(), text.size(), "%.*f", decimals, value);
  return text.data();
}

std::string id_ranges(const std::vector<std::int32_t>& ids) {
  std::string text;
  for (std::size_t first = 0; first < ids.size();) {
    std::size_t last = first;
    while (last + 1 < ids.size() && ids[last + 1] == ids[last] + 1) ++last;
    text += (text.empty() ? "" : ",") + std::to_string(ids[first]);
    if (last > first) text += "-" + std::to_string(ids[last]);
    first = last + 1;
  }
  return text;
}

std::string join(const std::vector<std::string>& parts, std::string_view separator) {
  std::string text;
  for (const auto& part : parts) {
    if (!text.empty()) text += separator;
    text += part;
  }
  return text;
}

std::string lowercase(std::string_view text) {
  std::string lower(text);
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return lower;
}

std::string yes_no(bool value) { return value ? "yes" : "no"; }

std::string stamp_text(const robotd::Time& stamp) {
  std::array<char, 16> fraction{};
  std::snprintf(fraction.data(), fraction.size(), ".%06u", stamp.nanosec / 1000U);
  return std::to_string(stamp.sec) + fraction.data();
}

}  // namespace robotctl
