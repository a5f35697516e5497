// The joystick mapper (daemon/src/joystick) on any config the loader accepts and any event
// stream a js or evdev node (or a recorded file, or a FIFO) can deliver, with any axis ranges
// the device reports (EVIOCGABS). After every event each Joy field must hold what its kind
// allows: sticks and d-pads -1 … 1, triggers 0 … 1, buttons 0 or 1; never NaN.
//
// Input: one line of JSON, the "joystick" config object (empty: {}); u8 flags (bit 0: the device
// reports a range for each mapped axis, then i32 LE min, max and value per axis); then the
// events, struct js_event or struct input_event records as read() returns them.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "fuzz_check.hpp"
#include "fuzz_input.hpp"
#include "joystick/joystick_config.hpp"
#include "joystick/joystick_mapper.hpp"

namespace {

using namespace robotd::joystick;
using robotd::Joy;
using robotd::fuzz::FuzzInput;

constexpr std::uint8_t kReportsRanges = 0x01;

void check_joy(const Joy& joy) {
  for (std::size_t i = 0; i < kJoyFieldCount; ++i) {
    const float value = joy_field(joy, i);
    FUZZ_CHECK(std::isfinite(value));
    switch (kJoyFields[i].kind) {
      case FieldKind::kStick:
      case FieldKind::kDpad:
        FUZZ_CHECK(value >= -1.0F && value <= 1.0F);
        break;
      case FieldKind::kTrigger:
        FUZZ_CHECK(value >= 0.0F && value <= 1.0F);
        break;
      case FieldKind::kButton:
        FUZZ_CHECK(value == 0.0F || value == 1.0F);
        break;
    }
  }
}

template <class Event>
void apply_records(JoystickMapper& mapper, std::span<const std::uint8_t> bytes) {
  for (; bytes.size() >= sizeof(Event); bytes = bytes.subspan(sizeof(Event))) {
    Event event{};
    std::memcpy(&event, bytes.data(), sizeof(Event));
    mapper.apply(event);
    check_joy(mapper.joy());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzInput input(data, size);
  const std::string_view line = input.line();
  const nlohmann::json object = line.empty() ? nlohmann::json::object() : nlohmann::json::parse(line, nullptr, false);
  if (!object.is_object()) return 0;
  std::vector<std::string> errors;
  robotd::JsonReader reader(object, "joystick", errors);
  const JoystickConfig config = read_joystick_config(reader, errors);
  if (!errors.empty()) return 0;  // robotd refuses to start

  JoystickMapper mapper(config);
  if ((input.u8() & kReportsRanges) != 0) {
    for (const int code : mapper.mapped_axes()) {
      const std::int32_t min = input.i32_le();
      const std::int32_t max = input.i32_le();
      mapper.set_axis_range(code, min, max);
      mapper.apply(
          input_event{.time = {}, .type = EV_ABS, .code = static_cast<std::uint16_t>(code), .value = input.i32_le()});
      check_joy(mapper.joy());
    }
  }
  if (config.interface == Interface::kJs) {
    apply_records<js_event>(mapper, input.rest());
  } else {
    apply_records<input_event>(mapper, input.rest());
  }
  return 0;
}
