#include "joystick/joystick_mapper.hpp"

#include <algorithm>
#include <cmath>

namespace robotd::joystick {
namespace {

using Kind = FieldSource::Kind;

constexpr std::int32_t kJsAxisMax = 32767;  // joydev scales every axis to -32767..32767
constexpr std::int32_t kDefaultTriggerMax = 255;
constexpr std::int32_t kDefaultStickMin = -32768;
constexpr std::int32_t kDefaultStickMax = 32767;

float dead_zoned(float value, double deadzone) {
  const double magnitude = std::abs(static_cast<double>(value));
  if (magnitude <= deadzone) return 0.0F;
  return static_cast<float>(std::copysign((magnitude - deadzone) / (1.0 - deadzone), static_cast<double>(value)));
}

bool is_hat(int code) { return code >= ABS_HAT0X && code <= ABS_HAT3Y; }

constexpr std::array<float Joy::*, kJoyFieldCount> kJoyMembers{&Joy::l_horizontal,
                                                               &Joy::l_vertical,
                                                               &Joy::lt,
                                                               &Joy::r_horizontal,
                                                               &Joy::r_vertical,
                                                               &Joy::rt,
                                                               &Joy::dpad_horizontal,
                                                               &Joy::dpad_vertical,
                                                               &Joy::a,
                                                               &Joy::b,
                                                               &Joy::x,
                                                               &Joy::y,
                                                               &Joy::lb,
                                                               &Joy::rb,
                                                               &Joy::back,
                                                               &Joy::start,
                                                               &Joy::center,
                                                               &Joy::l,
                                                               &Joy::r};

}  // namespace

float& joy_field(Joy& joy, std::size_t index) { return joy.*kJoyMembers.at(index); }
float joy_field(const Joy& joy, std::size_t index) { return joy.*kJoyMembers.at(index); }

bool same_values(const Joy& a, const Joy& b) {
  return std::all_of(kJoyMembers.begin(), kJoyMembers.end(),
                     [&](float Joy::*member) { return a.*member == b.*member; });
}

JoystickMapper::JoystickMapper(const JoystickConfig& config)
    : interface_(config.interface), deadzone_(config.deadzone), mapping_(config.mapping) {}

bool JoystickMapper::apply(const js_event& event) {
  const auto type = static_cast<std::uint8_t>(event.type & ~JS_EVENT_INIT);
  if (type == JS_EVENT_AXIS) return on_axis(event.number, event.value);
  if (type == JS_EVENT_BUTTON) return on_button(event.number, event.value != 0);
  return false;
}

bool JoystickMapper::apply(const input_event& event) {
  if (event.type == EV_ABS) return on_axis(event.code, event.value);
  if (event.type == EV_KEY) return on_button(event.code, event.value != 0);  // 2 = autorepeat: still pressed
  return false;
}

void JoystickMapper::set_axis_range(int code, std::int32_t min, std::int32_t max) {
  if (min < max) device_ranges_[code] = Range{min, max};
}

void JoystickMapper::reset() {
  joy_ = Joy{};
  pressed_.clear();
}

std::vector<int> JoystickMapper::mapped_axes() const {
  std::vector<int> codes;
  for (const FieldSource& source : mapping_) {
    if (source.kind == Kind::kAxis) codes.push_back(source.code);
  }
  return codes;
}

std::vector<int> JoystickMapper::mapped_buttons() const {
  std::vector<int> codes;
  for (const FieldSource& source : mapping_) {
    if (source.kind == Kind::kButton || source.kind == Kind::kButtonPair) codes.push_back(source.code);
    if (source.kind == Kind::kButtonPair) codes.push_back(source.negative_code);
  }
  return codes;
}

bool JoystickMapper::on_axis(int code, std::int32_t value) {
  bool changed = false;
  for (std::size_t i = 0; i < kJoyFieldCount; ++i) {
    const FieldSource& source = mapping_[i];
    if (source.kind == Kind::kAxis && source.code == code) changed = set_field(i, scale_axis(i, value)) || changed;
  }
  return changed;
}

bool JoystickMapper::on_button(int code, bool pressed) {
  pressed_[code] = pressed;
  bool changed = false;
  for (std::size_t i = 0; i < kJoyFieldCount; ++i) {
    const FieldSource& source = mapping_[i];
    if (source.kind == Kind::kButton && source.code == code) {
      changed = set_field(i, pressed ? 1.0F : 0.0F) || changed;
    } else if (source.kind == Kind::kButtonPair && (source.code == code || source.negative_code == code)) {
      const float value = (pressed_[source.code] ? 1.0F : 0.0F) - (pressed_[source.negative_code] ? 1.0F : 0.0F);
      changed = set_field(i, source.invert ? -value : value) || changed;
    }
  }
  return changed;
}

JoystickMapper::Range JoystickMapper::range_of(std::size_t field) const {
  const FieldSource& source = mapping_[field];
  if (interface_ == Interface::kJs) return Range{-kJsAxisMax, kJsAxisMax};
  if (source.min && source.max) return Range{*source.min, *source.max};
  if (const auto found = device_ranges_.find(source.code); found != device_ranges_.end()) return found->second;
  if (is_hat(source.code)) return Range{-1, 1};
  if (kJoyFields[field].kind == FieldKind::kTrigger) return Range{0, kDefaultTriggerMax};
  return Range{kDefaultStickMin, kDefaultStickMax};
}

float JoystickMapper::scale_axis(std::size_t field, std::int32_t raw) const {
  const FieldSource& source = mapping_[field];
  const Range range = range_of(field);
  const double span = static_cast<double>(range.max) - static_cast<double>(range.min);
  const double value = static_cast<double>(raw);
  if (kJoyFields[field].kind == FieldKind::kTrigger) {
    double pressed = std::clamp((value - range.min) / span, 0.0, 1.0);
    if (source.invert) pressed = 1.0 - pressed;
    return dead_zoned(static_cast<float>(pressed), deadzone_);
  }
  const double centre = (static_cast<double>(range.min) + static_cast<double>(range.max)) / 2.0;
  double deflection = std::clamp((value - centre) / (span / 2.0), -1.0, 1.0);
  if (source.invert) deflection = -deflection;
  if (kJoyFields[field].kind == FieldKind::kDpad) return static_cast<float>(std::round(deflection));
  return dead_zoned(static_cast<float>(deflection), deadzone_);
}

bool JoystickMapper::set_field(std::size_t field, float value) {
  if (value == 0.0F) value = 0.0F;  // an inverted 0 is -0: publish it as 0
  float& current = joy_field(joy_, field);
  if (current == value) return false;
  current = value;
  return true;
}

}  // namespace robotd::joystick
