#include "device_lookup.hpp"

#include <chrono>
#include <utility>

namespace robotd::rbtscript::detail {
namespace {

constexpr std::chrono::milliseconds kJointStateWait{2000};

}  // namespace

Result<DeviceInfo> find_device(Client& client, const std::string& name) {
  auto devices = client.list_devices();
  if (!devices) return devices.error();
  std::string names;
  for (const DeviceInfo& device : devices.value()) {
    if (device.name == name || (name.empty() && devices.value().size() == 1)) return device;
    names += (names.empty() ? "" : ", ") + device.name;
  }
  if (name.empty()) return Error{ErrorCode::kInvalidArgument, "robotd runs several devices (" + names + "); name one"};
  return Error{ErrorCode::kInvalidArgument, "robotd has no device '" + name + "' (it has: " + names + ")"};
}

Result<motion::Joints> measured_joints(Client& client, const DeviceInfo& device, std::size_t arm_joints) {
  auto state = client.next_joint_state(device.name, kJointStateWait);
  if (!state) return state.error();
  if (state.value().position.size() != device.joint_names.size()) {
    return Error{ErrorCode::kRefused, "device '" + device.name + "' published " +
                                          std::to_string(state.value().position.size()) + " joint positions for " +
                                          std::to_string(device.joint_names.size()) + " joints"};
  }
  motion::Joints joints = std::move(state).value().position;
  joints.resize(arm_joints);
  return joints;
}

}  // namespace robotd::rbtscript::detail
