// A bus of motors on CAN-FD (SocketCAN or the stand-in): one-to-many block frames for the tick's
// commands (six MIT motors per frame), single frames where no block form fits.
#include <algorithm>
#include <array>
#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <utility>

#include "driver/motor_bus_factory.hpp"
#include "robotd/transport/can_transport.hpp"

namespace robotd::hightorque {
namespace {

constexpr std::size_t kMaxBlockFrames = 32;
constexpr int kMaxFramesPerReceive = 512;  // bounds one tick's work even on a flooded bus

class CanFdBus final : public MotorBus {
 public:
  CanFdBus(const transport::CanLinkConfig& config, const ScalingById& scaling, Width width, int highest_id)
      : transport_(transport::make_can_transport(config)), scaling_(scaling), width_(width), highest_id_(highest_id) {}

  Result<void> open(const driver::AbortFlag& /*abort*/) override { return transport_->open(); }
  void close() noexcept override { transport_->close(); }
  std::string describe() const override { return transport_->describe(); }

  BusIo send_commands(std::span<const BlockSlot> commanded, std::span<const int> idle, Query query) noexcept override {
    if (const BusIo sent = send_slots(commanded, query); sent == BusIo::kClosed) return sent;
    std::array<BlockSlot, driver::kMaxJoints> stops;  // a device has at most this many motors
    for (std::size_t i = 0; i < idle.size() && i < stops.size(); ++i) {
      stops[i].motor = idle[i];
      stops[i].command.mode = Mode::kStop;
    }
    return send_slots(std::span(stops).first(std::min(idle.size(), stops.size())), query);
  }

  BusIo send_brake(std::span<const int> motors, Query query) noexcept override {
    std::array<BlockSlot, driver::kMaxJoints> brakes;
    for (std::size_t i = 0; i < motors.size() && i < brakes.size(); ++i) {
      brakes[i].motor = motors[i];
      brakes[i].command.mode = Mode::kBrake;
    }
    return send_slots(std::span(brakes).first(std::min(motors.size(), brakes.size())), query);
  }

  BusIo send_system(const SystemRequest& request) noexcept override {
    return send(system_frame(request, width_, scaling_[static_cast<std::size_t>(request.motor)]));
  }

  BusIo receive(ReplySink& sink) noexcept override {
    transport::CanMessage message;
    for (int i = 0; i < kMaxFramesPerReceive; ++i) {
      switch (transport_->receive(message)) {
        case transport::CanIo::kNone:
          return BusIo::kOk;
        case transport::CanIo::kClosed:
          return BusIo::kClosed;
        case transport::CanIo::kBusError:
          ++frames_dropped_;
          continue;
        case transport::CanIo::kDone:
          break;
      }
      ++frames_received_;
      const auto motor = static_cast<std::size_t>((message.id >> 8) & 0x7F);
      if (const auto reply = decode_reply(message, kMaxMotorId, scaling_[motor])) {
        sink.on_reply(*reply);
      } else {
        ++frames_dropped_;
      }
    }
    return BusIo::kOk;
  }

 private:
  BusIo send(const transport::CanMessage& message) noexcept {
    switch (transport_->send(message)) {
      case transport::CanIo::kDone:
        ++frames_sent_;
        return BusIo::kOk;
      case transport::CanIo::kClosed:
        return BusIo::kClosed;
      default:
        ++frames_dropped_;
        return BusIo::kBusy;
    }
  }

  /// Block frames with every motor of the bus (1…highest id) when the mode has a block form, one
  /// frame per motor otherwise.
  BusIo send_slots(std::span<const BlockSlot> slots, Query query) noexcept {
    if (slots.empty()) return BusIo::kOk;
    std::array<transport::CanMessage, kMaxBlockFrames> frames;
    const std::size_t count = encode_block(slots, query, scaling_, highest_id_, frames);
    BusIo status = BusIo::kOk;
    if (count > 0) {
      for (std::size_t f = 0; f < count; ++f) status = worst(status, send(frames[f]));
      return status;
    }
    for (const BlockSlot& slot : slots) {
      status = worst(status, send(encode_command(slot.motor, slot.command, width_, query,
                                                 scaling_[static_cast<std::size_t>(slot.motor)])));
    }
    return status;
  }

  static BusIo worst(BusIo a, BusIo b) noexcept { return static_cast<int>(a) > static_cast<int>(b) ? a : b; }

  std::unique_ptr<transport::CanTransport> transport_;
  ScalingById scaling_;
  Width width_;
  int highest_id_;
};

}  // namespace

std::unique_ptr<MotorBus> make_can_fd_bus(const transport::CanLinkConfig& config, const ScalingById& scaling,
                                          Width width, int highest_id) {
  return std::make_unique<CanFdBus>(config, scaling, width, highest_id);
}

}  // namespace robotd::hightorque
