#include "statement_binding.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <span>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>

namespace robotd::rbtscript::detail {
namespace {

using Bound = std::variant<StatementKind, LineError>;

LineError error_at(const Argument& argument, std::string expected) {
  return {argument.column, describe(argument), std::move(expected)};
}
/// An error about the argument at `index`, or about the ')' when there are fewer arguments.
LineError error_at_position(const Call& call, std::size_t index, std::string expected) {
  if (index < call.arguments.size()) return error_at(call.arguments[index], std::move(expected));
  return error_at(call.close, std::move(expected));
}

bool is_plain(const Argument& argument, TokenKind kind) { return !argument.name && argument.value.kind == kind; }
bool is_word(const Argument& argument, std::string_view word) {
  return is_plain(argument, TokenKind::kWord) && argument.value.text == word;
}

/// A number written as a whole number (no point, no exponent), if it is one and fits an int.
std::optional<int> whole_number(const Argument& argument) {
  if (!is_plain(argument, TokenKind::kNumber)) return std::nullopt;
  std::string_view text = argument.value.text;
  if (text.starts_with('+')) text.remove_prefix(1);
  int value = 0;
  const auto [rest, status] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (status != std::errc{} || rest != text.data() + text.size()) return std::nullopt;
  return value;
}

/// The leading plain numbers, at most `max`; an error when there are fewer than `min`.
std::variant<std::vector<double>, LineError> leading_numbers(const Call& call, std::size_t min, std::size_t max,
                                                             std::string_view what) {
  std::vector<double> values;
  for (const auto& argument : call.arguments) {
    if (values.size() == max || !is_plain(argument, TokenKind::kNumber)) break;
    values.push_back(argument.value.number);
  }
  if (values.size() < min) return error_at_position(call, values.size(), std::string(what));
  return values;
}

/// Nothing may follow the first `count` arguments.
std::optional<LineError> no_more_arguments(const Call& call, std::size_t count, std::string_view takes) {
  if (call.arguments.size() <= count) return std::nullopt;
  return error_at(call.arguments[count], "')': " + std::string(call.name.text) + " takes " + std::string(takes));
}

// The optional arguments of the moves, in the one order the language allows.
enum class Option { kSpeed, kAcceleration, kDuration, kProfile, kTracking };
constexpr std::array<std::string_view, 5> kOptionSpelling = {"v=", "a=", "t=", "func", "speed"};
constexpr std::array kJointMoveOptions = {Option::kSpeed, Option::kAcceleration, Option::kDuration, Option::kProfile,
                                          Option::kTracking};
constexpr std::array kCartesianMoveOptions = {Option::kDuration, Option::kProfile, Option::kTracking};

std::string_view spelling(Option option) { return kOptionSpelling.at(static_cast<std::size_t>(option)); }

std::string option_list(std::span<const Option> allowed) {
  std::string list;
  for (const Option option : allowed) list += (list.empty() ? "" : ", ") + std::string(spelling(option));
  return list;
}

std::optional<Profile> profile_named(std::string_view name) {
  if (name == "poly") return Profile::kPolynomial;
  if (name == "trap") return Profile::kTrapezoid;
  return std::nullopt;
}

/// poly or trap, bare or quoted.
std::optional<Profile> profile_of(const Token& token) {
  if (token.kind == TokenKind::kWord) return profile_named(token.text);
  if (token.kind == TokenKind::kString) return profile_named(string_content(token));
  return std::nullopt;
}

/// Which optional argument this is, from its name or, unnamed, from its value (func, speed).
std::optional<Option> option_of(const Argument& argument) {
  if (argument.name) {
    const std::string_view name = argument.name->text;
    if (name == "v") return Option::kSpeed;
    if (name == "a") return Option::kAcceleration;
    if (name == "t") return Option::kDuration;
    if (name == "func") return Option::kProfile;
    if (name == "speed") return Option::kTracking;
    return std::nullopt;
  }
  if (is_word(argument, "speed")) return Option::kTracking;
  if (profile_of(argument.value)) return Option::kProfile;
  return std::nullopt;
}

std::optional<LineError> bind_percent(const Argument& argument, std::string_view meaning, std::optional<double>& out) {
  const Token& value = argument.value;
  if (value.kind != TokenKind::kNumber || !(value.number > 0 && value.number <= 100)) {
    return error_at(value, "a number greater than 0 and at most 100 (" + std::string(meaning) + ")");
  }
  out = value.number;
  return std::nullopt;
}

std::optional<LineError> bind_option(const Argument& argument, Option option, JointMotion& options) {
  switch (option) {
    case Option::kSpeed:
      return bind_percent(argument, "v: percent of the leading joint's maximum speed", options.speed_percent);
    case Option::kAcceleration:
      return bind_percent(argument, "a: percent of the leading joint's maximum acceleration",
                          options.acceleration_percent);
    case Option::kDuration:
      if (argument.value.kind != TokenKind::kNumber || !(argument.value.number > 0)) {
        return error_at(argument.value, "a number of seconds greater than 0 (t: the move's duration)");
      }
      options.duration_s = argument.value.number;
      return std::nullopt;
    case Option::kProfile:
      options.profile = profile_of(argument.value);
      if (!options.profile) return error_at(argument.value, "poly or trap (func: the velocity profile)");
      return std::nullopt;
    case Option::kTracking:
      if (argument.name) return error_at(argument, "the bare word speed, without a value");
      options.tracking = Tracking::kSpeedOnly;
      return std::nullopt;
  }
  return std::nullopt;
}

/// The optional arguments from `first` on: each of `allowed` at most once, in that order.
std::variant<JointMotion, LineError> bind_options(const Call& call, std::size_t first, std::span<const Option> allowed,
                                                  std::string_view values_note) {
  JointMotion options;
  std::optional<Option> previous;
  for (std::size_t i = first; i < call.arguments.size(); ++i) {
    const Argument& argument = call.arguments[i];
    const auto option = option_of(argument);
    if (!option || std::find(allowed.begin(), allowed.end(), *option) == allowed.end()) {
      return error_at(argument, "')' or one of the optional arguments " + option_list(allowed) + " (" +
                                    std::string(values_note) + ")");
    }
    if (previous && *option == *previous) {
      return error_at(argument,
                      "each optional argument at most once, but " + std::string(spelling(*option)) + " is given twice");
    }
    if (previous && *option < *previous) {
      return error_at(argument, "the optional arguments in the order " + option_list(allowed) + ", so " +
                                    std::string(spelling(*option)) + " before " + std::string(spelling(*previous)));
    }
    previous = option;
    if (auto error = bind_option(argument, *option, options)) return std::move(*error);
  }
  return options;
}

/// The Cartesian moves' share of the options (bind_options has refused v and a for them).
CartesianMotion cartesian_motion(const JointMotion& options) {
  return {options.duration_s, options.profile, options.tracking};
}

Pose pose_of(const std::vector<double>& values) {
  return {values[0], values[1], values[2], values[3], values[4], values[5]};
}

constexpr std::string_view kPoseValues = "6 pose values: x, y, z in mm, then Rx, Ry, Rz in degrees";

/// The pose values and the optional arguments a pose move takes.
template <class Build>
Bound bind_pose_move(const Call& call, std::span<const Option> allowed, std::string_view values_note, Build build) {
  auto values = leading_numbers(call, 6, 6, kPoseValues);
  if (auto* error = std::get_if<LineError>(&values)) return std::move(*error);
  auto options = bind_options(call, 6, allowed, values_note);
  if (auto* error = std::get_if<LineError>(&options)) return std::move(*error);
  return build(pose_of(std::get<std::vector<double>>(values)), std::get<JointMotion>(options));
}

Bound bind_move_joint(const Call& call) {
  auto values = leading_numbers(call, 1, kMaxJointValues, "1 to 7 joint values in degrees");
  if (auto* error = std::get_if<LineError>(&values)) return std::move(*error);
  auto joints = std::get<std::vector<double>>(std::move(values));
  auto options = bind_options(call, joints.size(), kJointMoveOptions, "MoveJoint takes at most 7 joint values");
  if (auto* error = std::get_if<LineError>(&options)) return std::move(*error);
  return MoveJoint{std::move(joints), std::get<JointMotion>(options)};
}

Bound bind_move_pose(const Call& call) {
  return bind_pose_move(call, kJointMoveOptions, "MovePose takes exactly 6 pose values",
                        [](const Pose& pose, const JointMotion& options) -> StatementKind {
                          return MovePose{pose, options};
                        });
}

Bound bind_move_cart(const Call& call) {
  return bind_pose_move(call, kCartesianMoveOptions, "MoveCart takes exactly 6 pose values, and no v or a",
                        [](const Pose& pose, const JointMotion& options) -> StatementKind {
                          return MoveCart{pose, cartesian_motion(options)};
                        });
}

Bound bind_move_cart_rel_trf(const Call& call) {
  return bind_pose_move(call, kCartesianMoveOptions, "MoveCartRelTRF takes exactly 6 pose values, and no v or a",
                        [](const Pose& pose, const JointMotion& options) -> StatementKind {
                          return MoveCartRelTrf{pose, cartesian_motion(options)};
                        });
}

Bound bind_delay(const Call& call) {
  constexpr std::string_view kExpected = "the delay in seconds, a number of at least 0";
  if (call.arguments.empty()) return error_at(call.close, std::string(kExpected));
  const Argument& seconds = call.arguments[0];
  if (!is_plain(seconds, TokenKind::kNumber) || seconds.value.number < 0) {
    return error_at(seconds, std::string(kExpected));
  }
  if (auto error = no_more_arguments(call, 1, "one value")) return std::move(*error);
  return Delay{seconds.value.number};
}

template <class Statement>
Bound bind_no_arguments(const Call& call) {
  if (auto error = no_more_arguments(call, 0, "no arguments")) return std::move(*error);
  return Statement{};
}

Bound bind_output(const Call& call) {
  constexpr std::string_view kOutputNumberExpected = "the output number, a whole number of at least 1";
  if (call.arguments.empty()) return error_at(call.close, std::string(kOutputNumberExpected));
  const auto number = whole_number(call.arguments[0]);
  if (!number || *number < 1) return error_at(call.arguments[0], std::string(kOutputNumberExpected));
  if (call.arguments.size() < 2) return error_at(call.close, "',' and then HIGH or LOW");
  const Argument& level = call.arguments[1];
  if (!is_word(level, "HIGH") && !is_word(level, "LOW")) return error_at(level, "HIGH or LOW");
  if (auto error = no_more_arguments(call, 2, "an output number and HIGH or LOW")) return std::move(*error);
  return Output{*number, is_word(level, "HIGH") ? Level::kHigh : Level::kLow};
}

Bound bind_gripper(const Call& call) {
  struct Field {
    std::string_view expected;
    int max;
  };
  constexpr std::array<Field, 3> kFields = {{
      {"the gripper position, a whole number from 0 (open) to 255 (closed)", 255},
      {"the gripper speed, a whole number from 0 to 255", 255},
      {"the gripper current in mA, a whole number from 0 to 1300", 1300},
  }};
  std::array<int, 3> values{};
  for (std::size_t i = 0; i < kFields.size(); ++i) {
    const Field& field = kFields.at(i);
    const auto value = i < call.arguments.size() ? whole_number(call.arguments[i]) : std::nullopt;
    if (!value || *value < 0 || *value > field.max) return error_at_position(call, i, std::string(field.expected));
    values.at(i) = *value;
  }
  if (auto error = no_more_arguments(call, 3, "position, speed and current")) return std::move(*error);
  return Gripper{values[0], values[1], values[2]};
}

struct StatementSpec {
  std::string_view name;
  Bound (*bind)(const Call&);
};

constexpr std::array<StatementSpec, 11> kStatements = {{
    {"MoveJoint", bind_move_joint},
    {"MovePose", bind_move_pose},
    {"MoveCart", bind_move_cart},
    {"MoveCartRelTRF", bind_move_cart_rel_trf},
    {"Delay", bind_delay},
    {"Begin", bind_no_arguments<Begin>},
    {"End", bind_no_arguments<End>},
    {"Loop", bind_no_arguments<Loop>},
    {"Output", bind_output},
    {"Gripper_cal", bind_no_arguments<GripperCalibrate>},
    {"Gripper", bind_gripper},
}};

bool equal_ignoring_case(std::string_view a, std::string_view b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](char x, char y) {
    return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
  });
}

}  // namespace

std::string expected_statement(const Token& found) {
  for (const auto& spec : kStatements) {
    if (equal_ignoring_case(spec.name, found.text)) {
      return std::string(spec.name) + " (statement names are case-sensitive)";
    }
  }
  std::string expected = "a statement: ";
  for (const auto& spec : kStatements) {
    expected += std::string(spec.name) + (&spec == &kStatements.back() ? "" : ", ");
  }
  return expected;
}

std::variant<StatementKind, LineError> bind_statement(const Call& call) {
  for (const auto& spec : kStatements) {
    if (spec.name == call.name.text) return spec.bind(call);
  }
  return error_at(call.name, expected_statement(call.name));
}

}  // namespace robotd::rbtscript::detail
