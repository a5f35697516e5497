#include "control/device_model.hpp"

namespace robotd::control {

std::vector<ControlMode> DeviceModel::control_modes() const {
  if (!read_only_reason.empty()) return {};
  if (supports_torque) return {ControlMode::kPosition, ControlMode::kTorque, ControlMode::kMixed};
  return {ControlMode::kPosition};
}

}  // namespace robotd::control
