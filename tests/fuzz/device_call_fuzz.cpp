// Each driver's device_call ops (Driver::call) with any op name and any args_json, as robotd's
// /device_call service hands them over: parsed by the service's parse_call_arguments, then
// called on a configured driver that has no device (connected only where that needs none: the
// sim driver). Every op must check its arguments and answer, a result or an error with a
// message, without blocking and without throwing; a result must be JSON the service can send
// as is (dump() throws on text that is not UTF-8).
//
// Without a controller, the RealMan and xArm drivers read and check an op's arguments, then
// refuse it as not connected: their argument checks are fuzzed, the requests they would send are
// not (tests/drivers/*/ run those against the simulators).
//
// Input: the driver's name ("sim", "piper", …) on the first line, the op on the second, then
// args_json.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "drivers/driver_factory.hpp"
#include "fuzz_check.hpp"
#include "fuzz_input.hpp"
#include "service/call_arguments.hpp"

namespace {

struct DeviceParams {
  std::string_view driver;
  std::string_view params;
  bool connect;  // connect() needs no device (the simulated robot)
};

// Each driver's params for a device that is not there: links to paths and ports nothing serves.
constexpr std::array<DeviceParams, 6> kDevices{{
    {"sim", R"({"joint_count": 6, "imu": true})", true},
    {"piper", R"({"can": {"transport": "standin", "path": "/nonexistent/robotd-fuzz-piper.sock"}})", false},
    {"parol6", R"({"serial": {"device": "/nonexistent/robotd-fuzz-parol6.tty"}})", false},
    {"realman", R"({"model": "RM65", "host": "127.0.0.1", "port": 9, "push": {"ip": "127.0.0.1", "port": 0}})", false},
    {"xarm", R"({"model": "xarm6", "host": "127.0.0.1", "port": 9, "report": {"kind": "real", "port": 9}})", false},
    {"hightorque", R"({"buses": [{"name": "legs", "can": {"transport": "standin", "path": "/nonexistent/ht.sock"}}],
                      "motors": [{"name": "hip", "bus": "legs", "id": 1}, {"name": "knee", "bus": "legs", "id": 2}]})",
     false},
}};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  robotd::fuzz::FuzzInput input(data, size);
  const std::string_view name = input.line();
  const auto* device =
      std::find_if(kDevices.begin(), kDevices.end(), [&](const DeviceParams& entry) { return entry.driver == name; });
  if (device == kDevices.end()) return 0;
  const std::string op(input.line());
  const auto args = robotd::service::parse_call_arguments(input.rest_text());
  if (!args) {  // the service answers with the message; no driver sees the call
    FUZZ_CHECK(!args.error().message.empty());
    return 0;
  }

  auto driver = robotd::fuzz::make_driver(name);
  FUZZ_CHECK(driver != nullptr);
  FUZZ_CHECK(driver->configure(nlohmann::json::parse(device->params)).ok());
  if (device->connect) FUZZ_CHECK(driver->connect().ok());
  const auto result = driver->call(op, args.value());
  if (result) {
    static_cast<void>(result.value().dump());
  } else {
    FUZZ_CHECK(!result.error().message.empty());
  }
  return 0;
}
