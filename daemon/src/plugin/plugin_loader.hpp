// Loads driver plugins: shared libraries named librobotd_driver_<name>.so exporting
// robotd_driver_plugin(). A plugin built for another ABI, or that is not a robotd plugin at
// all, is refused with a message that says what to do about it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "robotd/driver/driver.hpp"
#include "robotd/result.hpp"

namespace robotd::plugin {

/// A driver instance and the library it came from; the driver is destroyed before the
/// library is unloaded.
class LoadedDriver {
 public:
  LoadedDriver(void* library, const driver::PluginInfo* info, driver::Driver* instance, std::string path);
  /// A driver compiled into the program instead of loaded from a plugin (tests that step a
  /// device's loop themselves); `name` stands where a plugin's path would.
  static std::unique_ptr<LoadedDriver> built_in(std::unique_ptr<driver::Driver> driver, std::string name);
  LoadedDriver(const LoadedDriver&) = delete;
  LoadedDriver& operator=(const LoadedDriver&) = delete;
  ~LoadedDriver();

  driver::Driver& driver() { return *instance_; }
  const std::string& path() const { return path_; }
  std::string version() const { return info_->version; }

 private:
  void* library_;
  const driver::PluginInfo* info_;
  driver::Driver* instance_;
  std::string path_;
};

/// Where plugins are looked for, in order: the config's plugin_dirs, $ROBOTD_PLUGIN_PATH
/// (colon-separated), <robotd's directory>/../<libdir>/robotd/drivers, then the install directory.
std::vector<std::string> plugin_search_path(const std::vector<std::string>& config_dirs);

std::string plugin_file_name(const std::string& driver_name);

Result<std::unique_ptr<LoadedDriver>> load_driver(const std::string& driver_name,
                                                  const std::vector<std::string>& search_path);

/// Loads the plugin at exactly `path` (used by load_driver and by tests).
Result<std::unique_ptr<LoadedDriver>> load_driver_file(const std::string& path, const std::string& expected_name);

}  // namespace robotd::plugin
