#include "sim_options.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <utility>

namespace robotd::hightorque::sim {
namespace {

Error invalid(std::string message) { return make_error(ErrorCode::kInvalidArgument, std::move(message)); }

/// A whole decimal integer, or nullopt.
std::optional<int> whole_number(std::string_view text) {
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc{} || end != text.data() + text.size()) return std::nullopt;
  return value;
}

}  // namespace

Result<std::vector<int>> parse_motor_ids(std::string_view text) {
  const std::string expected = "motor ids such as 1-6, 1,2,5 or 1-4,7 (each 1 … 30, no repeats)";
  if (text.empty()) return invalid("no motor ids: expected " + expected);
  std::vector<int> ids;
  std::string_view rest = text;
  while (true) {
    const std::size_t comma = rest.find(',');
    const std::string_view item = rest.substr(0, comma);
    const std::size_t dash = item.find('-');
    const std::optional<int> first = whole_number(item.substr(0, dash));
    const std::optional<int> last = dash == std::string_view::npos ? first : whole_number(item.substr(dash + 1));
    if (!first || !last || *first < kMinMotorId || *last > kMaxMotorId || *first > *last) {
      return invalid("'" + std::string(item) + "' in '" + std::string(text) + "': expected " + expected);
    }
    for (int id = *first; id <= *last; ++id) ids.push_back(id);
    if (comma == std::string_view::npos) break;
    rest = rest.substr(comma + 1);
  }
  std::sort(ids.begin(), ids.end());
  if (std::adjacent_find(ids.begin(), ids.end()) != ids.end()) {
    return invalid("'" + std::string(text) + "' names a motor twice: expected " + expected);
  }
  return ids;
}

Result<BusSpec> parse_bus_spec(BusSpec::Kind kind, std::string_view text, std::string_view option) {
  const std::size_t colon = text.rfind(':');
  if (colon == std::string_view::npos || colon == 0) {
    return invalid(std::string(option) + " '" + std::string(text) +
                   "': expected PATH:IDS, e.g. /tmp/legs.sock:1-6 (motor ids 1 … 30)");
  }
  auto ids = parse_motor_ids(text.substr(colon + 1));
  if (!ids) return invalid(std::string(option) + " '" + std::string(text) + "': " + ids.error().message);
  return BusSpec{.kind = kind, .path = std::string(text.substr(0, colon)), .ids = std::move(ids.value())};
}

Result<FirmwareVersion> parse_firmware(std::string_view text, std::string_view option) {
  std::array<int, 3> parts{};
  std::string_view rest = text;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const std::size_t dot = rest.find('.');
    const bool last = i + 1 == parts.size();
    const std::optional<int> part = whole_number(rest.substr(0, last ? std::string_view::npos : dot));
    if ((dot == std::string_view::npos) != last || !part || *part < 0 || *part > 255) {
      return invalid(std::string(option) + " '" + std::string(text) +
                     "': expected MAJOR.MINOR.PATCH, each 0 … 255, e.g. 4.4.6");
    }
    parts.at(i) = *part;
    if (!last) rest = rest.substr(dot + 1);
  }
  return FirmwareVersion{.motor = 0, .major = parts[0], .minor = parts[1], .patch = parts[2]};
}

Result<BoardFirmware> parse_board_firmware(std::string_view text) {
  const std::size_t dot = text.find('.');
  const std::optional<int> major = whole_number(text.substr(0, dot));
  const std::optional<int> minor = dot == std::string_view::npos ? std::nullopt : whole_number(text.substr(dot + 1));
  if (!major || !minor || *major < 0 || *major > 255 || *minor < 0 || *minor > 255) {
    return invalid("--board-firmware '" + std::string(text) + "': expected MAJOR.MINOR, each 0 … 255, e.g. 4.3");
  }
  return BoardFirmware{.major = *major, .minor = *minor};
}

Result<BoardMotorFirmware> parse_board_motor_firmware(std::string_view text) {
  constexpr std::string_view kOption = "--board-motor-firmware";
  const std::size_t colon = text.find(':');
  BoardMotorFirmware firmware;
  if (colon != std::string_view::npos) {
    auto ids = parse_motor_ids(text.substr(0, colon));
    if (!ids) return invalid(std::string(kOption) + " '" + std::string(text) + "': " + ids.error().message);
    firmware.ids = std::move(ids.value());
  }
  auto version = parse_firmware(colon == std::string_view::npos ? text : text.substr(colon + 1), kOption);
  if (!version) return version.error();
  firmware.version = version.value();
  return firmware;
}

double model_torque_per_unit(std::string_view model) {
  // The livelybot SDK's per-model torque factors (../shared/protocols/hightorque_and_ros2.md §1.6.3).
  constexpr std::array<std::pair<std::string_view, double>, 7> kFactors = {{{"5047_36", 0.004938},
                                                                            {"4438_32", 0.005584},
                                                                            {"6056_36", 0.00677},
                                                                            {"7256_35", 0.00677},
                                                                            {"60BM_35", 0.007942},
                                                                            {"60SG_35", 0.007942},
                                                                            {"5043_20", 0.00966}}};
  for (const auto& [name, factor] : kFactors) {
    if (name == model) return factor;
  }
  return 0;
}

}  // namespace robotd::hightorque::sim
