// RBTscript's Gripper_cal / Gripper on an xArm through robotd: the xarm driver and
// robotd-xarm-sim's gripper (850 pulses open .. 0 closed), mapped by DeviceIo.
#include <chrono>
#include <cmath>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "robotd/motion/device_io.hpp"
#include "robotd_fixture.hpp"
#include "xarm_sim_process.hpp"

namespace robotd::motion {
namespace {

using namespace std::chrono_literals;
using robotd::testing::RobotdTest;
using robotd::testing::XarmSimProcess;

class DeviceIoXarmTest : public RobotdTest {
 protected:
  void SetUp() override {
    const nlohmann::json params{{"model", "xarm6"},
                                {"host", "127.0.0.1"},
                                {"port", sim_.port()},
                                {"report", {{"kind", "real"}, {"port", sim_.report_port()}}}};
    start_with_device(vendor_device("xarm", params), /*with_sim_arm=*/false);
    auto devices = client().list_devices();
    ASSERT_TRUE(devices) << devices.error().message;
    io_.emplace(devices.value().at(0));
  }
  void run(const Result<DeviceCall>& call) {
    ASSERT_TRUE(call) << call.error().message;
    const auto result = io_->run(client(), call.value());
    EXPECT_TRUE(result) << result.error().message;
  }
  // Whether the gripper reaches `pulses` (within 5) in 10 s; it reports its position in pulses.
  bool reaches(double pulses) {
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    while (std::chrono::steady_clock::now() < deadline) {
      if (std::fabs(call_device("xarm", "gripper_get_position")["position"].get<double>() - pulses) <= 5) return true;
      std::this_thread::sleep_for(50ms);
    }
    return false;
  }

  XarmSimProcess sim_{{"--quiet"}};
  std::optional<DeviceIo> io_;
};

TEST_F(DeviceIoXarmTest, GripperCalibrateEnablesTheGripperAndGripperMovesItInPulses) {
  run(io_->gripper_calibrate());
  run(io_->gripper({.position = 0, .speed = 255, .current_ma = 0}));
  EXPECT_TRUE(reaches(850)) << "the gripper did not open";
  run(io_->gripper({.position = 255, .speed = 255, .current_ma = 0}));
  EXPECT_TRUE(reaches(0)) << "the gripper did not close";
}

TEST_F(DeviceIoXarmTest, OutputIsAClearErrorOnAnXarm) {
  const auto call = io_->output(1, true);
  ASSERT_FALSE(call);
  EXPECT_EQ(call.error().message,
            "device 'xarm' (driver xarm) cannot do Output(1, HIGH): the xarm driver has no digital output op");
}

}  // namespace
}  // namespace robotd::motion
