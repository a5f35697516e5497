#include "bus.hpp"

#include <algorithm>

#include <spdlog/spdlog.h>

#include "robotd/transport/can_bus.hpp"
#include "robotd/transport/unix_socket.hpp"

namespace robotd::hightorque::sim {
namespace {

constexpr std::int64_t kReopenRetryNs = 100'000'000;
constexpr double kDefaultBoardTorquePerUnit = 0.01;  // a model the SDK's table does not list

}  // namespace

Bus::Bus(BusSpec spec, const SimOptions& options, std::int64_t now_ns)
    : spec_(std::move(spec)), model_(options.model), firmware_(options.firmware) {
  motors_.reserve(spec_.ids.size());
  for (const int id : spec_.ids) motors_.emplace_back(id, options.physics, now_ns);
  scaling_.gain_factor = options.gain_factor;
  double torque_per_unit = options.board_torque_per_unit;
  if (torque_per_unit <= 0) torque_per_unit = model_torque_per_unit(options.model);
  if (torque_per_unit <= 0) torque_per_unit = kDefaultBoardTorquePerUnit;
  board_scaling_.fill(
      MotorScaling{.torque_per_unit = torque_per_unit, .torque_offset_nm = 0, .gain_factor = options.gain_factor});
  board_firmware_ = options.board_firmware;
  board_motor_firmware_.fill(kBoardMotorFirmware);
  for (const BoardMotorFirmware& given : options.board_motor_firmware) {
    for (const int id : spec_.ids) {
      if (given.ids.empty() || std::ranges::find(given.ids, id) != given.ids.end()) {
        board_motor_firmware_.at(static_cast<std::size_t>(id)) = given.version;
      }
    }
  }
  // Firmware-5 motors speak the "General" constants on the board, whatever their model.
  for (const int id : spec_.ids) {
    const auto index = static_cast<std::size_t>(id);
    if (index < board_scaling_.size() && board_motor_firmware_.at(index).major == 5) {
      board_scaling_.at(index) = kGeneralBoardScaling;
    }
  }
  packet_.resize(kBoardHeaderSize + kMaxBoardPayload);
  if (spec_.kind != BusSpec::Kind::kBoard) {
    transport::CanLinkConfig link;
    link.kind = spec_.kind == BusSpec::Kind::kStandIn ? transport::CanLinkConfig::Kind::kStandIn
                                                      : transport::CanLinkConfig::Kind::kSocketCan;
    link.path = spec_.path;
    link.interface = spec_.path;
    link.fd = true;
    can_ = transport::make_can_bus(link);
  }
}

const char* Bus::kind_text() const {
  switch (spec_.kind) {
    case BusSpec::Kind::kStandIn:
      return "standin";
    case BusSpec::Kind::kSocketCan:
      return "socketcan";
    case BusSpec::Kind::kBoard:
      return "board";
  }
  return "unknown";
}

Result<void> Bus::open() {
  if (board()) {
    if (auto opened = pty_.open(spec_.path); !opened) return opened;
  } else {
    if (spec_.kind == BusSpec::Kind::kStandIn && transport::unix_socket_in_use(spec_.path)) {
      return make_error(ErrorCode::kNotAvailable,
                        "the stand-in bus " + spec_.path + " is in use: another simulator listens there");
    }
    if (auto opened = can_->open(); !opened) return opened;
  }
  open_ = true;
  return {};
}

void Bus::close() noexcept {
  if (can_) can_->close();
  pty_.close();
  open_ = false;
  host_connected_ = false;
}

void Bus::disconnect(std::int64_t for_ms, std::int64_t now_ns) {
  close();
  reopen_at_ns_ = now_ns + for_ms * 1'000'000;
}

void Bus::reopen_if_due(std::int64_t now_ns) {
  if (!reopen_at_ns_ || now_ns < *reopen_at_ns_) return;
  if (auto opened = open(); !opened) {
    spdlog::warn("cannot reopen {}: {}; retrying", spec_.path, opened.error().message);
    reopen_at_ns_ = now_ns + kReopenRetryNs;
    return;
  }
  reopen_at_ns_.reset();
  spdlog::info("{} open again", spec_.path);
}

void Bus::poll(std::int64_t now_ns) {
  now_ns_ = now_ns;
  if (!open_) return;
  if (board()) {
    poll_board(now_ns);
  } else {
    poll_can(now_ns);
  }
}

void Bus::send_due(std::int64_t now_ns) {
  now_ns_ = now_ns;
  if (!open_) return;
  if (board()) {
    send_board_garbage();
    return;
  }
  for (SimMotor& motor : motors_) {
    if (motor.push_due(now_ns) && !motor.muted()) {
      reply(encode_reply(motor.report(motor.push_query()), motor.push_width(), scaling_));
    }
  }
  constexpr int kGarbageFramesPerPass = 10;  // spread out, so replies keep flowing between them
  for (int i = 0; i < kGarbageFramesPerPass && garbage_pending_ > 0; ++i, --garbage_pending_)
    send_frame(garbage_frame());
}

SimMotor* Bus::motor(int id) {
  for (SimMotor& motor : motors_) {
    if (motor.id() == id) return &motor;
  }
  return nullptr;
}

bool Bus::reply_survives() {
  if (now_ns_ < silent_until_ns_) {
    ++replies_dropped_;
    return false;
  }
  if (drop_pending_ <= 0) return true;
  --drop_pending_;
  ++replies_dropped_;
  return false;
}

std::uint64_t Bus::bad_frames() const { return bad_frames_ + splitter_.crc_errors() - crc_errors_base_; }

void Bus::reset_counters() {
  frames_received_ = 0;
  frames_sent_ = 0;
  bad_frames_ = 0;
  replies_dropped_ = 0;
  crc_errors_base_ = splitter_.crc_errors();
}

}  // namespace robotd::hightorque::sim
