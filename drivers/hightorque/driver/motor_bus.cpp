#include "driver/motor_bus.hpp"

#include <algorithm>
#include <chrono>
#include <utility>
#include <vector>

#include "driver/motor_bus_factory.hpp"

namespace robotd::hightorque {

transport::CanMessage system_frame(const SystemRequest& request, Width width, const MotorScaling& scaling) noexcept {
  switch (request.kind) {
    case SystemRequest::Kind::kQuery:
      return encode_query(request.motor, Query::kStateTemperature, width);
    case SystemRequest::Kind::kStop: {
      MotorCommand stop;
      stop.mode = Mode::kStop;
      return encode_command(request.motor, stop, width, Query::kStateTemperature, scaling);
    }
    case SystemRequest::Kind::kSetZero:
      return encode_set_zero(request.motor);
    case SystemRequest::Kind::kSaveToFlash:
      return encode_save_to_flash(request.motor);
    case SystemRequest::Kind::kSoftReboot:
      return encode_soft_reboot(request.motor);
    case SystemRequest::Kind::kCommandTimeout:
      return encode_command_timeout(request.motor, static_cast<std::uint16_t>(request.value));
    case SystemRequest::Kind::kInfo:
      return encode_info_request(request.motor, request.info);
  }
  return encode_query(request.motor, Query::kStateTemperature, width);
}

std::unique_ptr<MotorBus> make_motor_bus(const HighTorqueParams& params, std::size_t bus) {
  ScalingById scaling{};
  std::vector<int> ids;
  for (const std::size_t motor : params.motors_on(bus)) {
    scaling[static_cast<std::size_t>(params.motors[motor].id)] = params.motors[motor].scaling;
    ids.push_back(params.motors[motor].id);
  }
  std::ranges::sort(ids);
  const int highest_id = ids.empty() ? 0 : ids.back();
  const BusParams& config = params.buses[bus];
  if (config.kind == BusParams::Kind::kBoard) {
    return make_board_bus(config.serial, scaling, std::move(ids), std::chrono::milliseconds(params.connect_timeout_ms));
  }
  return make_can_fd_bus(config.can, scaling, params.width, highest_id);
}

}  // namespace robotd::hightorque
