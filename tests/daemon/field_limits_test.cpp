// Every string and list a client sends is held to its limit (dds/field_limits.hpp): at the
// limit it passes, one beyond it is named with its length and the limit.
#include "dds/field_limits.hpp"

#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "robotd/limits.hpp"

namespace robotd::dds {
namespace {

// A field of some message, made `length` long, and the check of that message.
struct FieldCase {
  const char* field;
  std::size_t limit;
  std::function<std::optional<Oversize>(std::size_t length)> check;
};

std::string text(std::size_t length) { return std::string(length, 'x'); }
template <class T>
std::vector<T> list(std::size_t length) {
  return std::vector<T>(length);
}

std::vector<FieldCase> every_field() {
  using namespace limits;
  return {
      {"uuid", kUuidBytes,
       [](std::size_t n) {
         ControlCommand m;
         m.uuid = text(n);
         return find_oversize(m);
       }},
      {"device", kDeviceNameBytes,
       [](std::size_t n) {
         ControlCommand m;
         m.device = text(n);
         return find_oversize(m);
       }},
      {"header.frame_id", kFrameIdBytes,
       [](std::size_t n) {
         ControlCommand m;
         m.header.frame_id = text(n);
         return find_oversize(m);
       }},
      {"motor_ids", kJoints,
       [](std::size_t n) {
         ControlCommand m;
         m.motor_ids = list<std::int32_t>(n);
         return find_oversize(m);
       }},
      {"positions", kJoints,
       [](std::size_t n) {
         ControlCommand m;
         m.positions = list<float>(n);
         return find_oversize(m);
       }},
      {"velocities", kJoints,
       [](std::size_t n) {
         ControlCommand m;
         m.velocities = list<float>(n);
         return find_oversize(m);
       }},
      {"kp", kJoints,
       [](std::size_t n) {
         ControlCommand m;
         m.kp = list<float>(n);
         return find_oversize(m);
       }},
      {"kd", kJoints,
       [](std::size_t n) {
         ControlCommand m;
         m.kd = list<float>(n);
         return find_oversize(m);
       }},
      {"torques", kJoints,
       [](std::size_t n) {
         ControlCommand m;
         m.torques = list<float>(n);
         return find_oversize(m);
       }},
      {"node_name", kNodeNameBytes,
       [](std::size_t n) {
         RequestControlRequest m;
         m.node_name = text(n);
         return find_oversize(m);
       }},
      {"device", kDeviceNameBytes,
       [](std::size_t n) {
         RequestControlRequest m;
         m.device = text(n);
         return find_oversize(m);
       }},
      {"motor_ids", kJoints,
       [](std::size_t n) {
         RequestControlRequest m;
         m.motor_ids = list<std::int32_t>(n);
         return find_oversize(m);
       }},
      {"default_kp", kJoints,
       [](std::size_t n) {
         RequestControlRequest m;
         m.default_kp = list<float>(n);
         return find_oversize(m);
       }},
      {"default_kd", kJoints,
       [](std::size_t n) {
         RequestControlRequest m;
         m.default_kd = list<float>(n);
         return find_oversize(m);
       }},
      {"node_name", kNodeNameBytes,
       [](std::size_t n) {
         ReleaseControlRequest m;
         m.node_name = text(n);
         return find_oversize(m);
       }},
      {"uuid", kUuidBytes,
       [](std::size_t n) {
         ReleaseControlRequest m;
         m.uuid = text(n);
         return find_oversize(m);
       }},
      {"node_name", kNodeNameBytes,
       [](std::size_t n) {
         GetAvailableMotorsRequest m;
         m.node_name = text(n);
         return find_oversize(m);
       }},
      {"device", kDeviceNameBytes,
       [](std::size_t n) {
         GetAvailableMotorsRequest m;
         m.device = text(n);
         return find_oversize(m);
       }},
      {"device", kDeviceNameBytes,
       [](std::size_t n) {
         ResetZeroRequest m;
         m.device = text(n);
         return find_oversize(m);
       }},
      {"motor_ids", kJoints,
       [](std::size_t n) {
         ResetZeroRequest m;
         m.motor_ids = list<std::int32_t>(n);
         return find_oversize(m);
       }},
      {"device", kDeviceNameBytes,
       [](std::size_t n) {
         EstopRequest m;
         m.device = text(n);
         return find_oversize(m);
       }},
      {"node_name", kNodeNameBytes,
       [](std::size_t n) {
         ListDevicesRequest m;
         m.node_name = text(n);
         return find_oversize(m);
       }},
      {"device", kDeviceNameBytes,
       [](std::size_t n) {
         DeviceCallRequest m;
         m.device = text(n);
         return find_oversize(m);
       }},
      {"op", kOpBytes,
       [](std::size_t n) {
         DeviceCallRequest m;
         m.op = text(n);
         return find_oversize(m);
       }},
      {"args_json", kArgsJsonBytes,
       [](std::size_t n) {
         DeviceCallRequest m;
         m.args_json = text(n);
         return find_oversize(m);
       }},
  };
}

TEST(FieldLimits, EveryFieldPassesAtItsLimitAndIsNamedOneBeyondIt) {
  for (const FieldCase& field : every_field()) {
    EXPECT_FALSE(field.check(field.limit)) << field.field;
    const std::optional<Oversize> beyond = field.check(field.limit + 1);
    ASSERT_TRUE(beyond) << field.field;
    EXPECT_STREQ(beyond->field, field.field);
    EXPECT_EQ(beyond->length, field.limit + 1);
    EXPECT_EQ(beyond->limit, field.limit);
  }
}

TEST(FieldLimits, TheRefusalSaysWhatWasWrongAndWhatIsExpected) {
  RequestControlRequest request;
  request.node_name = text(1U << 20U);
  request.motor_ids = list<std::int32_t>(70);
  EXPECT_EQ(find_oversize(request)->describe(), "node_name is 1048576 bytes long; the limit is 255 bytes");
  request.node_name = "teleop";
  EXPECT_EQ(find_oversize(request)->describe(), "motor_ids is 70 entries long; the limit is 64 entries");
}

TEST(FieldLimits, AnEstopIsNotRefusedForItsWordsButTheyAreCutAtACharacterBoundary) {
  EstopRequest request;
  request.node_name = "panel";
  request.reason = std::string(254, 'r') + "\xc3\xa9" + "tail";  // 'é' straddles byte 255
  EXPECT_FALSE(find_oversize(request));
  const std::optional<Oversize> cut = cut_to_limits(request);
  ASSERT_TRUE(cut);
  EXPECT_EQ(cut->describe(), "reason is 260 bytes long; the limit is 255 bytes");
  EXPECT_EQ(request.reason, std::string(254, 'r'));
  EXPECT_EQ(request.node_name, "panel");

  request.node_name = text(300);
  EXPECT_STREQ(cut_to_limits(request)->field, "node_name");
  EXPECT_EQ(request.node_name.size(), limits::kNodeNameBytes);
  EXPECT_FALSE(cut_to_limits(request)) << "nothing left to cut";
}

}  // namespace
}  // namespace robotd::dds
