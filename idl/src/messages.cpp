#include "robotd/messages.hpp"

#include <array>
#include <cctype>
#include <string>

#include "robotd/result.hpp"

namespace robotd {
namespace {

constexpr std::int64_t kNsPerSecond = 1'000'000'000;

bool equals_ignoring_case(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i]))) return false;
  }
  return true;
}

// Accepts the enum's name, its name with the PI Plus "_MODE" suffix, or its number.
template <class Enum, std::size_t N>
std::optional<Enum> parse_enum(std::string_view text, const std::array<std::string_view, N>& names) {
  for (std::size_t i = 0; i < N; ++i) {
    const std::string with_suffix = std::string(names[i]) + "_MODE";
    if (equals_ignoring_case(text, names[i]) || equals_ignoring_case(text, with_suffix) || text == std::to_string(i)) {
      return static_cast<Enum>(i);
    }
  }
  return std::nullopt;
}

constexpr std::array<std::string_view, 3> kModeNames{"POSITION", "TORQUE", "MIXED"};
constexpr std::array<std::string_view, 3> kBehaviorNames{"KEEP", "DAMPING", "ZERO_TORQUE"};
constexpr std::array<std::string_view, 2> kLowRateActionNames{"WARN", "FALLBACK"};
constexpr std::array<std::string_view, 6> kStateNames{"CONNECTING", "RUNNING",     "FAULT",
                                                      "ESTOP",      "MAINTENANCE", "STOPPED"};

}  // namespace

const char* to_string(ErrorCode code) {
  switch (code) {
    case ErrorCode::kTimeout:
      return "timeout";
    case ErrorCode::kNotAvailable:
      return "not available";
    case ErrorCode::kRefused:
      return "refused";
    case ErrorCode::kInvalidArgument:
      return "invalid argument";
    case ErrorCode::kTransport:
      return "transport error";
    case ErrorCode::kNotPermitted:
      return "not permitted";
  }
  return "unknown error";
}

bool is_valid(ControlMode mode) {
  return static_cast<std::int32_t>(mode) >= 0 && static_cast<std::size_t>(mode) < kModeNames.size();
}
bool is_valid(Behavior behavior) {
  return static_cast<std::int32_t>(behavior) >= 0 && static_cast<std::size_t>(behavior) < kBehaviorNames.size();
}
bool is_valid(LowRateAction action) {
  return static_cast<std::int32_t>(action) >= 0 && static_cast<std::size_t>(action) < kLowRateActionNames.size();
}

std::string_view to_string(ControlMode mode) {
  return is_valid(mode) ? kModeNames[static_cast<std::size_t>(mode)] : "INVALID_MODE";
}
std::string_view to_string(Behavior behavior) {
  return is_valid(behavior) ? kBehaviorNames[static_cast<std::size_t>(behavior)] : "INVALID_BEHAVIOR";
}
std::string_view to_string(LowRateAction action) {
  return is_valid(action) ? kLowRateActionNames[static_cast<std::size_t>(action)] : "INVALID_ACTION";
}
std::string_view to_string(DeviceState state) {
  const auto index = static_cast<std::size_t>(state);
  return index < kStateNames.size() ? kStateNames[index] : "INVALID_STATE";
}

std::optional<ControlMode> parse_control_mode(std::string_view text) {
  return parse_enum<ControlMode>(text, kModeNames);
}
std::optional<Behavior> parse_behavior(std::string_view text) { return parse_enum<Behavior>(text, kBehaviorNames); }
std::optional<LowRateAction> parse_low_rate_action(std::string_view text) {
  return parse_enum<LowRateAction>(text, kLowRateActionNames);
}

Time Time::from_ns(std::int64_t ns) {
  std::int64_t sec = ns / kNsPerSecond;
  std::int64_t rem = ns % kNsPerSecond;
  if (rem < 0) {
    rem += kNsPerSecond;
    --sec;
  }
  return Time{static_cast<std::int32_t>(sec), static_cast<std::uint32_t>(rem)};
}

std::int64_t Time::to_ns() const { return static_cast<std::int64_t>(sec) * kNsPerSecond + nanosec; }

std::uint64_t CommandCounters::rejected_total() const {
  return rejected_unknown_session + rejected_wrong_device + rejected_not_owner + rejected_unknown_motor +
         rejected_malformed + rejected_non_finite + rejected_out_of_range + rejected_estop + rejected_fault;
}

}  // namespace robotd
