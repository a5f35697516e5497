// One bus of HighTorque motors as the driver drives it, whatever carries it: CAN-FD frames on
// SocketCAN or the stand-in, or packets to the livelybot USB-CDC CAN board. Every call after
// open() is non-blocking and allocation-free (one system call per frame or packet), so robotd's
// RT thread drives every bus of a device in turn within one tick without waiting on any.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "codec/hightorque_codec.hpp"
#include "driver/hightorque_params.hpp"
#include "robotd/driver/abort_flag.hpp"
#include "robotd/result.hpp"

namespace robotd::hightorque {

enum class BusIo : std::uint8_t {
  kOk,
  kBusy,    // the transmit queue or tty buffer is full: this frame was dropped
  kClosed,  // the link is gone
};

/// A motor-side system command (set zero, timeout, …) for one motor.
struct SystemRequest {
  enum class Kind : std::uint8_t {
    kQuery,  // the motor's state, without changing what it does
    kStop,   // free-wheel (zero torque)
    kSetZero,
    kSaveToFlash,
    kSoftReboot,
    kCommandTimeout,  // `value` ms, 0 disarms
    kInfo,            // `info`
  };
  Kind kind = Kind::kQuery;
  int motor = 0;  // CAN id on the bus
  int value = 0;
  InfoKind info = InfoKind::kFirmwareVersion;
};

/// Where a bus delivers what its motors said.
class ReplySink {
 public:
  virtual void on_reply(const Reply& reply) noexcept = 0;

 protected:
  ~ReplySink() = default;
};

class MotorBus {
 public:
  virtual ~MotorBus() = default;

  /// Opens the link (blocking; the board runs its start-up here); `abort` pre-empts the waiting.
  virtual Result<void> open(const driver::AbortFlag& abort) = 0;
  virtual void close() noexcept = 0;
  /// "stand-in /tmp/legs.sock", "board /dev/ttyACM0", for messages.
  virtual std::string describe() const = 0;

  /// This tick's commands: `commanded` (MIT, motor frame) and `idle` motors (free-wheel), each
  /// motor asked to reply with `query`.
  virtual BusIo send_commands(std::span<const BlockSlot> commanded, std::span<const int> idle,
                              Query query) noexcept = 0;
  /// Every motor of `motors` to BRAKE (phases shorted): the vendor's e-stop.
  virtual BusIo send_brake(std::span<const int> motors, Query query) noexcept = 0;
  virtual BusIo send_system(const SystemRequest& request) noexcept = 0;
  /// Decodes everything received since the last call into `sink`.
  virtual BusIo receive(ReplySink& sink) noexcept = 0;

  std::uint64_t frames_sent() const noexcept { return frames_sent_; }
  std::uint64_t frames_received() const noexcept { return frames_received_; }
  std::uint64_t frames_dropped() const noexcept { return frames_dropped_; }
  std::uint64_t bytes_skipped() const noexcept { return bytes_skipped_; }

 protected:
  std::uint64_t frames_sent_ = 0;
  std::uint64_t frames_received_ = 0;
  std::uint64_t frames_dropped_ = 0;  // transmit full, or undecodable on receive
  std::uint64_t bytes_skipped_ = 0;   // a byte stream's bytes outside any frame (the board's tty)
};

/// The bus `params.buses[bus]` with the motor scalings of its motors (indexed by CAN id).
std::unique_ptr<MotorBus> make_motor_bus(const HighTorqueParams& params, std::size_t bus);

}  // namespace robotd::hightorque
