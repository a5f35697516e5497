#include "joystick/joystick_config.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <linux/input-event-codes.h>
#include <utility>

namespace robotd::joystick {
namespace {

using Kind = FieldSource::Kind;

constexpr int kMaxJsNumber = 255;  // js_event.number is a byte

struct NamedCode {
  std::string_view name;
  int code;
};

constexpr std::array<NamedCode, 34> kEvdevCodes{{
    {"ABS_X", ABS_X},
    {"ABS_Y", ABS_Y},
    {"ABS_Z", ABS_Z},
    {"ABS_RX", ABS_RX},
    {"ABS_RY", ABS_RY},
    {"ABS_RZ", ABS_RZ},
    {"ABS_THROTTLE", ABS_THROTTLE},
    {"ABS_RUDDER", ABS_RUDDER},
    {"ABS_GAS", ABS_GAS},
    {"ABS_BRAKE", ABS_BRAKE},
    {"ABS_HAT0X", ABS_HAT0X},
    {"ABS_HAT0Y", ABS_HAT0Y},
    {"BTN_SOUTH", BTN_SOUTH},
    {"BTN_A", BTN_A},
    {"BTN_EAST", BTN_EAST},
    {"BTN_B", BTN_B},
    {"BTN_NORTH", BTN_NORTH},
    {"BTN_X", BTN_X},
    {"BTN_WEST", BTN_WEST},
    {"BTN_Y", BTN_Y},
    {"BTN_TL", BTN_TL},
    {"BTN_TR", BTN_TR},
    {"BTN_TL2", BTN_TL2},
    {"BTN_TR2", BTN_TR2},
    {"BTN_SELECT", BTN_SELECT},
    {"BTN_START", BTN_START},
    {"BTN_MODE", BTN_MODE},
    {"BTN_THUMBL", BTN_THUMBL},
    {"BTN_THUMBR", BTN_THUMBR},
    {"BTN_DPAD_UP", BTN_DPAD_UP},
    {"BTN_DPAD_DOWN", BTN_DPAD_DOWN},
    {"BTN_DPAD_LEFT", BTN_DPAD_LEFT},
    {"BTN_DPAD_RIGHT", BTN_DPAD_RIGHT},
    {"BTN_C", BTN_C},
}};

FieldSource source(Kind kind, int code, bool invert = false) {
  FieldSource out;
  out.kind = kind;
  out.code = code;
  out.invert = invert;
  return out;
}
FieldSource axis(int code, bool invert) { return source(Kind::kAxis, code, invert); }
FieldSource button(int code) { return source(Kind::kButton, code); }

std::string code_expectation(Interface interface, bool is_axis) {
  if (interface == Interface::kJs) return "a js " + std::string(is_axis ? "axis" : "button") + " number 0..255";
  return is_axis ? "an ABS_* code 0.." + std::to_string(ABS_MAX) + " or name like \"ABS_X\""
                 : "a key code 0.." + std::to_string(KEY_MAX) + " or BTN_* name like \"BTN_SOUTH\"";
}

std::optional<int> code_from_json(const nlohmann::json& value, Interface interface, bool is_axis) {
  const int max = interface == Interface::kJs ? kMaxJsNumber : (is_axis ? ABS_MAX : KEY_MAX);
  if (value.is_number_integer()) {
    const auto number = value.get<long long>();
    if (number >= 0 && number <= max) return static_cast<int>(number);
  } else if (value.is_string() && interface == Interface::kEvdev) {
    const auto name = value.get<std::string>();
    if (name.starts_with(is_axis ? "ABS_" : "BTN_")) return evdev_code(name);
  }
  return std::nullopt;
}

// An axis or button number (js) or code (evdev, also by name), or nullopt with an error.
std::optional<int> read_code(JsonReader& reader, std::string_view key, Interface interface, bool is_axis) {
  const auto value = reader.raw(key);
  if (!value) return std::nullopt;
  const auto code = code_from_json(*value, interface, is_axis);
  if (!code) reader.error(key, "expected " + code_expectation(interface, is_axis) + ", got " + value->dump());
  return code;
}

std::optional<FieldSource> read_button_pair(JsonReader& reader, Interface interface) {
  const auto value = reader.raw("buttons");
  if (!value) return std::nullopt;
  if (!value->is_array() || value->size() != 2) {
    reader.error("buttons", "expected [negative, positive]: the buttons that give -1 and +1, got " + value->dump());
    return std::nullopt;
  }
  std::array<int, 2> codes{};
  for (std::size_t i = 0; i < 2; ++i) {
    const auto code = code_from_json((*value)[i], interface, false);
    if (!code) {
      reader.error("buttons[" + std::to_string(i) + "]",
                   "expected " + code_expectation(interface, false) + ", got " + (*value)[i].dump());
      return std::nullopt;
    }
    codes.at(i) = *code;
  }
  FieldSource pair = source(Kind::kButtonPair, codes[1]);
  pair.negative_code = codes[0];
  return pair;
}

FieldSource read_field(JsonReader& reader, const JoyFieldSpec& field, Interface interface) {
  FieldSource source;
  if (field.kind == FieldKind::kButton) {
    reader.require("button", code_expectation(interface, false));
    if (const auto code = read_code(reader, "button", interface, false)) source = button(*code);
    reader.finish();
    return source;
  }
  if (reader.has("axis") == reader.has("buttons")) {
    reader.error("axis", "give either \"axis\" or \"buttons\": [negative, positive]");
  }
  if (reader.has("axis")) {
    if (const auto code = read_code(reader, "axis", interface, true)) source = axis(*code, false);
  } else if (auto pair = read_button_pair(reader, interface)) {
    source = *pair;
  }
  source.invert = reader.boolean_or("invert", false);
  if (reader.has("min") || reader.has("max")) {
    if (interface == Interface::kJs || source.kind != Kind::kAxis) {
      reader.error(reader.has("min") ? "min" : "max",
                   "a raw range is for evdev axes only (js axes always span -32767..32767)");
    }
    source.min =
        reader.integer("min", std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::max());
    source.max =
        reader.integer("max", std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::max());
    if (!source.min || !source.max || *source.min >= *source.max) {
      reader.error("max", "give both min and max, min below max");
    }
  }
  reader.finish();
  return source;
}

}  // namespace

const std::array<JoyFieldSpec, kJoyFieldCount> kJoyFields{{
    {"l_horizontal", FieldKind::kStick},
    {"l_vertical", FieldKind::kStick},
    {"lt", FieldKind::kTrigger},
    {"r_horizontal", FieldKind::kStick},
    {"r_vertical", FieldKind::kStick},
    {"rt", FieldKind::kTrigger},
    {"dpad_horizontal", FieldKind::kDpad},
    {"dpad_vertical", FieldKind::kDpad},
    {"a", FieldKind::kButton},
    {"b", FieldKind::kButton},
    {"x", FieldKind::kButton},
    {"y", FieldKind::kButton},
    {"lb", FieldKind::kButton},
    {"rb", FieldKind::kButton},
    {"back", FieldKind::kButton},
    {"start", FieldKind::kButton},
    {"center", FieldKind::kButton},
    {"l", FieldKind::kButton},
    {"r", FieldKind::kButton},
}};

std::optional<int> evdev_code(std::string_view name) {
  const auto* found =
      std::find_if(kEvdevCodes.begin(), kEvdevCodes.end(), [&](const NamedCode& code) { return code.name == name; });
  return found == kEvdevCodes.end() ? std::nullopt : std::optional<int>(found->code);
}

std::array<FieldSource, kJoyFieldCount> default_mapping(Interface interface) {
  // Linux reports left and up as negative; Joy has them positive (sensor_msgs/Joy, REP 103).
  if (interface == Interface::kJs) {
    return {axis(0, true), axis(1, true), axis(2, false), axis(3, true), axis(4, true), axis(5, false), axis(6, true),
            axis(7, true), button(0),     button(1),      button(2),     button(3),     button(4),      button(5),
            button(6),     button(7),     button(8),      button(9),     button(10)};
  }
  return {axis(ABS_X, true),   axis(ABS_Y, true),     axis(ABS_Z, false),    axis(ABS_RX, true), axis(ABS_RY, true),
          axis(ABS_RZ, false), axis(ABS_HAT0X, true), axis(ABS_HAT0Y, true), button(BTN_SOUTH),  button(BTN_EAST),
          button(BTN_X),       button(BTN_Y),         button(BTN_TL),        button(BTN_TR),     button(BTN_SELECT),
          button(BTN_START),   button(BTN_MODE),      button(BTN_THUMBL),    button(BTN_THUMBR)};
}

JoystickConfig read_joystick_config(JsonReader& reader, std::vector<std::string>& errors) {
  JoystickConfig config;
  config.enabled = reader.boolean_or("enabled", config.enabled);
  config.interface =
      reader.string_or("interface", "js", {"js", "evdev"}) == "evdev" ? Interface::kEvdev : Interface::kJs;
  if (config.interface == Interface::kEvdev) {
    reader.require("device", "the evdev node of the controller, e.g. /dev/input/by-id/usb-…-event-joystick");
  }
  config.device = reader.string_or("device", config.device);
  if (config.device.empty()) reader.error("device", "expected a device path, got \"\"");
  config.topic = reader.string_or("topic", config.topic);
  if (config.topic.starts_with('/')) config.topic.erase(0, 1);  // a ROS name may be given absolute
  if (config.topic.empty() || config.topic.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                             "0123456789_/") != std::string::npos) {
    reader.error("topic", "expected a ROS topic name of letters, digits, _ and /, got \"" + config.topic + "\"");
  }
  config.rate_hz = static_cast<int>(reader.integer_or("rate_hz", config.rate_hz, 0, 1000));
  config.deadzone = reader.number_or("deadzone", config.deadzone, {0.0, 0.9});
  config.mapping = default_mapping(config.interface);
  if (auto mapping = reader.object("mapping")) {
    for (std::size_t i = 0; i < kJoyFieldCount; ++i) {
      const JoyFieldSpec& field = kJoyFields[i];
      const auto value = mapping->raw(field.name);
      if (!value) continue;
      if (value->is_null()) {
        config.mapping[i] = FieldSource{};  // unmapped: always 0
        continue;
      }
      if (!value->is_object()) {
        mapping->error(field.name,
                       "expected an object ({\"axis\": …} or {\"button\": …}) or null, got " + value->dump());
        continue;
      }
      JsonReader field_reader(*value, mapping->path_of(field.name), errors);
      config.mapping[i] = read_field(field_reader, field, config.interface);
    }
    mapping->finish();
  }
  reader.finish();
  return config;
}

}  // namespace robotd::joystick
