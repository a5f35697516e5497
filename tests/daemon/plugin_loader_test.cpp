// Loading driver plugins: the real sim plugin loads; a library built for another ABI, with
// another view of the RT structs, without the entry symbol or under another name is refused
// with a message that says what to do.
#include "plugin/plugin_loader.hpp"

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace robotd::plugin {
namespace {

using ::testing::ElementsAre;
using ::testing::EndsWith;
using ::testing::HasSubstr;

std::string refusal(const Result<std::unique_ptr<LoadedDriver>>& loaded) {
  if (loaded.ok()) {
    ADD_FAILURE() << "plugin was loaded";
    return "";
  }
  EXPECT_EQ(loaded.error().code, ErrorCode::kRefused);
  return loaded.error().message;
}

// Sets (or unsets) an environment variable for one test and restores it afterwards.
class ScopedEnvironment {
 public:
  ScopedEnvironment(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) saved_ = old;  // NOLINT(concurrency-mt-unsafe)
    if (value != nullptr) {
      setenv(name, value, 1);  // NOLINT(concurrency-mt-unsafe)
    } else {
      unsetenv(name);  // NOLINT(concurrency-mt-unsafe)
    }
  }
  ScopedEnvironment(const ScopedEnvironment&) = delete;
  ScopedEnvironment& operator=(const ScopedEnvironment&) = delete;
  ~ScopedEnvironment() {
    if (saved_) {
      setenv(name_, saved_->c_str(), 1);  // NOLINT(concurrency-mt-unsafe)
    } else {
      unsetenv(name_);  // NOLINT(concurrency-mt-unsafe)
    }
  }

 private:
  const char* name_;
  std::optional<std::string> saved_;
};

// A fresh directory under /tmp for one test, removed afterwards.
class TemporaryDirectory {
 public:
  explicit TemporaryDirectory(const std::string& prefix)
      : path_(std::filesystem::temp_directory_path() / (prefix + "-" + std::to_string(getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  TemporaryDirectory(const TemporaryDirectory&) = delete;
  TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;
  ~TemporaryDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

TEST(PluginLoader, LoadsTheSimPluginAndItsDriverWorks) {
  auto loaded = load_driver_file(ROBOTD_SIM_PLUGIN_PATH, "sim");
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  LoadedDriver& plugin = *loaded.value();
  EXPECT_EQ(plugin.path(), ROBOTD_SIM_PLUGIN_PATH);
  EXPECT_EQ(plugin.version(), "1.0.0");
  const Result<void> configured = plugin.driver().configure(nlohmann::json{{"joint_count", 2}});
  ASSERT_TRUE(configured.ok()) << configured.error().message;
  EXPECT_EQ(plugin.driver().describe().joints.size(), 2u);
}

TEST(PluginLoader, LoadDriverFindsThePluginInTheFirstDirectoryThatHasIt) {
  const std::string sim_dir = std::filesystem::path(ROBOTD_SIM_PLUGIN_PATH).parent_path().string();
  auto loaded = load_driver("sim", {"/nonexistent/robotd-plugins", sim_dir});
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  EXPECT_EQ(std::filesystem::path(loaded.value()->path()), std::filesystem::path(ROBOTD_SIM_PLUGIN_PATH));
}

TEST(PluginLoader, PluginBuiltForAnotherAbiIsRefusedWithAdviceToRebuild) {
  const std::string message = refusal(load_driver_file(ROBOTD_WRONG_ABI_PLUGIN_PATH, "wrong_abi"));
  EXPECT_THAT(message, HasSubstr(ROBOTD_WRONG_ABI_PLUGIN_PATH));
  EXPECT_THAT(message, HasSubstr("built for driver ABI v" + std::to_string(driver::kAbiVersion + 1) +
                                 " but this robotd speaks v" + std::to_string(driver::kAbiVersion)));
  EXPECT_THAT(message, HasSubstr("rebuild the plugin"));
}

TEST(PluginLoader, PluginWithAnotherRtStructLayoutIsRefusedWithAdviceToRebuild) {
  const std::string message = refusal(load_driver_file(ROBOTD_WRONG_STRUCT_SIZE_PLUGIN_PATH, "wrong_struct_size"));
  EXPECT_THAT(message, HasSubstr("disagrees with robotd on the RT struct layout"));
  EXPECT_THAT(message, HasSubstr(std::to_string(sizeof(driver::CommandFrame) + 8) + " vs " +
                                 std::to_string(sizeof(driver::CommandFrame)) + " bytes"));
  EXPECT_THAT(message, HasSubstr("rebuild"));
}

TEST(PluginLoader, LibraryWithoutTheEntrySymbolIsRefusedNamingTheSymbol) {
  const std::string message = refusal(load_driver_file(ROBOTD_NO_ENTRY_PLUGIN_PATH, "no_entry"));
  EXPECT_THAT(message, HasSubstr("is not a robotd driver plugin: it does not export robotd_driver_plugin()"));
}

TEST(PluginLoader, PluginCallingItselfByAnotherNameIsRefused) {
  EXPECT_THAT(refusal(load_driver_file(ROBOTD_SIM_PLUGIN_PATH, "piper")), HasSubstr("calls itself 'sim', not 'piper'"));
}

TEST(PluginLoader, FileThatIsNotASharedLibraryIsRefused) {
  const std::string not_a_library = ROBOTD_SOURCE_DIR "/config/robotd.json";
  EXPECT_THAT(refusal(load_driver_file(not_a_library, "sim")), HasSubstr("cannot load driver plugin " + not_a_library));
}

TEST(PluginLoader, UnknownDriverIsReportedWithEveryDirectorySearched) {
  const std::string message =
      refusal(load_driver("nosuch", {"/nonexistent/first", "/nonexistent/second", "/nonexistent/third"}));
  EXPECT_THAT(message, HasSubstr("driver plugin 'nosuch' not found"));
  EXPECT_THAT(message, HasSubstr("librobotd_driver_nosuch.so"));
  EXPECT_THAT(message, HasSubstr("/nonexistent/first, /nonexistent/second, /nonexistent/third"));
  EXPECT_THAT(message, HasSubstr("ROBOTD_PLUGIN_PATH"));
}

TEST(PluginLoader, PluginFileNameFollowsTheDriverName) {
  EXPECT_EQ(plugin_file_name("piper"), "librobotd_driver_piper.so");
}

TEST(PluginSearchPath, ConfigDirectoriesComeFirstThenThePluginPathEnvironment) {
  const ScopedEnvironment environment("ROBOTD_PLUGIN_PATH", "/env/one::/env/two");
  const std::vector<std::string> path = plugin_search_path({"/cfg/a", "/cfg/b"});
  ASSERT_EQ(path.size(), 6u);  // + next to the executable, + the install directory
  EXPECT_THAT(std::vector<std::string>(path.begin(), path.begin() + 4),
              ElementsAre("/cfg/a", "/cfg/b", "/env/one", "/env/two"));
  EXPECT_THAT(path[4], EndsWith("robotd/drivers"));
  EXPECT_THAT(path[5], EndsWith("robotd/drivers"));
}

TEST(PluginSearchPath, WithoutTheEnvironmentOnlyTheBuiltInDirectoriesFollowTheConfigs) {
  const ScopedEnvironment environment("ROBOTD_PLUGIN_PATH", nullptr);
  const std::vector<std::string> path = plugin_search_path({"/cfg/a"});
  ASSERT_EQ(path.size(), 3u);
  EXPECT_EQ(path[0], "/cfg/a");
  EXPECT_THAT(path[1], EndsWith("robotd/drivers"));
  EXPECT_THAT(path[2], EndsWith("robotd/drivers"));
}

TEST(PluginSearchPath, PluginPathEnvironmentIsSearchedBeforeTheBuiltInDirectories) {
  // A directory of our own holding the sim plugin under its file name (a symlink to the built one).
  const TemporaryDirectory dir("robotd-plugin-path-test");
  const std::filesystem::path link = dir.path() / plugin_file_name("sim");
  std::filesystem::create_symlink(ROBOTD_SIM_PLUGIN_PATH, link);
  const ScopedEnvironment environment("ROBOTD_PLUGIN_PATH",
                                      ("/nonexistent/robotd-plugins:" + dir.path().string()).c_str());
  auto loaded = load_driver("sim", plugin_search_path({}));
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  EXPECT_EQ(loaded.value()->path(), link.string());
}

}  // namespace
}  // namespace robotd::plugin
