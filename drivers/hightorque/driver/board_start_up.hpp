// The start-up the livelybot board SDK performs on each port before it commands motors
// (robot.cc, canport.cc): tell the board how many motors the port has and read its firmware
// (0x05), restart its CAN-FD controllers on firmware 4.1 and later (0x0E, three times), read every
// motor's firmware (0x0B), and set the board's function version from the lowest of them (0x0C).
// Runs at connect, on the caller's thread (never the RT loop): it blocks, allocates and retries,
// each step bounded by `timeout`. Internal to the driver.
#pragma once

#include <array>
#include <chrono>
#include <span>

#include "codec/hightorque_codec.hpp"
#include "robotd/driver/abort_flag.hpp"
#include "robotd/result.hpp"
#include "robotd/transport/serial_port.hpp"

namespace robotd::hightorque {

/// What a port's start-up found.
struct BoardSetup {
  BoardFirmware firmware;
  BoardFunction function = BoardFunction::kV5;
  std::array<FirmwareVersion, kMaxMotorId + 1> motor_firmware{};  // by motor id
};

/// Runs the start-up for the motors `motor_ids` (ascending, 1…kMaxMotorId) on an open board
/// port. An error names the step the board or a motor did not answer, or why robotd cannot drive
/// what answered (board firmware before 4.0, motor firmware before 4.2.0, firmware-5 motors
/// mixed with others). `abort` ends the waiting at once (an e-stop or shutdown).
Result<BoardSetup> start_up_board(transport::SerialPort& port, std::span<const int> motor_ids,
                                  std::chrono::milliseconds timeout, const driver::AbortFlag& abort);

}  // namespace robotd::hightorque
