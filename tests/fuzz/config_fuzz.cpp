// The config loader (daemon/src/config) on any file content: JSON with comments, validated
// completely. It must answer with a config or an error that lists what is wrong, never crash or
// throw; a config it accepts must have at least one device and unique device names.
//
// Input: the file's text.
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>
#include <string_view>

#include "config/config.hpp"
#include "fuzz_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const auto config = robotd::config::parse_config(text, "fuzz.json");
  if (!config) {
    FUZZ_CHECK(!config.error().message.empty());
    return 0;
  }
  FUZZ_CHECK(!config.value().devices.empty());
  std::set<std::string> names;
  for (const auto& device : config.value().devices) FUZZ_CHECK(names.insert(device.name).second);
  return 0;
}
