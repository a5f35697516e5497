// RBTscript's Output / Gripper_cal / Gripper on a PAROL6 through robotd: the parol6 driver and
// robotd-parol6-sim (its board and SSG-48 gripper), mapped by DeviceIo from the device's
// /list_devices entry, while a session holds the arm as a running program's does.
#include <chrono>
#include <functional>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "parol6_sim_process.hpp"
#include "robotd/motion/device_io.hpp"
#include "robotd_fixture.hpp"

namespace robotd::motion {
namespace {

using namespace std::chrono_literals;
using robotd::testing::Parol6SimProcess;
using robotd::testing::RobotdTest;

class DeviceIoParol6Test : public RobotdTest {
 protected:
  void SetUp() override {
    const nlohmann::json params{{"serial", {{"device", sim_.pty_path()}, {"baud", 3000000}}}};
    start_with_device(vendor_device("parol6", params), /*with_sim_arm=*/false);
    auto devices = client().list_devices();
    ASSERT_TRUE(devices) << devices.error().message;
    ASSERT_EQ(devices.value().size(), 1U);
    io_.emplace(devices.value()[0]);
  }
  // Runs the call robotd must accept: its JSON result.
  nlohmann::json run(const Result<DeviceCall>& call) {
    EXPECT_TRUE(call) << call.error().message;
    if (!call) return nullptr;
    auto result = io_->run(client(), call.value());
    EXPECT_TRUE(result) << result.error().message;
    return result ? nlohmann::json::parse(result.value()) : nlohmann::json();
  }
  // Asks `op` until `holds` is true of its answer (the board reports a change a few frames later).
  bool eventually(const std::string& op, const std::function<bool(const nlohmann::json&)>& holds) {
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    while (std::chrono::steady_clock::now() < deadline) {
      if (holds(call_device("parol6", op))) return true;
      std::this_thread::sleep_for(20ms);
    }
    return false;
  }

  Parol6SimProcess sim_{Parol6SimProcess::unique_path("parol6-io"), {"--homed"}};
  std::optional<DeviceIo> io_;
};

TEST_F(DeviceIoParol6Test, OutputSetsTheBoardsIsolatedOutputs) {
  Session session = acquire_device("parol6");
  EXPECT_EQ(run(io_->output(2, true))["out2"], true);
  EXPECT_TRUE(eventually("io", [](const nlohmann::json& io) { return io["out2"] == true && io["out1"] == false; }));
  EXPECT_EQ(run(io_->output(2, false))["out2"], false);
  EXPECT_TRUE(eventually("io", [](const nlohmann::json& io) { return io["out2"] == false; }));
}

TEST_F(DeviceIoParol6Test, GripperCalibrateThenGripperMovesTheSsg48) {
  Session session = acquire_device("parol6");
  EXPECT_EQ(run(io_->gripper_calibrate())["sent"], "gripper_calibrate");
  EXPECT_TRUE(eventually("gripper_state", [](const nlohmann::json& g) { return g.value("calibrated", false); }));
  const nlohmann::json sent = run(io_->gripper({.position = 200, .speed = 255, .current_ma = 500}));
  EXPECT_EQ(sent["position"], 200);
  EXPECT_EQ(sent["current_a"], 0.5);
  EXPECT_TRUE(eventually("gripper_state", [](const nlohmann::json& g) { return g.value("position", -1) == 200; }));
}

TEST_F(DeviceIoParol6Test, AStatementThePAROL6CannotDoIsAClearError) {
  const auto call = io_->output(3, true);
  ASSERT_FALSE(call);
  EXPECT_EQ(call.error().message,
            "device 'parol6' (driver parol6) cannot do Output(3, HIGH): the PAROL6 has outputs 1 and 2 (OUT1, OUT2), "
            "not 3");
}

}  // namespace
}  // namespace robotd::motion
