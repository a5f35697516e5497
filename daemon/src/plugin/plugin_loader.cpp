#include "plugin/plugin_loader.hpp"

#include <cstdlib>
#include <dlfcn.h>
#include <filesystem>
#include <sstream>
#include <unistd.h>

#if !defined(ROBOTD_PLUGIN_INSTALL_DIR) || !defined(ROBOTD_PLUGIN_SUBDIR)
#error "ROBOTD_PLUGIN_INSTALL_DIR and ROBOTD_PLUGIN_SUBDIR must be defined by the build"
#endif

namespace robotd::plugin {
namespace {

std::string executable_directory() {
  std::error_code error;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", error);
  return error ? std::string() : self.parent_path().string();
}

Error refused(std::string message) { return make_error(ErrorCode::kRefused, std::move(message)); }

}  // namespace

LoadedDriver::LoadedDriver(void* library, const driver::PluginInfo* info, driver::Driver* instance, std::string path)
    : library_(library), info_(info), instance_(instance), path_(std::move(path)) {}

LoadedDriver::~LoadedDriver() {
  info_->destroy(instance_);
  if (library_ != nullptr) dlclose(library_);
}

std::unique_ptr<LoadedDriver> LoadedDriver::built_in(std::unique_ptr<driver::Driver> driver, std::string name) {
  static const driver::PluginInfo kBuiltIn{driver::kAbiVersion,
                                           static_cast<std::uint32_t>(sizeof(driver::CommandFrame)),
                                           static_cast<std::uint32_t>(sizeof(driver::Feedback)),
                                           "built-in",
                                           "built-in",
                                           nullptr,
                                           [](driver::Driver* instance) noexcept { delete instance; }};
  return std::make_unique<LoadedDriver>(nullptr, &kBuiltIn, driver.release(), std::move(name));
}

std::vector<std::string> plugin_search_path(const std::vector<std::string>& config_dirs) {
  std::vector<std::string> path = config_dirs;
  if (const char* env = std::getenv("ROBOTD_PLUGIN_PATH"); env != nullptr) {  // NOLINT(concurrency-mt-unsafe)
    std::stringstream list(env);
    for (std::string dir; std::getline(list, dir, ':');) {
      if (!dir.empty()) path.push_back(dir);
    }
  }
  if (const std::string exe_dir = executable_directory(); !exe_dir.empty()) {
    // The install tree and the build tree both put plugins at <prefix>/<libdir>/robotd/drivers.
    path.push_back((std::filesystem::path(exe_dir) / ".." / ROBOTD_PLUGIN_SUBDIR).lexically_normal().string());
  }
  path.emplace_back(ROBOTD_PLUGIN_INSTALL_DIR);
  return path;
}

std::string plugin_file_name(const std::string& driver_name) { return "librobotd_driver_" + driver_name + ".so"; }

Result<std::unique_ptr<LoadedDriver>> load_driver(const std::string& driver_name,
                                                  const std::vector<std::string>& search_path) {
  const std::string file = plugin_file_name(driver_name);
  for (const auto& dir : search_path) {
    const auto candidate = std::filesystem::path(dir) / file;
    if (std::filesystem::exists(candidate)) return load_driver_file(candidate.string(), driver_name);
  }
  std::string looked;
  for (const auto& dir : search_path) looked += (looked.empty() ? "" : ", ") + dir;
  return refused("driver plugin '" + driver_name + "' not found: looked for " + file + " in " + looked +
                 " (set daemon.plugin_dirs in the config or ROBOTD_PLUGIN_PATH)");
}

Result<std::unique_ptr<LoadedDriver>> load_driver_file(const std::string& path, const std::string& expected_name) {
  void* library = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (library == nullptr) return refused("cannot load driver plugin " + path + ": " + dlerror());  // NOLINT

  const auto close_and_refuse = [&](std::string message) {
    dlclose(library);
    return refused(std::move(message));
  };
  void* symbol = dlsym(library, driver::kPluginEntrySymbol);
  if (symbol == nullptr) {
    return close_and_refuse(path + " is not a robotd driver plugin: it does not export " + driver::kPluginEntrySymbol +
                            "() (use ROBOTD_DRIVER_PLUGIN)");
  }
  const auto entry =
      reinterpret_cast<driver::PluginEntry>(symbol);  // NOLINT(cppcoreguidelines-pro-type-reinterpret-cast)
  const driver::PluginInfo* info = entry();
  if (info == nullptr) return close_and_refuse(path + ": " + driver::kPluginEntrySymbol + "() returned nothing");
  if (info->abi_version != driver::kAbiVersion) {
    return close_and_refuse(path + " was built for driver ABI v" + std::to_string(info->abi_version) +
                            " but this robotd speaks v" + std::to_string(driver::kAbiVersion) +
                            ": rebuild the plugin against this robotd's headers");
  }
  if (info->command_frame_size != sizeof(driver::CommandFrame) || info->feedback_size != sizeof(driver::Feedback)) {
    return close_and_refuse(path + " disagrees with robotd on the RT struct layout (CommandFrame " +
                            std::to_string(info->command_frame_size) + " vs " +
                            std::to_string(sizeof(driver::CommandFrame)) +
                            " bytes): rebuild it against this "
                            "robotd's headers");
  }
  // Only now, with the layout known to match, can the rest of PluginInfo be trusted.
  if (info->name == nullptr || info->version == nullptr || info->create == nullptr || info->destroy == nullptr) {
    return close_and_refuse(path + ": " + driver::kPluginEntrySymbol +
                            "() returned an incomplete PluginInfo (use ROBOTD_DRIVER_PLUGIN)");
  }
  if (expected_name != info->name) {
    return close_and_refuse(path + " calls itself '" + std::string(info->name) + "', not '" + expected_name + "'");
  }
  driver::Driver* instance = info->create();
  if (instance == nullptr) return close_and_refuse(path + ": the plugin failed to create a driver instance");
  return std::make_unique<LoadedDriver>(library, info, instance, path);
}

}  // namespace robotd::plugin
