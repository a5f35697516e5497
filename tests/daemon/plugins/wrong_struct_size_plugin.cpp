// A plugin whose view of the RT structs differs from robotd's (built against other headers
// that kept the ABI number): robotd must refuse it rather than exchange misread frames.
#include "robotd/driver/driver.hpp"

extern "C" __attribute__((visibility("default"))) const robotd::driver::PluginInfo* robotd_driver_plugin() {
  static const robotd::driver::PluginInfo info{robotd::driver::kAbiVersion,
                                               static_cast<std::uint32_t>(sizeof(robotd::driver::CommandFrame) + 8),
                                               static_cast<std::uint32_t>(sizeof(robotd::driver::Feedback)),
                                               "wrong_struct_size",
                                               "0.0.1",
                                               nullptr,
                                               nullptr};
  return &info;
}
