// Finding a device by name and reading where its joints are: what every run and move starts from.
#pragma once

#include <cstddef>
#include <string>

#include "robotd/client/client.hpp"
#include "robotd/motion/trajectory.hpp"
#include "robotd/result.hpp"

namespace robotd::rbtscript::detail {

/// The device `name` as /list_devices describes it ("" = robotd's only device).
Result<DeviceInfo> find_device(Client& client, const std::string& name);
/// The positions of the device's first `arm_joints` joints (those its arm model has; a PiPER's
/// gripper comes after them) from its next /joint_states sample.
Result<motion::Joints> measured_joints(Client& client, const DeviceInfo& device, std::size_t arm_joints);

}  // namespace robotd::rbtscript::detail
