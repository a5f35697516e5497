#include "sim_options.hpp"

#include <charconv>
#include <string_view>

namespace robotd::parol6::sim {
Result<std::array<std::int32_t, kJoints>> parse_initial_steps(const std::string& text) {
  std::array<std::int32_t, kJoints> steps{};
  std::string_view rest = text;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const std::size_t comma = rest.find(',');
    if ((comma == std::string_view::npos) != (i + 1 == steps.size())) {
      return make_error(
          ErrorCode::kInvalidArgument,
          "--initial-steps '" + text + "' must be six comma-separated step counts, e.g. 0,-32000,57905,0,0,32000");
    }
    const std::string_view item = rest.substr(0, comma);
    rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
    const auto [end, error] = std::from_chars(item.data(), item.data() + item.size(), steps[i]);
    if (error != std::errc{} || end != item.data() + item.size() || steps[i] < kMinInt24 || steps[i] > kMaxInt24) {
      return make_error(ErrorCode::kInvalidArgument, "--initial-steps: '" + std::string(item) + "' (joint " +
                                                         std::to_string(i + 1) +
                                                         ") is not an integer step count in -8388608 … 8388607");
    }
  }
  return steps;
}

}  // namespace robotd::parol6::sim
