// Loads the built plugin module the way robotd does: dlopen, then the one entry symbol.
#include <dlfcn.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "robotd/driver/driver.hpp"

namespace robotd::driver {
namespace {

class SimPluginTest : public ::testing::Test {
 protected:
  void SetUp() override {
    handle_ = dlopen(ROBOTD_SIM_PLUGIN_PATH, RTLD_NOW | RTLD_LOCAL);
    ASSERT_NE(handle_, nullptr) << dlerror();
    void* symbol = dlsym(handle_, kPluginEntrySymbol);
    ASSERT_NE(symbol, nullptr) << dlerror();
    // dlsym returns functions as object pointers; POSIX guarantees the conversion.
    const auto entry = reinterpret_cast<PluginEntry>(symbol);  // NOLINT(cppcoreguidelines-pro-type-reinterpret-cast)
    info_ = entry();
    ASSERT_NE(info_, nullptr);
  }

  void TearDown() override {
    if (handle_ != nullptr) dlclose(handle_);
  }

  void* handle_ = nullptr;
  const PluginInfo* info_ = nullptr;
};

TEST_F(SimPluginTest, EntryReportsMatchingAbiNameAndStructSizes) {
  EXPECT_EQ(info_->abi_version, kAbiVersion);
  EXPECT_EQ(info_->command_frame_size, sizeof(CommandFrame));
  EXPECT_EQ(info_->feedback_size, sizeof(Feedback));
  EXPECT_STREQ(info_->name, "sim");
  EXPECT_STRNE(info_->version, "");
}

TEST_F(SimPluginTest, CreatedDriverRunsThroughTheInterfaceAndIsDestroyed) {
  Driver* driver = info_->create();
  ASSERT_NE(driver, nullptr);
  const Result<void> configured = driver->configure(nlohmann::json{{"joint_count", 23}, {"imu", true}});
  EXPECT_TRUE(configured.ok()) << configured.error().message;
  EXPECT_EQ(driver->describe().joints.size(), 23u);
  EXPECT_TRUE(driver->connect().ok());
  Feedback feedback;
  FaultInfo fault;
  EXPECT_EQ(driver->read(feedback, fault), IoResult::kOk);
  EXPECT_EQ(feedback.joint_count, 23u);
  EXPECT_TRUE(feedback.has_imu);
  driver->disconnect();
  info_->destroy(driver);
}

}  // namespace
}  // namespace robotd::driver
