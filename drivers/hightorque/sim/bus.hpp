// One bus of motors as the simulator serves it: a CAN-FD bus (the stand-in or SocketCAN) whose
// motors each answer for themselves, or one port of the livelybot USB-CDC CAN board on a pty,
// which answers for all its motors at once. Requests are applied and answered as they are read;
// the misbehaviour the control channel asks for (lost replies, garbage, a disconnect) happens here.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <random>
#include <span>
#include <vector>

#include "codec/hightorque_codec.hpp"
#include "motor.hpp"
#include "robotd/result.hpp"
#include "robotd/transport/can_transport.hpp"
#include "robotd/transport/serial_port.hpp"
#include "sim_options.hpp"

namespace robotd::hightorque::sim {

/// The hardware version 00 05 reports.
inline constexpr FirmwareVersion kHardwareVersion{.motor = 0, .major = 1, .minor = 0, .patch = 0};
/// What a board motor reports (0x0B) unless --board-motor-firmware says otherwise: function v5.
inline constexpr FirmwareVersion kBoardMotorFirmware{.motor = 0, .major = 4, .minor = 4, .patch = 6};

class Bus {
 public:
  Bus(BusSpec spec, const SimOptions& options, std::int64_t now_ns);
  Bus(const Bus&) = delete;
  Bus& operator=(const Bus&) = delete;
  ~Bus() { close(); }

  /// Listens on the stand-in path, joins the interface, or makes the pty and its symlink.
  Result<void> open();
  void close() noexcept;
  bool is_open() const { return open_; }

  /// Reads everything waiting, applies it and answers at once.
  void poll(std::int64_t now_ns);
  /// The status pushes due at `now_ns`, then some of the garbage asked for.
  void send_due(std::int64_t now_ns);
  void reopen_if_due(std::int64_t now_ns);

  // ---- The control channel ----
  /// Closes the link (every node sees it end, the stand-in path or the pty symlink vanishes)
  /// and opens it again after `for_ms`.
  void disconnect(std::int64_t for_ms, std::int64_t now_ns);
  void drop_replies(std::int64_t count) { drop_pending_ += count; }
  /// Every reply vanishes for `for_ms` while the link stays up: the motors hear but never answer.
  void silence(std::int64_t for_ms, std::int64_t now_ns) { silent_until_ns_ = now_ns + for_ms * 1'000'000; }
  void queue_garbage(std::int64_t count) { garbage_pending_ += count; }
  void reset_counters();

  const BusSpec& spec() const { return spec_; }
  const char* kind_text() const;
  std::vector<SimMotor>& motors() { return motors_; }
  const std::vector<SimMotor>& motors() const { return motors_; }
  /// The motor answering to `id` now, or null.
  SimMotor* motor(int id);

  std::uint64_t frames_received() const { return frames_received_; }
  std::uint64_t frames_sent() const { return frames_sent_; }
  std::uint64_t bad_frames() const;
  std::uint64_t replies_dropped() const { return replies_dropped_; }
  std::int64_t drop_pending() const { return drop_pending_; }
  std::int64_t garbage_pending() const { return garbage_pending_; }
  bool host_connected() const { return host_connected_; }
  // The board's start-up state (board buses only).
  const BoardFirmware& board_firmware() const { return board_firmware_; }
  BoardFunction function_version() const { return function_; }
  std::uint64_t fdcan_resets() const { return fdcan_resets_; }

 private:
  bool board() const { return spec_.kind == BusSpec::Kind::kBoard; }
  /// False when the reply is one of those asked to vanish.
  bool reply_survives();

  // CAN-FD (can_link.cpp)
  void poll_can(std::int64_t now_ns);
  void serve(SimMotor& motor, const MotorRequest& request, std::int64_t now_ns);
  void send_frame(const transport::CanMessage& message);
  void reply(const transport::CanMessage& message);
  transport::CanMessage garbage_frame();

  // The board (board_link.cpp)
  void poll_board(std::int64_t now_ns);
  void serve_board(const BoardFrame& frame, std::int64_t now_ns);
  /// The motors a per-motor byte payload selects (byte id−1 non-zero; an empty payload: all).
  template <class Action>
  void for_selected(std::span<const std::uint8_t> payload, std::int64_t now_ns, Action action);
  void reply_packet(BoardCommand command, std::span<const std::uint8_t> payload);
  /// Every motor's record in one kMotorState or kMotorState2 packet (a muted motor has none).
  void reply_motor_states(BoardCommand command);
  void send_bytes(std::span<const std::uint8_t> bytes);
  void send_board_garbage();
  /// The host's start-up packets (0x05, 0x0B, 0x0C, 0x0E); false for any other command.
  bool serve_board_start_up(const BoardFrame& frame);

  BusSpec spec_;
  std::string model_;
  FirmwareVersion firmware_;
  std::vector<SimMotor> motors_;
  MotorScaling scaling_;                                       // CAN-FD
  std::array<MotorScaling, kMaxMotorId + 1> board_scaling_{};  // by motor id
  std::array<MotorRequest, kMaxMotorId + 1> requests_{};       // decode_request's output
  BoardFirmware board_firmware_;
  std::array<FirmwareVersion, kBroadcastId + 1> board_motor_firmware_{};  // by motor id
  /// What the host last set (0x0C): 0xB0 needs v5, state requests 0x0A v4. A board starts at v1
  /// and keeps what it was given across a link drop (it stays powered).
  BoardFunction function_ = BoardFunction::kV1;
  std::uint64_t fdcan_resets_ = 0;

  std::unique_ptr<transport::CanTransport> can_;
  transport::PseudoTerminal pty_;
  BoardFrameSplitter splitter_;
  BoardFrame frame_;
  std::vector<std::uint8_t> packet_;  // an encoded board packet (kBoardHeaderSize + kMaxBoardPayload)
  bool open_ = false;
  bool host_connected_ = false;  // board: a process holds the pty's device end open
  std::optional<std::int64_t> reopen_at_ns_;

  std::int64_t drop_pending_ = 0;
  std::int64_t silent_until_ns_ = 0;
  std::int64_t now_ns_ = 0;  // of the poll or send under way
  std::int64_t garbage_pending_ = 0;
  std::mt19937 random_{0x47D5EED};

  std::uint64_t frames_received_ = 0;
  std::uint64_t frames_sent_ = 0;
  std::uint64_t bad_frames_ = 0;
  std::uint64_t replies_dropped_ = 0;
  std::uint64_t crc_errors_base_ = 0;  // splitter_.crc_errors() at the last reset_counters
};

}  // namespace robotd::hightorque::sim
