// A plugin built against a driver ABI robotd does not speak: robotd must refuse it.
#include "robotd/driver/driver.hpp"

extern "C" __attribute__((visibility("default"))) const robotd::driver::PluginInfo* robotd_driver_plugin() {
  static const robotd::driver::PluginInfo info{robotd::driver::kAbiVersion + 1,
                                               static_cast<std::uint32_t>(sizeof(robotd::driver::CommandFrame)),
                                               static_cast<std::uint32_t>(sizeof(robotd::driver::Feedback)),
                                               "wrong_abi",
                                               "0.0.1",
                                               nullptr,
                                               nullptr};
  return &info;
}
