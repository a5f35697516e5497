// A CAN-FD bus: every motor reads the frames addressed to it (or to 127, all of them) and
// answers with its own frame (../shared/protocols/hightorque_and_ros2.md §1.6.1 and errata).
#include <spdlog/spdlog.h>

#include "bus.hpp"

namespace robotd::hightorque::sim {
namespace {

constexpr int kMaxFramesPerPoll = 1000;
constexpr std::uint8_t kResultOk = 0;
constexpr std::uint8_t kResultRefused = 1;

}  // namespace

void Bus::poll_can(std::int64_t now_ns) {
  transport::CanMessage message;
  for (int i = 0; i < kMaxFramesPerPoll && open_; ++i) {
    const transport::CanIo result = can_->receive(message);
    if (result == transport::CanIo::kNone) return;
    if (result == transport::CanIo::kClosed) {
      spdlog::warn("{} closed; reopening", can_->describe());
      close();
      reopen_at_ns_ = now_ns + 100'000'000;
      return;
    }
    if (result == transport::CanIo::kBusError) continue;
    ++frames_received_;
    const std::size_t count = decode_request(message, scaling_, requests_);
    if (count == 0) {
      ++bad_frames_;
      continue;
    }
    for (std::size_t r = 0; r < count; ++r) {
      const MotorRequest& request = requests_.at(r);
      if (request.motor == kBroadcastId) {
        for (SimMotor& motor : motors_) serve(motor, request, now_ns);
      } else if (SimMotor* motor = this->motor(request.motor)) {
        serve(*motor, request, now_ns);
      }
    }
  }
}

void Bus::serve(SimMotor& motor, const MotorRequest& request, std::int64_t now_ns) {
  if (motor.muted()) return;  // unplugged: hears nothing, says nothing
  motor.heard(now_ns);
  const int id = motor.id();
  const auto answer_state = [&] {
    if (request.query != Query::kNone) reply(encode_reply(motor.report(request.query), request.width, scaling_));
  };
  switch (request.kind) {
    case MotorRequest::Kind::kCommand:
      motor.command(request);
      answer_state();
      break;
    case MotorRequest::Kind::kQuery:
      answer_state();
      break;
    case MotorRequest::Kind::kSoftReboot:
      motor.soft_reboot();
      reply(encode_command_result(id, kResultOk));
      break;
    case MotorRequest::Kind::kSaveToFlash:
      reply(encode_command_result(id, kResultOk));
      break;
    case MotorRequest::Kind::kSetZero:
      motor.set_zero();
      reply(encode_command_result(id, kResultOk));
      break;
    case MotorRequest::Kind::kChangeId: {
      const bool valid = request.motor != kBroadcastId && request.new_id >= kMinMotorId &&
                         request.new_id <= kMaxMotorId &&
                         (request.new_id == id || this->motor(request.new_id) == nullptr);
      reply(encode_command_result(id, valid ? kResultOk : kResultRefused));
      if (valid) motor.set_id(request.new_id);
      break;
    }
    case MotorRequest::Kind::kCommandTimeout:
      motor.set_command_timeout(request.timeout_ms);
      reply(encode_command_result(id, kResultOk));
      break;
    case MotorRequest::Kind::kStatusPush: {
      const bool accepted = motor.set_status_push(request.query, request.width, request.period_us, now_ns);
      reply(encode_command_result(id, accepted ? kResultOk : kResultRefused));
      break;
    }
    case MotorRequest::Kind::kInfo:
      if (request.info == InfoKind::kModel) {
        reply(encode_model_name(id, model_));
      } else {
        FirmwareVersion version = request.info == InfoKind::kHardwareVersion ? kHardwareVersion : firmware_;
        version.motor = id;
        reply(encode_firmware_version(version, request.info));
      }
      break;
  }
}

void Bus::reply(const transport::CanMessage& message) {
  if (reply_survives()) send_frame(message);
}

void Bus::send_frame(const transport::CanMessage& message) {
  if (open_ && can_->send(message) == transport::CanIo::kDone) ++frames_sent_;
}

transport::CanMessage Bus::garbage_frame() {
  // Frames a reply decoder must drop (errata: type bits 00, motor 0, DLC 0, truncated payload)
  // and standard ids, which the protocol never uses.
  const auto random = [this](int low, int high) { return std::uniform_int_distribution<int>(low, high)(random_); };
  const int motor = spec_.ids.at(static_cast<std::size_t>(random(0, static_cast<int>(spec_.ids.size()) - 1)));
  transport::CanMessage message;
  message.extended = true;
  message.fd = true;
  message.bitrate_switch = true;
  message.length = static_cast<std::uint8_t>(random(1, 8));
  switch (random(0, 4)) {
    case 0:  // type bits 00
      message.id = static_cast<std::uint32_t>(motor) << 8U;
      break;
    case 1:  // motor 0
      message.id = static_cast<std::uint32_t>(random(1, 3)) << 16U;
      break;
    case 2:  // no payload
      message.id = reply_id(Width::kInt16, motor);
      message.length = 0;
      break;
    case 3:  // a state reply cut short
      message.id = reply_id(Width::kInt16, motor);
      message.length = 2;
      break;
    default:  // a standard id
      message.id = static_cast<std::uint32_t>(random(0, 0x7FF));
      message.extended = false;
      message.fd = false;
      message.bitrate_switch = false;
      break;
  }
  for (std::size_t i = 0; i < message.length; ++i) message.data.at(i) = static_cast<std::uint8_t>(random(0, 255));
  if (message.length == 2) message.data[0] = static_cast<std::uint8_t>(Query::kState);
  return message;
}

}  // namespace robotd::hightorque::sim
