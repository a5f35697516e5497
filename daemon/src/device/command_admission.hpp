// Whether a device takes commands now, as the command intake (and anything that plays it in a
// test) decides before validating one. One home for the rule.
#pragma once

#include <optional>
#include <string>

#include "control/command_validator.hpp"
#include "device/device_channel.hpp"

namespace robotd::device {

struct CommandRefusal {
  control::Rejection reason;
  std::string detail;
};

/// Only a RUNNING device takes commands, and never while its e-stop is engaged: the e-stop is
/// read from the flag the e-stop service sets, because the state the loop publishes lags it
/// by up to a tick.
std::optional<CommandRefusal> command_refusal(const DeviceChannel& channel);

}  // namespace robotd::device
