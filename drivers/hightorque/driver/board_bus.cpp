// A bus of motors behind the livelybot USB-CDC CAN board: one tty is one CAN port. open() runs
// the vendor's start-up (board_start_up.hpp), which decides the command and state packets: each
// tick is one 0xB0 slot packet (0x93 where a motor's firmware is older than 4.4.6; position,
// velocity, torque, kp, kd per motor id; a motor not commanded this tick keeps the values it was
// last sent, as in the vendor's SDK); the board answers with a motor-state packet (0x0A, or 0x06
// below function version 4). Port-wide admin packets stand in for the per-motor system commands
// the board does not have (docs/drivers/hightorque.md says which).
#include <algorithm>
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "driver/board_start_up.hpp"
#include "driver/motor_bus_factory.hpp"

namespace robotd::hightorque {
namespace {

constexpr std::size_t kMaxPacket = kBoardHeaderSize + kMaxBoardPayload;
constexpr int kMaxReadsPerReceive = 64;

class BoardBus final : public MotorBus {
 public:
  BoardBus(const transport::SerialConfig& config, const ScalingById& scaling, std::vector<int> motor_ids,
           std::chrono::milliseconds start_up_timeout)
      : port_(config),
        configured_scaling_(scaling),
        scaling_(scaling),
        motor_ids_(std::move(motor_ids)),
        highest_id_(motor_ids_.empty() ? 0 : std::ranges::max(motor_ids_)),
        start_up_timeout_(start_up_timeout),
        slots_(highest_id_) {}

  Result<void> open(const driver::AbortFlag& abort) override {
    if (auto opened = port_.open(); !opened) return opened;
    port_.flush();
    auto setup = start_up_board(port_, motor_ids_, start_up_timeout_, abort);
    if (!setup) {
      port_.close();
      return setup.error();
    }
    apply(setup.value());
    slots_.reset();
    timeouts_.fill(0);
    splitter_ = BoardFrameSplitter{};
    counted_crc_errors_ = 0;
    counted_skipped_bytes_ = 0;
    return {};
  }
  void close() noexcept override { port_.close(); }
  std::string describe() const override { return "board " + port_.describe(); }

  BusIo send_commands(std::span<const BlockSlot> commanded, std::span<const int> /*idle*/,
                      Query /*query*/) noexcept override {
    // With no command at all, a state request keeps the feedback coming.
    if (commanded.empty()) return send_admin(state_request_);
    const std::span<const std::uint8_t> payload = slots_.update(mit_command_, commanded, scaling_);
    if (payload.empty()) {
      ++frames_dropped_;
      return BusIo::kBusy;
    }
    return send_packet(mit_command_, payload);
  }

  BusIo send_brake(std::span<const int> /*motors*/, Query /*query*/) noexcept override {
    return send_admin(BoardCommand::kBrake);
  }

  BusIo send_system(const SystemRequest& request) noexcept override {
    switch (request.kind) {
      case SystemRequest::Kind::kQuery:
        return send_admin(state_request_);
      case SystemRequest::Kind::kStop:
        return send_admin(BoardCommand::kStop);
      case SystemRequest::Kind::kSetZero:
        return send_admin(BoardCommand::kResetZero);
      case SystemRequest::Kind::kSaveToFlash:
        return send_admin(BoardCommand::kSave);
      case SystemRequest::Kind::kSoftReboot:
        return send_admin(BoardCommand::kReboot);
      case SystemRequest::Kind::kCommandTimeout: {
        // 0x85 is a slot command: each motor's timeout (LE16 ms) in its slot, the others' kept.
        if (request.motor < kMinMotorId || request.motor > highest_id_) return BusIo::kBusy;
        timeouts_.at(static_cast<std::size_t>(request.motor - 1)) = static_cast<std::uint16_t>(request.value);
        std::array<std::uint8_t, kMaxPacket> packet{};
        return write_packet(std::span(packet).first(
            encode_board_timeouts(std::span(timeouts_).first(static_cast<std::size_t>(highest_id_)), packet)));
      }
      case SystemRequest::Kind::kInfo:
        // The board answers firmware versions only; hardware version and model are not asked.
        return request.info == InfoKind::kFirmwareVersion ? send_admin(BoardCommand::kVersion) : BusIo::kOk;
    }
    return BusIo::kBusy;
  }

  BusIo receive(ReplySink& sink) noexcept override {
    std::array<std::uint8_t, 4096> bytes{};
    for (int i = 0; i < kMaxReadsPerReceive; ++i) {
      std::size_t count = 0;
      const transport::SerialIo io = port_.read(bytes, count);
      if (io == transport::SerialIo::kClosed) return BusIo::kClosed;
      if (io == transport::SerialIo::kNone) return BusIo::kOk;
      std::span<const std::uint8_t> rest(bytes.data(), count);
      while (!rest.empty()) {
        rest = rest.subspan(splitter_.feed(rest));
        BoardFrame frame;
        while (splitter_.next(frame)) deliver(frame, sink);
      }
      count_junk();
    }
    return BusIo::kOk;
  }

 private:
  /// What the start-up found: 0xB0 needs function version 5 (motor firmware 4.4.6), 0x0A
  /// version 4; firmware-5 motors take the "General" constants whatever the config names, as
  /// the SDK forces them (robot.cc motor_version_detection()).
  void apply(const BoardSetup& setup) {
    mit_command_ = setup.function >= BoardFunction::kV5 ? BoardCommand::kPositionVelocityTorqueKpKd
                                                        : BoardCommand::kPositionVelocityTorqueKpKdV1;
    state_request_ = setup.function >= BoardFunction::kV4 ? BoardCommand::kMotorState2 : BoardCommand::kMotorState;
    scaling_ = configured_scaling_;
    for (const int id : motor_ids_) {
      const auto index = static_cast<std::size_t>(id);
      if (setup.motor_firmware.at(index).major == 5) scaling_.at(index) = kGeneralBoardScaling;
    }
  }

  /// Packets that failed their CRC count as dropped, bytes outside any packet as skipped.
  void count_junk() noexcept {
    frames_dropped_ += splitter_.crc_errors() - counted_crc_errors_;
    bytes_skipped_ += splitter_.skipped_bytes() - counted_skipped_bytes_;
    counted_crc_errors_ = splitter_.crc_errors();
    counted_skipped_bytes_ = splitter_.skipped_bytes();
  }

  void deliver(const BoardFrame& frame, ReplySink& sink) noexcept {
    ++frames_received_;
    if (frame.command == BoardCommand::kVersion) {
      deliver_versions(frame, sink);
      return;
    }
    if (frame.command == BoardCommand::kResetZero || frame.command == BoardCommand::kSave ||
        frame.command == BoardCommand::kReloadConfig) {
      deliver_acknowledgements(frame, sink);
      return;
    }
    std::array<BoardMotorState, driver::kMaxJoints> states;
    const std::size_t count = decode_board_states(frame.command, frame.bytes(), scaling_, states);
    for (std::size_t i = 0; i < count; ++i) {
      Reply reply;
      reply.kind = Reply::Kind::kState;
      reply.state.motor = states[i].motor;
      reply.state.query = Query::kState;
      reply.state.mode = states[i].mode;
      reply.state.fault = states[i].fault;
      reply.state.position_rad = states[i].position_rad;
      reply.state.velocity_rad_s = states[i].velocity_rad_s;
      reply.state.torque_nm = states[i].torque_nm;
      sink.on_reply(reply);
    }
  }

  /// The board answers set-zero, save and reload with the ids of the motors that did it.
  void deliver_acknowledgements(const BoardFrame& frame, ReplySink& sink) noexcept {
    std::array<CommandResult, kMaxBoardPayload> results;
    const std::size_t count = decode_board_acknowledgements(frame.command, frame.bytes(), results);
    for (std::size_t i = 0; i < count; ++i) {
      Reply reply;
      reply.kind = Reply::Kind::kResult;
      reply.result = results[i];
      sink.on_reply(reply);
    }
  }

  void deliver_versions(const BoardFrame& frame, ReplySink& sink) noexcept {
    std::array<FirmwareVersion, kMaxMotorId> versions;
    const std::size_t count = decode_board_versions(frame.bytes(), versions);
    for (std::size_t i = 0; i < count; ++i) {
      Reply reply;
      reply.kind = Reply::Kind::kFirmwareVersion;
      reply.version = versions[i];
      sink.on_reply(reply);
    }
  }

  /// Admin commands and state requests name their motor in one byte; 0x7F is every motor.
  BusIo send_admin(BoardCommand command) noexcept {
    std::array<std::uint8_t, kMaxPacket> packet{};
    return write_packet(std::span(packet).first(encode_board_admin(command, kBroadcastId, packet)));
  }

  BusIo send_packet(BoardCommand command, std::span<const std::uint8_t> payload) noexcept {
    std::array<std::uint8_t, kMaxPacket> packet{};
    return write_packet(std::span(packet).first(encode_board_frame(command, payload, packet)));
  }

  BusIo write_packet(std::span<const std::uint8_t> packet) noexcept {
    const std::size_t size = packet.size();
    std::size_t written = 0;
    switch (port_.write(packet, written)) {
      case transport::SerialIo::kClosed:
        return BusIo::kClosed;
      case transport::SerialIo::kNone:
        ++frames_dropped_;
        return BusIo::kBusy;
      case transport::SerialIo::kDone:
        break;
    }
    if (written < size) {  // the board drops the torn packet on its CRC
      ++frames_dropped_;
      return BusIo::kBusy;
    }
    ++frames_sent_;
    return BusIo::kOk;
  }

  transport::SerialPort port_;
  ScalingById configured_scaling_;
  ScalingById scaling_;  // the configured one, firmware-5 motors "General"
  std::vector<int> motor_ids_;
  int highest_id_;
  std::chrono::milliseconds start_up_timeout_;
  BoardCommand mit_command_ = BoardCommand::kPositionVelocityTorqueKpKd;
  BoardCommand state_request_ = BoardCommand::kMotorState2;
  std::array<std::uint16_t, kMaxMotorId> timeouts_{};
  BoardSlotBuffer slots_;
  BoardFrameSplitter splitter_;
  std::uint64_t counted_crc_errors_ = 0;
  std::uint64_t counted_skipped_bytes_ = 0;
};

}  // namespace

std::unique_ptr<MotorBus> make_board_bus(const transport::SerialConfig& config, const ScalingById& scaling,
                                         std::vector<int> motor_ids, std::chrono::milliseconds start_up_timeout) {
  return std::make_unique<BoardBus>(config, scaling, std::move(motor_ids), start_up_timeout);
}

}  // namespace robotd::hightorque
