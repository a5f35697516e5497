// One port of the livelybot USB-CDC CAN board on a pty (../shared/protocols/hightorque_and_ros2.md
// §1.6.3 and errata): the host writes framed packets, the board applies them to the port's
// motors and answers slot commands with every motor's state in one packet.
#include <algorithm>
#include <cerrno>
#include <unistd.h>

#include "bus.hpp"

namespace robotd::hightorque::sim {
namespace {

constexpr int kMaxReadsPerPass = 64;
constexpr std::size_t kGarbageBytesPerPass = 256;  // bytes

constexpr int kFdcanResetFrom = 41;  // board firmware 4.1, in tenths

bool slot_command(BoardCommand command) {
  switch (command) {
    case BoardCommand::kPosition:
    case BoardCommand::kVelocity:
    case BoardCommand::kTorque:
    case BoardCommand::kPositionVelocityTorqueMax:
    case BoardCommand::kPositionVelocityTorqueKpKdV1:
    case BoardCommand::kPositionVelocityTorqueKpKd:
      return true;
    default:
      return false;
  }
}

MotorRequest mode_request(int motor, Mode mode) {
  MotorRequest request;
  request.kind = MotorRequest::Kind::kCommand;
  request.motor = motor;
  request.command.mode = mode;
  return request;
}

}  // namespace

void Bus::poll_board(std::int64_t now_ns) {
  std::array<std::uint8_t, 4096> bytes{};
  for (int i = 0; i < kMaxReadsPerPass && open_; ++i) {
    const ssize_t n = ::read(pty_.fd(), bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      // EAGAIN: a host holds the device open and sent nothing more. EIO (or 0): no process has
      // the device end open — no host connected, not an error.
      host_connected_ = n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK);
      return;
    }
    host_connected_ = true;
    std::span<const std::uint8_t> rest(bytes.data(), static_cast<std::size_t>(n));
    while (true) {
      const std::size_t consumed = splitter_.feed(rest);
      rest = rest.subspan(consumed);
      bool any = false;
      while (splitter_.next(frame_)) {
        any = true;
        ++frames_received_;
        serve_board(frame_, now_ns);
      }
      if (rest.empty() || (consumed == 0 && !any)) break;
    }
  }
}

template <class Action>
void Bus::for_selected(std::span<const std::uint8_t> payload, std::int64_t now_ns, Action action) {
  for (SimMotor& motor : motors_) {
    const bool selected = payload.empty() || std::ranges::any_of(payload, [&](std::uint8_t id) {
                            return id == kBroadcastId || id == motor.id();
                          });
    if (!selected || motor.muted()) continue;
    motor.heard(now_ns);
    action(motor);
  }
}

bool Bus::serve_board_start_up(const BoardFrame& frame) {
  const std::span<const std::uint8_t> payload = frame.bytes();
  switch (frame.command) {
    case BoardCommand::kSetMotorCount: {  // the host names the port's motor count; answered with the firmware
      std::array<std::uint8_t, 4> reply{};
      reply_packet(frame.command, std::span(reply).first(encode_board_firmware(board_firmware_, reply)));
      return true;
    }
    case BoardCommand::kFdcanReset:
      if (board_firmware_.tenths() < kFdcanResetFrom) {
        ++bad_frames_;  // older boards do not know it
      } else {
        ++fdcan_resets_;
      }
      return true;
    case BoardCommand::kVersion: {
      std::vector<FirmwareVersion> versions;
      for (const SimMotor& motor : motors_) {
        if (motor.muted()) continue;
        FirmwareVersion version = board_motor_firmware_.at(static_cast<std::size_t>(motor.id()));
        version.motor = motor.id();
        versions.push_back(version);
      }
      std::array<std::uint8_t, kMaxBoardPayload> versions_payload{};
      const std::size_t size = encode_board_versions(versions, versions_payload);
      reply_packet(frame.command, std::span<const std::uint8_t>(versions_payload.data(), size));
      return true;
    }
    case BoardCommand::kSetFunctionVersion: {  // echoes the version it now has
      const int asked = payload.empty() ? 0 : payload[0];
      if (asked >= static_cast<int>(BoardFunction::kV1) && asked <= static_cast<int>(BoardFunction::kV5)) {
        function_ = static_cast<BoardFunction>(asked);
      } else {
        ++bad_frames_;
      }
      const std::array<std::uint8_t, 1> echo{static_cast<std::uint8_t>(function_)};
      reply_packet(frame.command, echo);
      return true;
    }
    default:
      return false;
  }
}

void Bus::serve_board(const BoardFrame& frame, std::int64_t now_ns) {
  const std::span<const std::uint8_t> payload = frame.bytes();
  if (serve_board_start_up(frame)) return;
  // What the function version set at start-up does not allow, this board ignores.
  if ((frame.command == BoardCommand::kPositionVelocityTorqueKpKd && function_ < BoardFunction::kV5) ||
      (frame.command == BoardCommand::kMotorState2 && function_ < BoardFunction::kV4)) {
    ++bad_frames_;
    return;
  }
  if (slot_command(frame.command)) {
    const std::size_t count = decode_board_slots(frame.command, payload, board_scaling_, requests_);
    if (count == 0) {
      ++bad_frames_;
      return;
    }
    for (std::size_t r = 0; r < count; ++r) {
      SimMotor* motor = this->motor(requests_.at(r).motor);
      if (motor == nullptr || motor->muted()) continue;
      motor->heard(now_ns);
      motor->command(requests_.at(r));
    }
    // With mode and fault from function version 4 on: the watchdog shows.
    reply_motor_states(function_ >= BoardFunction::kV4 ? BoardCommand::kMotorState2 : BoardCommand::kMotorState);
    return;
  }
  std::array<std::uint8_t, kMaxMotorId + 1> answer{};
  std::size_t answered = 0;
  const auto note = [&](SimMotor& motor) { answer.at(answered++) = static_cast<std::uint8_t>(motor.id()); };
  switch (frame.command) {
    case BoardCommand::kResetZero:  // answered with the ids it zeroed (the SDK waits for them)
      for_selected(payload, now_ns, [&](SimMotor& motor) {
        motor.set_zero();
        note(motor);
      });
      reply_packet(frame.command, std::span<const std::uint8_t>(answer.data(), answered));
      return;
    case BoardCommand::kSave:
      for_selected(payload, now_ns, note);
      reply_packet(frame.command, std::span<const std::uint8_t>(answer.data(), answered));
      return;
    case BoardCommand::kStop:
    case BoardCommand::kBrake: {
      const Mode mode = frame.command == BoardCommand::kStop ? Mode::kStop : Mode::kBrake;
      for_selected(payload, now_ns, [&](SimMotor& motor) { motor.command(mode_request(motor.id(), mode)); });
      return;
    }
    case BoardCommand::kReboot:
      for_selected(payload, now_ns, [](SimMotor& motor) { motor.soft_reboot(); });
      return;
    case BoardCommand::kReloadConfig:
      return;
    case BoardCommand::kTimeout:  // a slot per motor id (LE16 ms); motors past the payload keep theirs
      for_selected({}, now_ns, [&](SimMotor& motor) {
        const auto at = static_cast<std::size_t>(motor.id() - 1) * 2;
        if (at + 1 < payload.size()) {
          motor.set_command_timeout(static_cast<std::uint16_t>(payload[at] | (payload[at + 1] << 8U)));
        }
      });
      return;
    case BoardCommand::kRunToZero:  // to the zero position, held in position mode
      for_selected(payload, now_ns, [&](SimMotor& motor) {
        MotorRequest request = mode_request(motor.id(), Mode::kPosition);
        request.command.position_rad = 0;
        request.has_position = true;
        motor.command(request);
      });
      return;
    case BoardCommand::kMotorState:  // the host asks: answered in kind
    case BoardCommand::kMotorState2:
      reply_motor_states(frame.command);
      return;
    default:
      ++bad_frames_;  // a mode this board does not simulate
      return;
  }
}

void Bus::reply_motor_states(BoardCommand command) {
  std::array<BoardMotorState, kMaxMotorId + 1> states{};
  std::size_t count = 0;
  for (const SimMotor& motor : motors_) {
    if (!motor.muted()) states.at(count++) = motor.board_report();
  }
  std::array<std::uint8_t, kMaxBoardPayload> payload{};
  const std::size_t size =
      encode_board_states(command, std::span<const BoardMotorState>(states.data(), count), board_scaling_, payload);
  reply_packet(command, std::span<const std::uint8_t>(payload.data(), size));
}

void Bus::reply_packet(BoardCommand command, std::span<const std::uint8_t> payload) {
  if (!reply_survives()) return;
  const std::size_t size = encode_board_frame(command, payload, packet_);
  if (size == 0) return;
  send_bytes(std::span<const std::uint8_t>(packet_.data(), size));
}

void Bus::send_bytes(std::span<const std::uint8_t> bytes) {
  // Nothing goes out without a host: it would wait in the pty for the next one to read.
  if (!open_ || !host_connected_) return;
  ssize_t n = -1;
  do {
    n = ::write(pty_.fd(), bytes.data(), bytes.size());
  } while (n < 0 && errno == EINTR);
  if (n == static_cast<ssize_t>(bytes.size())) ++frames_sent_;
}

void Bus::send_board_garbage() {
  if (!host_connected_ || garbage_pending_ <= 0) return;
  std::array<std::uint8_t, kGarbageBytesPerPass> bytes{};
  const auto count = static_cast<std::size_t>(std::min<std::int64_t>(garbage_pending_, kGarbageBytesPerPass));
  std::uniform_int_distribution<int> byte(0, 255);
  for (std::size_t i = 0; i < count; ++i) {
    do {
      bytes.at(i) = static_cast<std::uint8_t>(byte(random_));
    } while (bytes.at(i) == kBoardHeader);  // never a packet start: nothing here can decode
  }
  const ssize_t n = ::write(pty_.fd(), bytes.data(), count);
  if (n > 0) garbage_pending_ -= n;
}

}  // namespace robotd::hightorque::sim
