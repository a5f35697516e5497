// The device-level services: list_devices, estop (engage / reset), reset_zero and
// device_call. device_call reaches the driver's vendor ops plus robotd's own per-device ops:
//   recover   {}                 clear a latched fault (driver.recover), joints then hold
//   blackbox  {"fresh": false}   the last black-box capture, or a new one with fresh=true
//   loop_timing {"samples": false, "reset": false}
//                                wake latency / execution / period percentiles over the
//                                statistics window (and every sample), for benchmarks
#pragma once

#include <functional>
#include <memory>
#include <mutex>
#include <vector>

#include "device/black_box.hpp"
#include "device/device.hpp"
#include "robotd/messages.hpp"
#include "service/device_observer.hpp"
#include "service/session_service.hpp"

namespace robotd::service {

class DeviceServices {
 public:
  /// `observers[i]` tells device i's loop state and timing (its state publisher).
  DeviceServices(std::vector<device::Device*> devices, std::vector<device::BlackBox*> black_boxes,
                 std::vector<DeviceObserver*> observers, SessionService& sessions);

  ListDevicesResponse list_devices(const ListDevicesRequest& request) const;
  EstopResponse estop(const EstopRequest& request);
  ResetZeroResponse reset_zero(const ResetZeroRequest& request);
  DeviceCallResponse device_call(const DeviceCallRequest& request);

  /// robotd's own device_call ops, as listed in DeviceInfo.ops.
  static std::vector<std::string> daemon_ops();

 private:
  DeviceCallResponse daemon_op(std::size_t index, const std::string& op, const nlohmann::json& args);
  bool wait_for_state(std::size_t device, std::uint64_t after_tick, std::chrono::milliseconds timeout,
                      device::LoopState& out) const;

  std::vector<device::Device*> devices_;
  std::vector<device::BlackBox*> black_boxes_;
  SessionService& sessions_;
  std::vector<DeviceObserver*> observers_;
  std::vector<std::unique_ptr<std::mutex>> call_mutexes_;  // one vendor op at a time per driver
};

}  // namespace robotd::service
