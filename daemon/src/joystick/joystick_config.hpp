// The joystick source's configuration (config key "joystick"): which device, which Linux
// interface, where to publish, and how the controller's axes and buttons become the fields of
// robotd_msgs/Joy. The defaults are the Xbox / Logitech F710 (XInput) layout of the kernel's
// xpad driver, for both interfaces.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "robotd/driver/json_reader.hpp"

namespace robotd::joystick {

enum class Interface {
  kJs,     // /dev/input/jsN: struct js_event, axes and buttons numbered by the kernel
  kEvdev,  // /dev/input/eventN: struct input_event, EV_ABS / EV_KEY codes
};

/// How a Joy field scales its axis: a stick or d-pad is centred (-1..1), a trigger is 0..1.
enum class FieldKind { kStick, kTrigger, kDpad, kButton };

struct JoyFieldSpec {
  std::string_view name;  // the Joy field and its config key
  FieldKind kind;
};

inline constexpr std::size_t kJoyFieldCount = 19;
/// The Joy fields in message order (header, last, is not a field here).
extern const std::array<JoyFieldSpec, kJoyFieldCount> kJoyFields;

/// Where one Joy field's value comes from.
struct FieldSource {
  enum class Kind {
    kNone,        // always 0
    kAxis,        // an axis: js axis number or evdev ABS_* code
    kButton,      // a button: js button number or evdev KEY/BTN_* code
    kButtonPair,  // for axis fields: `code` pressed = +1, `negative_code` pressed = -1 (d-pads reported as buttons)
  };
  Kind kind = Kind::kNone;
  int code = 0;
  int negative_code = 0;
  bool invert = false;  // axis: negate (stick, d-pad) or flip (trigger: 1 - value)
  // evdev only: the raw range, overriding what the device reports (EVIOCGABS).
  std::optional<int> min;
  std::optional<int> max;
};

struct JoystickConfig {
  bool enabled = true;
  std::string device = "/dev/input/js0";
  Interface interface = Interface::kJs;
  std::string topic = "joy";  // ROS name; DDS topic "rt/" + topic
  int rate_hz = 50;           // periodic publications while the device is present; 0 = on change only
  double deadzone = 0.05;     // of sticks and triggers, as a fraction of full scale
  std::array<FieldSource, kJoyFieldCount> mapping{};
};

/// The Xbox / F710 layout for `interface`.
std::array<FieldSource, kJoyFieldCount> default_mapping(Interface interface);

/// Reads the "joystick" object; problems go to `errors` with their key path ("joystick.mapping.lt.axis: ...").
JoystickConfig read_joystick_config(JsonReader& reader, std::vector<std::string>& errors);

/// "ABS_X" → 0, "BTN_SOUTH" → 0x130, ...: the evdev codes a mapping may name; nullopt if unknown.
std::optional<int> evdev_code(std::string_view name);

}  // namespace robotd::joystick
