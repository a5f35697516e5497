// The two kinds of MotorBus and what they share. Internal to the driver.
#pragma once

#include <array>
#include <chrono>
#include <memory>
#include <vector>

#include "driver/motor_bus.hpp"
#include "robotd/transport/can_transport.hpp"
#include "robotd/transport/serial_port.hpp"

namespace robotd::hightorque {

/// Each motor's scaling, indexed by its CAN id (0 and 127 unused).
using ScalingById = std::array<MotorScaling, kBroadcastId + 1>;

/// The CAN-FD frame for a system request.
transport::CanMessage system_frame(const SystemRequest& request, Width width, const MotorScaling& scaling) noexcept;

/// `highest_id`: the highest motor id on the bus (block frames and board slot payloads carry
/// every motor from id 1 to it, as the vendor's SDKs do).
std::unique_ptr<MotorBus> make_can_fd_bus(const transport::CanLinkConfig& config, const ScalingById& scaling,
                                          Width width, int highest_id);
/// `motor_ids`: the port's motors (ascending); open() runs the board start-up for them, each
/// step bounded by `start_up_timeout`.
std::unique_ptr<MotorBus> make_board_bus(const transport::SerialConfig& config, const ScalingById& scaling,
                                         std::vector<int> motor_ids, std::chrono::milliseconds start_up_timeout);

}  // namespace robotd::hightorque
