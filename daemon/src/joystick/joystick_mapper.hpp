// Turns a controller's Linux input events into robotd_msgs/Joy values: the state of every
// mapped axis and button, scaled and dead-zoned. Pure: no I/O, no clock, no DDS.
//
// Scaling: sticks and d-pad -1..1 (after `invert`, which the defaults set so left and up are
// positive), triggers 0 (released) .. 1 (pressed), buttons 0 or 1. The js interface always
// spans -32767..32767; evdev axes span what the device reports (set_axis_range, from
// EVIOCGABS), else the field's configured min/max, else a default: ABS_HAT* -1..1, triggers
// 0..255 (xpad), other axes -32768..32767. The dead zone applies to sticks and triggers: a value
// within it reads 0, and the rest is rescaled so full deflection still reads 1.
#pragma once

#include <array>
#include <cstdint>
#include <linux/input.h>
#include <linux/joystick.h>
#include <map>
#include <vector>

#include "joystick/joystick_config.hpp"
#include "robotd/messages.hpp"

namespace robotd::joystick {

class JoystickMapper {
 public:
  explicit JoystickMapper(const JoystickConfig& config);

  /// An event of the js interface (JS_EVENT_INIT events included). True if the Joy changed.
  bool apply(const js_event& event);
  /// An event of the evdev interface (EV_ABS, EV_KEY; others are ignored). True if the Joy changed.
  bool apply(const input_event& event);
  /// The raw range of evdev axis `code`, as the device reports it (struct input_absinfo).
  void set_axis_range(int code, std::int32_t min, std::int32_t max);
  /// Back to neutral: every field 0 (a lost device, a fresh start).
  void reset();

  /// The current values; header left empty.
  const Joy& joy() const { return joy_; }
  /// The evdev axis and button codes the mapping reads (for querying their state on open).
  std::vector<int> mapped_axes() const;
  std::vector<int> mapped_buttons() const;

 private:
  struct Range {
    std::int32_t min = 0;
    std::int32_t max = 0;
  };
  bool on_axis(int code, std::int32_t value);
  bool on_button(int code, bool pressed);
  float scale_axis(std::size_t field, std::int32_t raw) const;
  Range range_of(std::size_t field) const;
  bool set_field(std::size_t field, float value);

  Interface interface_;
  double deadzone_;
  std::array<FieldSource, kJoyFieldCount> mapping_;
  std::map<int, Range> device_ranges_;  // evdev: what the device reported
  std::map<int, bool> pressed_;         // button code → pressed, for button-pair axes
  Joy joy_;
};

/// Joy fields by index, in message order (kJoyFields).
float& joy_field(Joy& joy, std::size_t index);
float joy_field(const Joy& joy, std::size_t index);
/// Every field equal (headers not compared).
bool same_values(const Joy& a, const Joy& b);

}  // namespace robotd::joystick
