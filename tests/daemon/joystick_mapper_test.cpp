// The joystick mapping: js and evdev event streams become Joy values with the documented
// conventions (left and up positive, triggers 0..1, buttons 0/1), dead zone and init events.
#include "joystick/joystick_mapper.hpp"

#include <gtest/gtest.h>

namespace robotd::joystick {
namespace {

constexpr std::int16_t kFull = 32767;

js_event js_axis(std::uint8_t number, std::int16_t value, bool init = false) {
  return js_event{.time = 0,
                  .value = value,
                  .type = static_cast<std::uint8_t>(JS_EVENT_AXIS | (init ? JS_EVENT_INIT : 0)),
                  .number = number};
}

js_event js_button(std::uint8_t number, bool pressed, bool init = false) {
  return js_event{.time = 0,
                  .value = static_cast<std::int16_t>(pressed ? 1 : 0),
                  .type = static_cast<std::uint8_t>(JS_EVENT_BUTTON | (init ? JS_EVENT_INIT : 0)),
                  .number = number};
}

input_event ev(std::uint16_t type, std::uint16_t code, std::int32_t value) {
  return input_event{.time = {}, .type = type, .code = code, .value = value};
}

JoystickConfig config(Interface interface, double deadzone = 0.0) {
  JoystickConfig out;
  out.interface = interface;
  out.deadzone = deadzone;
  out.mapping = default_mapping(interface);
  return out;
}

TEST(JoystickMapper, JsStickLeftAndUpReadPlusOneRightAndDownMinusOne) {
  JoystickMapper mapper(config(Interface::kJs));
  mapper.apply(js_axis(0, -kFull));
  mapper.apply(js_axis(1, -kFull));
  EXPECT_FLOAT_EQ(mapper.joy().l_horizontal, 1.0F);
  EXPECT_FLOAT_EQ(mapper.joy().l_vertical, 1.0F);
  mapper.apply(js_axis(3, kFull));
  mapper.apply(js_axis(4, kFull));
  EXPECT_FLOAT_EQ(mapper.joy().r_horizontal, -1.0F);
  EXPECT_FLOAT_EQ(mapper.joy().r_vertical, -1.0F);
}

TEST(JoystickMapper, JsTriggerReadsZeroReleasedOneFullyPressedAndHalfBetween) {
  JoystickMapper mapper(config(Interface::kJs));
  mapper.apply(js_axis(2, -kFull));
  EXPECT_FLOAT_EQ(mapper.joy().lt, 0.0F);
  mapper.apply(js_axis(5, kFull));
  EXPECT_FLOAT_EQ(mapper.joy().rt, 1.0F);
  mapper.apply(js_axis(5, 0));
  EXPECT_FLOAT_EQ(mapper.joy().rt, 0.5F);
}

TEST(JoystickMapper, JsButtonsFollowTheXboxLayout) {
  JoystickMapper mapper(config(Interface::kJs));
  for (std::uint8_t button = 0; button <= 10; ++button) mapper.apply(js_button(button, true));
  const Joy& joy = mapper.joy();
  for (const float value :
       {joy.a, joy.b, joy.x, joy.y, joy.lb, joy.rb, joy.back, joy.start, joy.center, joy.l, joy.r}) {
    EXPECT_FLOAT_EQ(value, 1.0F);
  }
  mapper.apply(js_button(3, false));
  EXPECT_FLOAT_EQ(mapper.joy().y, 0.0F);
  EXPECT_FLOAT_EQ(mapper.joy().x, 1.0F);
}

TEST(JoystickMapper, JsInitEventsSetTheInitialState) {
  JoystickMapper mapper(config(Interface::kJs));
  EXPECT_TRUE(mapper.apply(js_button(0, true, true)));
  EXPECT_TRUE(mapper.apply(js_axis(1, -kFull, true)));
  EXPECT_FALSE(mapper.apply(js_axis(2, -kFull, true))) << "a released trigger is already 0";
  EXPECT_FLOAT_EQ(mapper.joy().a, 1.0F);
  EXPECT_FLOAT_EQ(mapper.joy().l_vertical, 1.0F);
}

TEST(JoystickMapper, JsDpadReadsPlusOneLeftAndUp) {
  JoystickMapper mapper(config(Interface::kJs, 0.05));
  mapper.apply(js_axis(6, -kFull));
  mapper.apply(js_axis(7, kFull));
  EXPECT_FLOAT_EQ(mapper.joy().dpad_horizontal, 1.0F);
  EXPECT_FLOAT_EQ(mapper.joy().dpad_vertical, -1.0F);
  mapper.apply(js_axis(6, 0));
  EXPECT_FLOAT_EQ(mapper.joy().dpad_horizontal, 0.0F);
  EXPECT_FALSE(std::signbit(mapper.joy().dpad_horizontal)) << "an inverted 0 must read 0, not -0";
}

TEST(JoystickMapper, DeadzoneZeroesSmallDeflectionsAndRescalesTheRest) {
  JoystickMapper mapper(config(Interface::kJs, 0.1));
  mapper.apply(js_axis(0, static_cast<std::int16_t>(-0.08 * kFull)));
  EXPECT_FLOAT_EQ(mapper.joy().l_horizontal, 0.0F);
  mapper.apply(js_axis(0, static_cast<std::int16_t>(-0.55 * kFull)));
  EXPECT_NEAR(mapper.joy().l_horizontal, 0.5F, 1e-4);
  mapper.apply(js_axis(0, -kFull));
  EXPECT_FLOAT_EQ(mapper.joy().l_horizontal, 1.0F);
  mapper.apply(js_axis(2, static_cast<std::int16_t>(-0.9 * kFull)));  // trigger 5 % pressed
  EXPECT_FLOAT_EQ(mapper.joy().lt, 0.0F);
}

TEST(JoystickMapper, ApplyReportsOnlyChanges) {
  JoystickMapper mapper(config(Interface::kJs));
  EXPECT_TRUE(mapper.apply(js_button(4, true)));
  EXPECT_FALSE(mapper.apply(js_button(4, true)));
  EXPECT_FALSE(mapper.apply(js_axis(20, kFull))) << "an unmapped axis changes nothing";
}

TEST(JoystickMapper, EvdevAxesUseTheRangeTheDeviceReports) {
  JoystickMapper mapper(config(Interface::kEvdev));
  mapper.set_axis_range(ABS_Z, 0, 1023);  // an Xbox One trigger
  mapper.set_axis_range(ABS_X, -32768, 32767);
  mapper.apply(ev(EV_ABS, ABS_Z, 1023));
  mapper.apply(ev(EV_ABS, ABS_X, -32768));
  EXPECT_FLOAT_EQ(mapper.joy().lt, 1.0F);
  EXPECT_FLOAT_EQ(mapper.joy().l_horizontal, 1.0F);
  mapper.apply(ev(EV_ABS, ABS_Z, 0));
  EXPECT_FLOAT_EQ(mapper.joy().lt, 0.0F);
}

TEST(JoystickMapper, EvdevWithoutAReportedRangeUsesTheDocumentedDefaults) {
  JoystickMapper mapper(config(Interface::kEvdev));
  mapper.apply(ev(EV_ABS, ABS_RZ, 255));     // trigger 0..255
  mapper.apply(ev(EV_ABS, ABS_HAT0Y, -1));   // hat -1..1, up
  mapper.apply(ev(EV_ABS, ABS_RY, -32768));  // stick -32768..32767, up
  EXPECT_FLOAT_EQ(mapper.joy().rt, 1.0F);
  EXPECT_FLOAT_EQ(mapper.joy().dpad_vertical, 1.0F);
  EXPECT_FLOAT_EQ(mapper.joy().r_vertical, 1.0F);
}

TEST(JoystickMapper, EvdevConfiguredRangeOverridesTheDefault) {
  JoystickConfig configured = config(Interface::kEvdev);
  configured.mapping[2].min = 0;  // lt
  configured.mapping[2].max = 1023;
  JoystickMapper mapper(configured);
  mapper.apply(ev(EV_ABS, ABS_Z, 1023));
  EXPECT_FLOAT_EQ(mapper.joy().lt, 1.0F);
}

TEST(JoystickMapper, EvdevKeysAreButtonsAndAutorepeatStaysPressed) {
  JoystickMapper mapper(config(Interface::kEvdev));
  EXPECT_TRUE(mapper.apply(ev(EV_KEY, BTN_SOUTH, 1)));
  EXPECT_FALSE(mapper.apply(ev(EV_KEY, BTN_SOUTH, 2)));
  EXPECT_FLOAT_EQ(mapper.joy().a, 1.0F);
  mapper.apply(ev(EV_KEY, BTN_MODE, 1));
  mapper.apply(ev(EV_KEY, BTN_THUMBR, 1));
  EXPECT_FLOAT_EQ(mapper.joy().center, 1.0F);
  EXPECT_FLOAT_EQ(mapper.joy().r, 1.0F);
  EXPECT_FALSE(mapper.apply(ev(EV_SYN, SYN_REPORT, 0)));
  mapper.apply(ev(EV_KEY, BTN_SOUTH, 0));
  EXPECT_FLOAT_EQ(mapper.joy().a, 0.0F);
}

TEST(JoystickMapper, DpadReportedAsButtonsMapsThroughAButtonPair) {
  JoystickConfig configured = config(Interface::kEvdev);
  configured.mapping[6] = FieldSource{};  // dpad_horizontal: left +1, right -1
  configured.mapping[6].kind = FieldSource::Kind::kButtonPair;
  configured.mapping[6].negative_code = BTN_DPAD_RIGHT;
  configured.mapping[6].code = BTN_DPAD_LEFT;
  JoystickMapper mapper(configured);
  mapper.apply(ev(EV_KEY, BTN_DPAD_LEFT, 1));
  EXPECT_FLOAT_EQ(mapper.joy().dpad_horizontal, 1.0F);
  mapper.apply(ev(EV_KEY, BTN_DPAD_RIGHT, 1));
  EXPECT_FLOAT_EQ(mapper.joy().dpad_horizontal, 0.0F);
  mapper.apply(ev(EV_KEY, BTN_DPAD_LEFT, 0));
  EXPECT_FLOAT_EQ(mapper.joy().dpad_horizontal, -1.0F);
}

TEST(JoystickMapper, UnmappedFieldStaysZero) {
  JoystickConfig configured = config(Interface::kJs);
  configured.mapping[0] = FieldSource{};  // l_horizontal
  JoystickMapper mapper(configured);
  EXPECT_FALSE(mapper.apply(js_axis(0, kFull)));
  EXPECT_FLOAT_EQ(mapper.joy().l_horizontal, 0.0F);
}

TEST(JoystickMapper, ResetReturnsEveryFieldToNeutral) {
  JoystickMapper mapper(config(Interface::kJs));
  mapper.apply(js_axis(1, -kFull));
  mapper.apply(js_button(0, true));
  mapper.reset();
  EXPECT_TRUE(same_values(mapper.joy(), Joy{}));
}

}  // namespace
}  // namespace robotd::joystick
