// Finding a device by name among those robotd serves, with an error that lists the known ones.
#pragma once

#include <string>
#include <vector>

#include "robotd/client/client.hpp"

namespace robotctl {

/// The device named `name`, asking robotd for its list (so this also checks robotd answers).
robotd::Result<robotd::DeviceInfo> find_device(robotd::Client& client, const std::string& name);
/// Asks robotd for its devices; when `name` is not empty, fails unless one of them has that name.
robotd::Result<std::vector<robotd::DeviceInfo>> list_devices_including(robotd::Client& client, const std::string& name);

}  // namespace robotctl
