// Finding a device by name and reading where its joints are: what every run and move starts from.
#pragma once

#include <string>

#include "robotd/client/client.hpp"
#include "robotd/motion/trajectory.hpp"
#include "robotd/result.hpp"

namespace robotd::rbtscript::detail {

/// The device `name` as /list_devices describes it ("" = robotd's only device).
Result<DeviceInfo> find_device(Client& client, const std::string& name);
/// The device's joints' positions from its next /joint_states sample.
Result<motion::Joints> measured_joints(Client& client, const DeviceInfo& device);

}  // namespace robotd::rbtscript::detail
