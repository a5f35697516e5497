// The tool's registers (124–130): the Modbus RTU passthrough to the tool's RS-485 bus, where the
// xArm gripper answers as device 8, and the direct register accesses of the tool board (host id
// 9: the bus's baud rate, digital and analog IO) and of the gripper.
#include <cmath>
#include <string>

#include <spdlog/spdlog.h>

#include "controller.hpp"

namespace robotd::xarm::sim {
namespace {

// The tool board's registers (host id 9) that the SDK reads and writes around the gripper.
constexpr std::uint16_t kBaudRateWriteAddress = 0x1A0B;  // the write address of kToolBaudRateAddress
constexpr std::uint16_t kSoftReboot = 0x0607;
constexpr std::uint16_t kDigitalIn = 0x0A14;
constexpr std::uint16_t kDigitalOut = 0x0A15;
constexpr std::uint16_t kAnalogIn1 = 0x0A16;
constexpr std::uint16_t kAnalogIn2 = 0x0A17;

}  // namespace

Controller::Outcome Controller::tool_modbus(const Request& request) {
  const auto parsed = parse_tool_modbus_request(request.frame.body);
  if (!parsed) return parameter_error(request, parsed.error().message);
  const ToolModbusRequest& modbus = parsed.value();
  if (modbus.host_id != kToolHostId) {
    return parameter_error(request, "host id " + std::to_string(modbus.host_id) + " is not the tool board's (9)");
  }
  if (modbus.slave != kGripperId) {
    if (!options_.quiet)
      spdlog::info("tool_modbus_rtu: no device {} on the tool's bus (only the gripper, 8)", modbus.slave);
    return failed();
  }
  return answer(gripper_.modbus(modbus));
}

Controller::Outcome Controller::tool_gpio_error(const Request& /*request*/) {
  return answer(Bytes{0, static_cast<std::uint8_t>(gripper_.error())});
}

Controller::Outcome Controller::tool_read(const Request& request) {
  const auto parsed = parse_tool_register_access(request.frame.reg, request.frame.body);
  if (!parsed) return parameter_error(request, parsed.error().message);
  const ToolRegisterAccess& access = parsed.value();
  const bool wide = request.frame.reg == number(Register::kToolRead32);
  std::optional<std::int32_t> value;
  if (access.id == kGripperId) {
    const auto high = gripper_.read(access.address);
    const auto low =
        wide ? gripper_.read(static_cast<std::uint16_t>(access.address + 1)) : std::optional<std::uint16_t>(0);
    if (high && low) {
      value = wide ? static_cast<std::int32_t>((static_cast<std::uint32_t>(*high) << 16) | *low)
                   : static_cast<std::int32_t>(*high);
    }
  } else if (access.id == kToolHostId && !wide) {
    switch (access.address) {
      case kToolBaudRateAddress:
        value = tool_baud_index_;
        break;
      case kDigitalOut:
        value = tool_digital_out_;
        break;
      case kDigitalIn:
      case kAnalogIn1:
      case kAnalogIn2:
        value = 0;  // nothing is wired to the tool's inputs
        break;
      default:
        break;
    }
  }
  if (!value) {
    if (!options_.quiet) {
      spdlog::info("{}: device {} has no register {:#06x}", register_name(request.frame.reg), access.id,
                   access.address);
    }
    return failed();
  }
  return answer(encode_tool_register_value(*value));
}

Controller::Outcome Controller::tool_write(const Request& request) {
  const auto parsed = parse_tool_register_access(request.frame.reg, request.frame.body);
  if (!parsed) return parameter_error(request, parsed.error().message);
  const ToolRegisterAccess& access = parsed.value();
  const bool wide = request.frame.reg == number(Register::kToolWrite32);
  const auto value = static_cast<std::int32_t>(std::lround(access.value));
  bool written = false;
  if (access.id == kGripperId) {
    written =
        wide ? gripper_.write(access.address, static_cast<std::uint16_t>(static_cast<std::uint32_t>(value) >> 16)) &&
                   gripper_.write(static_cast<std::uint16_t>(access.address + 1),
                                  static_cast<std::uint16_t>(value & 0xFFFF))
             : gripper_.write(access.address, static_cast<std::uint16_t>(value));
  } else if (access.id == kToolHostId && !wide) {
    if (access.address == kBaudRateWriteAddress && value >= 0 && value < static_cast<int>(kToolBaudRates.size())) {
      tool_baud_index_ = value;
      written = true;
    } else if (access.address == kDigitalOut) {
      tool_digital_out_ = value;
      written = true;
    } else {
      written = access.address == kSoftReboot;  // the board restarts at once: nothing to do here
    }
  }
  if (!written) {
    if (!options_.quiet) {
      spdlog::info("{}: device {} refused {} at register {:#06x}", register_name(request.frame.reg), access.id, value,
                   access.address);
    }
    return failed();
  }
  return Outcome{};
}

}  // namespace robotd::xarm::sim
