// RBTscript's Output / Gripper_cal / Gripper as each driver's device_call op (no robotd): the
// devices are described as /list_devices would.
#include "robotd/motion/device_io.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace robotd::motion {
namespace {

DeviceInfo device(const std::string& name, const std::string& driver, std::vector<std::string> ops) {
  DeviceInfo info;
  info.name = name;
  info.driver = driver;
  info.ops = std::move(ops);
  return info;
}

DeviceInfo parol6() {
  return device("arm", "parol6",
                {"home: home every joint [needs free motors]", "output: set the isolated outputs",
                 "gripper: move the SSG-48 gripper", "gripper_calibrate: calibrate and activate the gripper"});
}

DeviceInfo piper() {
  DeviceInfo info = device("left", "piper", {"gripper: GripperCtrl [needs free motors]"});
  info.joint_names = {"joint1", "gripper"};
  info.position_min = {-2.6, 0.0};
  info.position_max = {2.6, 0.07};
  return info;
}

nlohmann::json args(const Result<DeviceCall>& call) {
  EXPECT_TRUE(call) << call.error().message;
  return call ? nlohmann::json::parse(call.value().args_json) : nlohmann::json();
}

std::string error(const Result<DeviceCall>& call) {
  EXPECT_FALSE(call);
  return call ? "" : call.error().message;
}

TEST(DeviceIoTest, Parol6DoesEveryStatementWithItsOwnOps) {
  const DeviceIo io(parol6());
  const auto out = io.output(2, true);
  EXPECT_EQ(out.value().op, "output");
  EXPECT_EQ(args(out), (nlohmann::json{{"out2", true}}));
  EXPECT_FALSE(out.value().needs_free_motors);
  EXPECT_EQ(args(io.output(1, false)), (nlohmann::json{{"out1", false}}));
  EXPECT_EQ(io.gripper_calibrate().value().op, "gripper_calibrate");
  const auto grip = io.gripper({.position = 200, .speed = 100, .current_ma = 800});
  EXPECT_EQ(grip.value().op, "gripper");
  EXPECT_EQ(args(grip), (nlohmann::json{{"position", 200}, {"speed", 100}, {"current_a", 0.8}}));
  EXPECT_EQ(grip.value().note, "");
}

TEST(DeviceIoTest, AnOutputTheArmDoesNotHaveNamesTheDeviceAndWhatItHas) {
  EXPECT_EQ(
      error(DeviceIo(parol6()).output(3, true)),
      "device 'arm' (driver parol6) cannot do Output(3, HIGH): the PAROL6 has outputs 1 and 2 (OUT1, OUT2), not 3");
}

TEST(DeviceIoTest, GripperValuesOutOfRangeAreRefusedBeforeAnyMapping) {
  const auto call = DeviceIo(parol6()).gripper({.position = 256, .speed = 0, .current_ma = 0});
  ASSERT_FALSE(call);
  EXPECT_EQ(call.error().code, ErrorCode::kInvalidArgument);
  EXPECT_EQ(call.error().message,
            "Gripper(256, 0, 0): position 256 is out of range: expected 0..255 (0 open, 255 closed)");
  EXPECT_EQ(error(DeviceIo(parol6()).gripper({.position = 0, .speed = 0, .current_ma = 1301})),
            "Gripper(0, 0, 1301): current 1301 is out of range: expected 0..1300 mA");
}

TEST(DeviceIoTest, PiperGripperSpreadsThePositionOverItsStrokeAndTheCurrentOverItsTorque) {
  const DeviceIo io(piper());
  const auto open = io.gripper({.position = 0, .speed = 50, .current_ma = 1300});
  EXPECT_EQ(open.value().op, "gripper");
  EXPECT_TRUE(open.value().needs_free_motors);
  EXPECT_NEAR(args(open)["stroke_m"].get<double>(), 0.07, 1e-12);
  EXPECT_NEAR(args(open)["effort_nm"].get<double>(), 5.0, 1e-12);
  EXPECT_NE(open.value().note.find("speed is not used"), std::string::npos);
  EXPECT_NEAR(args(io.gripper({.position = 255, .speed = 0, .current_ma = 260}))["stroke_m"].get<double>(), 0.0, 1e-12);
  EXPECT_EQ(error(io.output(1, true)),
            "device 'left' (driver piper) cannot do Output(1, HIGH): the piper driver has no "
            "digital outputs");
  EXPECT_NE(error(io.gripper_calibrate()).find("cannot do Gripper_cal(): the PiPER gripper has no calibration"),
            std::string::npos);
}

TEST(DeviceIoTest, PiperWithoutAGripperJointSaysSo) {
  DeviceInfo info = piper();
  info.joint_names = {"joint1"};
  EXPECT_EQ(error(DeviceIo(info).gripper({.position = 0, .speed = 0, .current_ma = 0})),
            "device 'left' (driver piper) cannot do Gripper(0, 0, 0): it has no joint \"gripper\" (configured with "
            "\"gripper\": false?)");
}

TEST(DeviceIoTest, XarmGripperTakesPulsesAndRpm) {
  const DeviceIo io(device("xarm", "xarm", {"gripper_enable: switch it on", "gripper_set_position: move it"}));
  EXPECT_EQ(args(io.gripper({.position = 0, .speed = 255, .current_ma = 0})),
            (nlohmann::json{{"position", 850}, {"speed_rpm", 5000}}));
  const auto closed = io.gripper({.position = 255, .speed = 0, .current_ma = 500});
  EXPECT_EQ(closed.value().op, "gripper_set_position");
  EXPECT_EQ(args(closed), (nlohmann::json{{"position", 0}, {"speed_rpm", 1}}));
  const auto enable = io.gripper_calibrate();
  EXPECT_EQ(enable.value().op, "gripper_enable");
  EXPECT_EQ(args(enable), (nlohmann::json{{"enable", true}}));
  EXPECT_NE(error(io.output(1, true)).find("the xarm driver has no digital output op"), std::string::npos);
}

TEST(DeviceIoTest, RealmanGripperTakesAnOpening) {
  const DeviceIo io(device("rm", "realman", {"set_gripper_position: move the gripper to an opening"}));
  EXPECT_EQ(args(io.gripper({.position = 0, .speed = 0, .current_ma = 0})), (nlohmann::json{{"position", 1000}}));
  EXPECT_EQ(args(io.gripper({.position = 255, .speed = 0, .current_ma = 0})), (nlohmann::json{{"position", 1}}));
  EXPECT_NE(error(io.gripper_calibrate()).find("the RealMan gripper has no calibration op"), std::string::npos);
}

TEST(DeviceIoTest, ADriverWithoutIoMappingAndAMissingOpAreClearErrors) {
  EXPECT_EQ(error(DeviceIo(device("arm", "sim", {})).output(1, true)),
            "device 'arm' (driver sim) cannot do Output(1, HIGH): Output works on the drivers parol6, piper, xarm, "
            "realman");
  EXPECT_EQ(error(DeviceIo(device("arm", "parol6", {"state: what the board reports"})).gripper_calibrate()),
            "device 'arm' (driver parol6) cannot do Gripper_cal(): the device does not offer the op gripper_calibrate "
            "(robotctl devices --json lists its ops)");
}

}  // namespace
}  // namespace robotd::motion
