// The "joystick" config section: defaults, overrides, and errors that name their key path.
#include <linux/input-event-codes.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "config/config.hpp"

namespace robotd::config {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;
using FieldKind = joystick::FieldSource::Kind;

json with_joystick(const json& joystick) {
  return json{{"devices", json::array({json{{"name", "arm"}, {"driver", "sim"}}})}, {"joystick", joystick}};
}

Result<Config> parse_document(const json& document) { return parse_config(document.dump(), "test.json"); }

std::string joystick_errors(const json& joystick) {
  const Result<Config> result = parse_document(with_joystick(joystick));
  if (result.ok()) {
    ADD_FAILURE() << "config was accepted: " << joystick.dump();
    return "";
  }
  return result.error().message;
}

TEST(JoystickConfig, AbsentSectionMeansNoJoystick) {
  const auto config = parse_document(json{{"devices", json::array({json{{"name", "arm"}, {"driver", "sim"}}})}});
  ASSERT_TRUE(config.ok()) << config.error().message;
  EXPECT_FALSE(config.value().joystick.has_value());
}

TEST(JoystickConfig, EmptySectionIsTheXboxPadOnJs0AtFiftyHertz) {
  const auto config = parse_document(with_joystick(json::object()));
  ASSERT_TRUE(config.ok()) << config.error().message;
  const joystick::JoystickConfig& joy = *config.value().joystick;
  EXPECT_EQ(joy.device, "/dev/input/js0");
  EXPECT_EQ(joy.interface, joystick::Interface::kJs);
  EXPECT_EQ(joy.topic, "joy");
  EXPECT_EQ(joy.rate_hz, 50);
  EXPECT_DOUBLE_EQ(joy.deadzone, 0.05);
  EXPECT_EQ(joy.mapping[2].kind, FieldKind::kAxis);  // lt
  EXPECT_EQ(joy.mapping[2].code, 2);
  EXPECT_EQ(joy.mapping[16].code, 8);  // center = guide
}

TEST(JoystickConfig, DisabledSectionMeansNoJoystick) {
  const auto config = parse_document(with_joystick(json{{"enabled", false}}));
  ASSERT_TRUE(config.ok()) << config.error().message;
  EXPECT_FALSE(config.value().joystick.has_value());
}

TEST(JoystickConfig, EvdevMappingTakesCodeNamesAndRanges) {
  const auto config = parse_document(
      with_joystick(json{{"interface", "evdev"},
                         {"device", "/dev/input/event7"},
                         {"mapping",
                          {{"lt", {{"axis", "ABS_BRAKE"}, {"min", 0}, {"max", 1023}}},
                           {"a", {{"button", "BTN_SOUTH"}}},
                           {"dpad_horizontal", {{"buttons", json::array({"BTN_DPAD_RIGHT", "BTN_DPAD_LEFT"})}}},
                           {"center", nullptr}}}}));
  ASSERT_TRUE(config.ok()) << config.error().message;
  const auto& mapping = config.value().joystick->mapping;
  EXPECT_EQ(mapping[2].code, ABS_BRAKE);
  EXPECT_EQ(mapping[2].max, 1023);
  EXPECT_EQ(mapping[8].code, BTN_SOUTH);
  EXPECT_EQ(mapping[6].kind, FieldKind::kButtonPair);
  EXPECT_EQ(mapping[6].negative_code, BTN_DPAD_RIGHT);
  EXPECT_EQ(mapping[16].kind, FieldKind::kNone);
  EXPECT_EQ(mapping[0].code, ABS_X) << "fields not given keep the default";
}

TEST(JoystickConfig, TopicMayBeGivenAsAnAbsoluteRosName) {
  const auto config = parse_document(with_joystick(json{{"topic", "/hightorque_joy"}}));
  ASSERT_TRUE(config.ok()) << config.error().message;
  EXPECT_EQ(config.value().joystick->topic, "hightorque_joy");
}

TEST(JoystickConfig, TopicWithSpacesIsRefused) {
  EXPECT_THAT(joystick_errors(json{{"topic", "my joy"}}), HasSubstr("joystick.topic: expected a ROS topic name"));
}

TEST(JoystickConfig, EvdevWithoutDeviceIsRefused) {
  EXPECT_THAT(joystick_errors(json{{"interface", "evdev"}}), HasSubstr("joystick.device: missing"));
}

TEST(JoystickConfig, UnknownInterfaceListsTheChoices) {
  EXPECT_THAT(joystick_errors(json{{"interface", "hid"}}),
              HasSubstr("joystick.interface: expected one of \"js\", \"evdev\""));
}

TEST(JoystickConfig, BadAxisIsNamedWithItsPath) {
  EXPECT_THAT(joystick_errors(json{{"mapping", {{"lt", {{"axis", "ABS_Z"}}}}}}),
              HasSubstr("joystick.mapping.lt.axis: expected a js axis number 0..255"));
}

TEST(JoystickConfig, UnknownMappingFieldIsNamedWithItsPath) {
  EXPECT_THAT(joystick_errors(json{{"mapping", {{"l_trigger", {{"axis", 2}}}}}}),
              HasSubstr("joystick.mapping.l_trigger"));
}

TEST(JoystickConfig, ButtonFieldNeedsAButton) {
  EXPECT_THAT(joystick_errors(json{{"mapping", {{"a", {{"axis", 2}}}}}}),
              HasSubstr("joystick.mapping.a.button: missing"));
}

TEST(JoystickConfig, RawRangeIsForEvdevOnly) {
  EXPECT_THAT(joystick_errors(json{{"mapping", {{"lt", {{"axis", 2}, {"min", 0}, {"max", 255}}}}}}),
              HasSubstr("joystick.mapping.lt.min: a raw range is for evdev axes only"));
}

TEST(JoystickConfig, DeadzoneAboveNinetyPercentIsOutOfRange) {
  EXPECT_THAT(joystick_errors(json{{"deadzone", 0.95}}), HasSubstr("joystick.deadzone: expected a number"));
}

}  // namespace
}  // namespace robotd::config
