#include "device_lookup.hpp"

namespace robotctl {
namespace {

robotd::Error unknown_device(const std::string& name, const std::vector<robotd::DeviceInfo>& devices) {
  std::string known;
  for (const auto& device : devices) known += (known.empty() ? "'" : ", '") + device.name + "'";
  return robotd::make_error(robotd::ErrorCode::kRefused,
                            "unknown device '" + name + "' (robotd serves " + (known.empty() ? "none" : known) + ")");
}

}  // namespace

robotd::Result<std::vector<robotd::DeviceInfo>> list_devices_including(robotd::Client& client,
                                                                       const std::string& name) {
  auto devices = client.list_devices();
  if (!devices || name.empty()) return devices;
  for (const auto& device : devices.value()) {
    if (device.name == name) return devices;
  }
  return unknown_device(name, devices.value());
}

robotd::Result<robotd::DeviceInfo> find_device(robotd::Client& client, const std::string& name) {
  auto devices = client.list_devices();
  if (!devices) return devices.error();
  for (auto& device : devices.value()) {
    if (device.name == name) return std::move(device);
  }
  return unknown_device(name, devices.value());
}

}  // namespace robotctl
