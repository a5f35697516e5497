// The writing side of a device's command mailbox: the newest target of every joint and each
// session slot's last accepted command, published whole to the RT loop after every accepted
// command (the loop reads only the newest snapshot, so nothing it skips is lost). Owned by the
// single thread that accepts commands.
#pragma once

#include <cstdint>

#include "control/command_validator.hpp"
#include "device/device_channel.hpp"

namespace robotd::device {

class CommandMailbox {
 public:
  explicit CommandMailbox(DeviceChannel& channel) : channel_(channel) {}

  /// Writes an accepted command of the session in `slot` (`generation`) and publishes it.
  /// `received_ns` is when robotd took the command (CLOCK_MONOTONIC), `sent_ns` the sender's
  /// stamp (0 = unknown), `answers_tick` the tick whose state it answers (0 = none).
  void post(std::uint8_t slot, std::uint32_t generation, const control::ValidatedCommand& command,
            std::int64_t received_ns, std::int64_t sent_ns, std::uint64_t answers_tick = 0) noexcept;

 private:
  DeviceChannel& channel_;
  CommandSnapshot working_{};
  std::uint64_t sequence_ = 0;
};

}  // namespace robotd::device
