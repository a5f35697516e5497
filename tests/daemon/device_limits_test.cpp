// A device's limits at run time (Device::narrow_limits, narrow_to_described): they narrow by
// what the driver describes, never widen, and a change that leaves no position range is refused
// whole. The loop's side of the hand-over is in control_loop_test.cpp.
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "device/device.hpp"

namespace robotd::device {
namespace {

using ::testing::HasSubstr;

// A two-joint device whose described limits the test changes, as an op or a reconnect would.
class DescribedDriver final : public driver::Driver {
 public:
  DescribedDriver() {
    for (const char* name : {"j1", "j2"}) {
      driver::JointDescription joint;
      joint.name = name;
      joint.limits.position_min_rad = -2;
      joint.limits.position_max_rad = 2;
      joint.default_kp = 50;
      joint.default_kd = 2;
      description.joints.push_back(joint);
    }
  }
  Result<void> configure(const nlohmann::json& /*params*/) override { return {}; }
  driver::DeviceDescription describe() const override { return description; }
  Result<void> connect() override { return {}; }
  void disconnect() noexcept override {}
  Result<void> recover() override { return {}; }
  Result<void> reset_zero(std::span<const int> /*joints*/) override { return {}; }
  void abort_maintenance() noexcept override {}
  driver::IoResult read(driver::Feedback& /*out*/, driver::FaultInfo& /*fault*/) noexcept override {
    return driver::IoResult::kNoNewData;
  }
  driver::IoResult write(const driver::CommandFrame& /*command*/, driver::FaultInfo& /*fault*/) noexcept override {
    return driver::IoResult::kOk;
  }
  Result<nlohmann::json> call(const std::string& op, const nlohmann::json& /*args*/) override {
    return make_error(ErrorCode::kRefused, "no op " + op);
  }
  driver::Diagnostics diagnostics() const override { return {}; }

  driver::DeviceDescription description;
};

class DeviceLimitsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto owned = std::make_unique<DescribedDriver>();
    driver_ = owned.get();
    config::DeviceConfig config;
    config.path = "devices[0]";
    config.name = "dev";
    config.driver = "described";
    config.realtime = rt::RealtimePolicy::kOff;
    config.reconnect_interval_ms = 0;
    device_ = std::make_unique<Device>(config, plugin::LoadedDriver::built_in(std::move(owned), "described"));
    ASSERT_TRUE(device_->configure());
    ASSERT_TRUE(device_->start(Device::LoopRunner::kCaller));
  }

  std::vector<driver::JointLimits> reported() const {
    std::vector<driver::JointLimits> limits;
    limits.reserve(driver_->description.joints.size());
    for (const auto& joint : driver_->description.joints) limits.push_back(joint.limits);
    return limits;
  }

  DescribedDriver* driver_ = nullptr;
  std::unique_ptr<Device> device_;
};

TEST_F(DeviceLimitsTest, WhatTheDriverDescribesAfterAnOpNarrowsTheDevicesLimits) {
  driver_->description.joints[0].limits.position_max_rad = 0.5;
  driver_->description.joints[1].limits.velocity_max_rad_s = 0.25;
  device_->narrow_to_described();
  const auto limits = device_->limits();
  EXPECT_DOUBLE_EQ((*limits)[0].position_max_rad, 0.5);
  EXPECT_DOUBLE_EQ((*limits)[0].position_min_rad, -2);
  EXPECT_DOUBLE_EQ((*limits)[1].velocity_max_rad_s, 0.25);
  EXPECT_DOUBLE_EQ(device_->model().limits[0].position_max_rad, 2) << "the model keeps what the config gave";
}

TEST_F(DeviceLimitsTest, AWiderDescriptionNeverWidensThem) {
  driver_->description.joints[0].limits.position_max_rad = 0.5;
  device_->narrow_to_described();
  driver_->description.joints[0].limits.position_max_rad = 3;  // e.g. a reconnect to an arm with wider limits
  device_->narrow_to_described();
  EXPECT_DOUBLE_EQ((*device_->limits())[0].position_max_rad, 0.5);
}

TEST_F(DeviceLimitsTest, ANarrowingThatLeavesNoPositionRangeIsRefusedWhole) {
  std::vector<driver::JointLimits> limits = reported();
  limits[0].velocity_max_rad_s = 0.5;
  limits[1].position_min_rad = 2.5;
  const auto refused = device_->narrow_limits(limits, "the test");
  ASSERT_FALSE(refused);
  EXPECT_THAT(refused.error().message, HasSubstr("device 'dev': joint 'j2'"));
  EXPECT_THAT(refused.error().message, HasSubstr("leaves no position range"));
  EXPECT_DOUBLE_EQ((*device_->limits())[0].velocity_max_rad_s, 1.0) << "nothing changes";
}

TEST_F(DeviceLimitsTest, ALimitsSnapshotTakenBeforeANarrowingStaysAsItWas) {
  const auto before = device_->limits();
  driver_->description.joints[0].limits.position_max_rad = 0.5;
  device_->narrow_to_described();
  EXPECT_DOUBLE_EQ((*before)[0].position_max_rad, 2) << "a reader (the command gate) never sees a half-written vector";
  EXPECT_DOUBLE_EQ((*device_->limits())[0].position_max_rad, 0.5);
}

}  // namespace
}  // namespace robotd::device
