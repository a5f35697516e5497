// HighTorque motors (../shared/protocols/hightorque_and_ros2.md §1.6 and its errata) as plain
// values: the current CAN-FD protocol (29-bit identifiers, single-motor mode frames, one-to-many
// block frames, system commands, replies and fault codes) and the livelybot USB-CDC "CAN board"
// framing (0xF7 header, CRC-8 / CRC-16) with its per-port slot payloads.
//
// Units at this surface are robotd's: rad, rad/s, rad/s², N·m, and gains in N·m/rad and
// N·m·s/rad. Revolutions, the int16/int32 scalings, the board's per-model torque factors and the
// gain conversion exist only inside this codec, driven by MotorScaling (from config).
// Scaling follows the vendor's code operation for operation: the value as a float, turned into
// revolutions and multiplied by the width's scale in float (the motor firmware SDK's convert.c;
// the board SDK's motor.cc for the board), then truncated toward zero. Unlike the vendor's code
// it saturates (never wraps) at ±32767 / ±2147483647, so that no finite value becomes the "no
// value" sentinel; NaN encodes as that sentinel (0x8000 / 0x80000000 / NaN). In a command the
// sentinel decodes as NaN ("no value"); in a reply it is a number (0x8000 = −32768, a saturated
// reading), as the vendor's parsers read it.
//
// Everything on the motor's hot path (encode_* into CanMessage or a caller's byte span,
// decode_reply, BoardFrameSplitter) is noexcept and allocation-free: robotd's RT thread calls it.
// Little-endian everywhere on the wire.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <tuple>

#include "robotd/result.hpp"
#include "robotd/transport/can_message.hpp"

namespace robotd::hightorque {

// Motor ids 1…30: the vendor's SDKs keep at most 30 motors a port (motor_many.h, the board's
// PORT_MOTOR_NUM_MAX) and drop replies of higher ids; block frames address motors 1…30. The 7-bit
// id field of the wire would carry 1…126.
inline constexpr int kMinMotorId = 1;
inline constexpr int kMaxMotorId = 30;
inline constexpr int kBroadcastId = 127;
inline constexpr int kMaxBlockMotorId = kMaxMotorId;

// ---- Scaling -------------------------------------------------------------------------------

/// Numeric width of a frame's parameters: the "type" field of a CAN-FD identifier.
enum class Width : std::uint8_t { kInt16 = 1, kInt32 = 2, kFloat = 3 };

/// Per-motor-model conversion between robotd's units and the motor's (config "motor_models").
struct MotorScaling {
  /// N·m per motor torque unit. 1.0 on CAN-FD firmware (which speaks N·m ×100 / ×1000 / float);
  /// on the USB board the model's LSB factor (e.g. 0.004938 for the 5047_36).
  double torque_per_unit = 1.0;
  double torque_offset_nm = 0.0;  // board: raw = (τ − offset) / torque_per_unit
  /// Motor gain = robotd gain × 2π / gain_factor (N·m/rad → the motor's per-revolution gain);
  /// the board then multiplies by 10 and saturates at ±32700. The spec leaves the physical
  /// unit of the new firmware's gains open (§1.6.1), hence configurable.
  double gain_factor = 1.0;
};

// ---- CAN-FD protocol: identifiers ----------------------------------------------------------

/// Command to one motor: (width << 16) | 0x8000 | motor. Block frames put the block code
/// (0x80…0x9C) where the motor id goes, always with Width::kInt16.
std::uint32_t command_id(Width width, int motor_or_block) noexcept;
/// Reply from a motor: (width << 16) | (motor << 8), bit 15 clear.
std::uint32_t reply_id(Width width, int motor) noexcept;

// ---- CAN-FD protocol: commands robotd sends ------------------------------------------------

enum class Mode : std::uint8_t {
  kStop = 0x01,     // phases open: free-wheel
  kBrake = 0x18,    // phases shorted
  kVoltage = 0x19,  // d = 0, q
  kCurrent = 0x1A,  // d = 0, q
  kTorque = 0x1B,
  kVelocity = 0x1C,
  kPosition = 0x1D,
  kVelocityAcceleration = 0x1E,
  kPositionVelocityTorque = 0x1F,        // p, v_max, τ_max
  kPositionVelocityAcceleration = 0x20,  // trapezoid: p, v_max, a
  kMit = 0x21,                           // p, v, τ_ff, kp, kd
};

/// The reply the motor sends back (byte 1 of a command, echoed in byte 0 of the reply).
enum class Query : std::uint8_t {
  kNone = 0x00,              // no reply
  kCounter = 0x0A,           // mode, fault, command counter
  kState = 0x0B,             // mode, fault, position, velocity, torque
  kStateTemperature = 0x0C,  // mode, fault, temperature, position, velocity, torque
  kCompact = 0x0E,           // fault, position, velocity, torque (fits 8 bytes)
};

/// One motor's command in robotd's units. Fields a mode does not use are ignored.
struct MotorCommand {
  Mode mode = Mode::kStop;
  double position_rad = 0;
  double velocity_rad_s = 0;  // MIT: v_des; kPositionVelocity*: v_max; kVelocity*: target
  double acceleration_rad_s2 = 0;
  double torque_nm = 0;  // MIT: τ_ff; kPositionVelocityTorque: τ_max; kTorque: target
  double kp = 0;         // N·m/rad
  double kd = 0;         // N·m·s/rad
  double voltage_q_v = 0;
  double current_q_a = 0;
};

/// A single-motor command frame (CAN-FD, extended id, BRS), padded to a valid FD length.
transport::CanMessage encode_command(int motor, const MotorCommand& command, Width width, Query query,
                                     const MotorScaling& scaling) noexcept;

/// One motor's slot in a one-to-many block frame.
struct BlockSlot {
  int motor = 0;  // 1…30
  MotorCommand command;
};

/// Block frames for a bus of motors 1…`motor_count` (int16 only; `motor_count` ≤
/// kMaxBlockMotorId), every motor's slot in every tick as the vendor's motor_many.c sends them:
/// MIT slots go in 0x98…0x9C frames (6 motors per frame, 10 bytes each, motors 1–6 in 0x98,
/// 7–12 in 0x99, …), kPositionVelocityTorque in 0x92…0x94 and kPositionVelocityAcceleration in
/// 0x95…0x97 (10 per frame), kVelocityAcceleration in 0x90…0x91 (15 per frame), kStop / kBrake
/// in 0x85 / 0x86 (1 byte per motor), position / velocity / torque / voltage q / current q in
/// 0x80…0x84 (30 per frame); the last frame carries the remaining motors.
/// Every slot must have the same mode (the mode of slots[0]); slots need not be sorted; the
/// motors not in `slots` get the "no value" marker (0x8000 in every 2-byte field, 0 in a 1-byte
/// slot). The query code is the padded frame's last byte, the padding before it 0.
/// `scaling_by_motor_id` is indexed by motor id (element 0 unused): one frame may carry motors
/// of different models. Returns the number of frames written to `out`, or 0 if there are no
/// slots, they do not fit `out`, mix modes, name a motor outside 1…motor_count or without
/// scaling, or use a mode that has no block form.
std::size_t encode_block(std::span<const BlockSlot> slots, Query query,
                         std::span<const MotorScaling> scaling_by_motor_id, int motor_count,
                         std::span<transport::CanMessage> out) noexcept;

/// The reboot (0x87) and rezero (0x88) blocks for a bus of motors 1…`motor_count`: one flag
/// byte per motor (1 = do it) as motor_many.c sends them, the query code last. Returns the
/// number of frames written (1), or 0 if `motors` is empty, names a motor outside
/// 1…motor_count, or `out` is empty.
enum class BlockSystem : std::uint8_t { kSoftReboot, kSetZero };
std::size_t encode_block_system(BlockSystem what, std::span<const int> motors, Query query, int motor_count,
                                std::span<transport::CanMessage> out) noexcept;

/// System commands (int16 id to one motor).
transport::CanMessage encode_soft_reboot(int motor) noexcept;    // 03 03 01
transport::CanMessage encode_save_to_flash(int motor) noexcept;  // 03 03 02
transport::CanMessage encode_set_zero(int motor) noexcept;       // 03 03 03
/// 03 03 04 <new id>; an error naming the id when `motor` or `new_id` is outside 1…kMaxMotorId
/// (the vendor's hightorque_id() refuses those too: a reply from such an id is never read).
Result<transport::CanMessage> encode_change_id(int motor, int new_id);
/// 05 <ms LE16>: the motor brakes by itself when no command arrives for `timeout_ms`; 0 disarms.
transport::CanMessage encode_command_timeout(int motor, std::uint16_t timeout_ms) noexcept;
/// 03 00 05 <query> <µs LE32>: periodic status push; 0 stops; the motor refuses < 100 µs.
transport::CanMessage encode_status_push(int motor, Query query, std::uint32_t period_us) noexcept;
enum class InfoKind : std::uint8_t { kFirmwareVersion = 0x04, kHardwareVersion = 0x05, kModel = 0x07 };
transport::CanMessage encode_info_request(int motor, InfoKind kind) noexcept;  // 00 04 / 00 05 / 00 07
/// A query with no mode change (the motor keeps doing what it was told).
transport::CanMessage encode_query(int motor, Query query, Width width) noexcept;

// ---- CAN-FD protocol: replies robotd reads -------------------------------------------------

struct MotorState {
  int motor = 0;
  Query query = Query::kNone;
  std::uint8_t mode = 0;   // the motor's current Mode code (not in kCompact replies: 0)
  std::uint8_t fault = 0;  // fault code, fault_text()
  double position_rad = 0;
  double velocity_rad_s = 0;
  double torque_nm = 0;
  std::optional<double> temperature_c;  // kStateTemperature only
  /// kCounter only. Its field has the frame's width (assumption: the vendor documents int16
  /// only); int32 counters are kept modulo 2^16, float ones saturated into 0…65535.
  std::optional<std::uint16_t> counter;
};
struct FirmwareVersion {
  int motor = 0;
  int major = 0;
  int minor = 0;
  int patch = 0;
  /// By major, minor, patch (the motor id does not count).
  [[nodiscard]] constexpr bool older_than(const FirmwareVersion& other) const noexcept {
    return std::tie(major, minor, patch) < std::tie(other.major, other.minor, other.patch);
  }
};
struct ModelName {
  int motor = 0;
  std::array<char, 60> text{};
};  // NUL-terminated printable ASCII (other bytes read as '?'), ≤ 59 chars
struct CommandResult {
  int motor = 0;
  bool success = false;
  std::uint8_t code = 0;
};  // 0x03 reply

struct Reply {
  enum class Kind : std::uint8_t { kState, kFirmwareVersion, kHardwareVersion, kModel, kResult };
  Kind kind = Kind::kState;
  MotorState state;
  FirmwareVersion version;  // kFirmwareVersion and kHardwareVersion
  ModelName model;
  CommandResult result;
};

/// Decodes one reply frame. nullopt for anything that is not a well-formed reply from a motor
/// 1…max_motor_id: bit 15 set (a command), type 00, motor 0, DLC 0, truncated or unknown
/// payloads. Never reads past message.length.
std::optional<Reply> decode_reply(const transport::CanMessage& message, int max_motor_id,
                                  const MotorScaling& scaling) noexcept;

// ---- CAN-FD protocol: the motor's side (for the simulator) ---------------------------------

/// What a command frame asks of one motor.
struct MotorRequest {
  enum class Kind : std::uint8_t {
    kCommand,  // a mode command (single or from a block): `command`, `query`
    kQuery,    // a query without a mode change
    kSoftReboot,
    kSaveToFlash,
    kSetZero,
    kChangeId,        // `new_id`
    kCommandTimeout,  // `timeout_ms`
    kStatusPush,      // `query`, `period_us`
    kInfo,            // `info`
  };
  Kind kind = Kind::kCommand;
  int motor = 0;
  MotorCommand command;
  /// Which fields of `command` the frame carried (a block slot of 0x8000 leaves a field unset;
  /// the motor keeps its previous value for it).
  bool has_position = false, has_velocity = false, has_torque = false, has_kp = false, has_kd = false;
  Query query = Query::kNone;
  Width width = Width::kInt16;
  int new_id = 0;
  std::uint16_t timeout_ms = 0;
  std::uint32_t period_us = 0;
  InfoKind info = InfoKind::kFirmwareVersion;
};

/// Decodes a command frame into per-motor requests (a block frame yields one per motor slot it
/// sets, in id order; reboot / rezero blocks 0x87 / 0x88 yield kSoftReboot / kSetZero). Returns
/// how many were written to `out` (0 for anything that is not a well-formed command: reply ids,
/// unknown modes or query codes, truncated payloads; stops when `out` is full).
std::size_t decode_request(const transport::CanMessage& message, const MotorScaling& scaling,
                           std::span<MotorRequest> out) noexcept;

/// A motor's reply frame, as the motor would send it for `state.query` at `width` (length 0 for
/// Query::kNone: the motor sends nothing).
transport::CanMessage encode_reply(const MotorState& state, Width width, const MotorScaling& scaling) noexcept;
transport::CanMessage encode_firmware_version(const FirmwareVersion& version, InfoKind kind) noexcept;
transport::CanMessage encode_model_name(int motor, std::string_view name) noexcept;
transport::CanMessage encode_command_result(int motor, std::uint8_t code) noexcept;

// ---- Fault and mode texts ------------------------------------------------------------------

/// "communication timeout" for 0x15, "ok" for 0, "unknown fault 0x42" style text otherwise
/// (static storage: safe on the RT thread).
const char* fault_text(std::uint8_t fault) noexcept;
/// "mit", "stop", "brake", … ; "unknown" for codes outside Mode.
const char* mode_text(std::uint8_t mode) noexcept;

// ---- USB-CDC CAN board (livelybot) ---------------------------------------------------------

inline constexpr std::uint8_t kBoardHeader = 0xF7;
inline constexpr std::size_t kBoardHeaderSize = 7;  // F7, cmd, len LE16, crc8, crc16 LE16
inline constexpr std::size_t kMaxBoardPayload = 1024;

/// CRC-8/MAXIM table with initial value 0xFF (check over "123456789": 0x0B).
std::uint8_t board_crc8(std::span<const std::uint8_t> bytes) noexcept;
/// CRC-16/MCRF4XX: reflected 0x8408, init 0xFFFF, no final XOR (check value 0x6F91).
std::uint16_t board_crc16(std::span<const std::uint8_t> bytes) noexcept;

/// Board command / admin codes (§1.6.3). The SDK sends admin commands and state requests with a
/// 1-byte payload: a motor id, or 0x7F for every motor; the board answers a state request in kind.
enum class BoardCommand : std::uint8_t {
  kResetZero = 0x01,
  kSave = 0x02,
  kStop = 0x03,
  kBrake = 0x04,
  kSetMotorCount = 0x05,
  kMotorState = 0x06,  // board → host: every motor's record without mode / fault (7 bytes)
  kReloadConfig = 0x07,
  kReboot = 0x08,
  kRunToZero = 0x09,    // every motor (0x7F) or one drives back to its zero position
  kMotorState2 = 0x0A,  // board → host: every motor's state2 record (9 bytes)
  kVersion = 0x0B,
  kSetFunctionVersion = 0x0C,  // host → board: BoardFunction; the board echoes the one it took
  kFdcanReset = 0x0E,          // board firmware ≥ 4.1: restarts its CAN-FD controllers (payload 0)
  kPosition = 0x80,
  kVelocity = 0x81,
  kTorque = 0x82,
  kVoltage = 0x83,  // q-axis volts × 10 per motor
  kCurrent = 0x84,  // q-axis amps × 10 per motor
  kTimeout = 0x85,
  kPositionVelocityTorqueMax = 0x90,
  kPositionVelocityTorqueKpKdV1 = 0x93,  // the SDK's control_type 9: pos, vel, τ, kp, kd per motor
  kPositionVelocityKpKd = 0x9E,          // pos, vel, kp, kd per motor
  kPositionVelocityAcceleration = 0xAD,  // not encoded: docs/drivers/hightorque.md "Conformance"
  kPositionVelocityTorqueKpKd = 0xB0,    // control_type 12, boards with function version 5: the same slots
};

/// The board's function version (the SDK's fun_version, robot.cc): what the board's firmware
/// does, set by the host from the lowest motor firmware of every port (0x0C).
enum class BoardFunction : std::uint8_t { kV1 = 1, kV2 = 2, kV3 = 3, kV4 = 4, kV5 = 5 };
/// fun_v5 from motor firmware 4.4.6 (0xB0 accepted), v4 from 4.2.3 (state requests 0x0A), v3
/// from 4.2.2, v2 from 4.2.0, else v1 (the SDK's motor_version_detection()).
BoardFunction board_function_for(const FirmwareVersion& lowest_motor_firmware) noexcept;
/// The board's own firmware in its 0x05 answer (bytes 2 and 3 of the payload: major, tenths);
/// nullopt for a payload shorter than 4 bytes.
struct BoardFirmware {
  int major = 0;
  int minor = 0;
  int tenths() const noexcept { return major * 10 + minor; }
};
std::optional<BoardFirmware> decode_board_firmware(std::span<const std::uint8_t> payload) noexcept;
/// The board's side: the 0x05 answer carrying `firmware` (bytes 0 and 1 are 0); its size.
std::size_t encode_board_firmware(BoardFirmware firmware, std::span<std::uint8_t> out) noexcept;
/// HighTorque's "General" motor constants (motor.cc mGeneral): the SDK applies them to every
/// motor of firmware major 5 whatever model the configuration names.
inline constexpr MotorScaling kGeneralBoardScaling{
    .torque_per_unit = 0.005, .torque_offset_nm = 0.0, .gain_factor = 0.5};

/// Writes one framed packet into `out`; returns its size, or 0 if it does not fit or the
/// payload exceeds kMaxBoardPayload.
std::size_t encode_board_frame(BoardCommand command, std::span<const std::uint8_t> payload,
                               std::span<std::uint8_t> out) noexcept;

/// Writes one admin packet (kResetZero, kSave, kStop, kBrake, kMotorState, kMotorState2,
/// kReloadConfig, kReboot, kVersion, kSetMotorCount) into `out`: a one-byte payload naming a
/// motor, kBroadcastId for every motor of the port (kSetMotorCount: the port's motor count).
/// Returns its size, 0 if it does not fit or `motor` is not a byte.
std::size_t encode_board_admin(BoardCommand command, int motor, std::span<std::uint8_t> out) noexcept;
/// Writes the 0x85 packet that arms every motor's command timeout: `timeout_ms` LE16 in the
/// slots of motors 1…motor_count (the SDK's canport::set_time_out). Returns its size, 0 if it
/// does not fit or motor_count is outside 1…kMaxMotorId.
std::size_t encode_board_timeout(std::uint16_t timeout_ms, int motor_count, std::span<std::uint8_t> out) noexcept;
/// The same packet with a timeout per motor (the SDK's motor::set_motorout): element i is motor
/// i + 1's, in ms (0 disarms); 0 if it does not fit or the count is outside 1…kMaxMotorId.
std::size_t encode_board_timeouts(std::span<const std::uint16_t> timeout_ms_by_motor,
                                  std::span<std::uint8_t> out) noexcept;

/// One port's command slots as the board SDK keeps them (motor.cc): a slot for every motor id
/// 1…motor_count, each the command's int16 values wide, in id order. A command other than the
/// last one resets every slot (position 0x8000, the rest 0); then each update overwrites the
/// slots of the motors it commands, and every other motor keeps the values it was last sent.
/// For kPositionVelocityTorqueKpKd / kPositionVelocityTorqueKpKdV1 (5 values),
/// kPositionVelocityKpKd (4), kPositionVelocityTorqueMax (3 values) and kPosition / kVelocity /
/// kTorque / kVoltage / kCurrent (1 value; volts and amps (float) × 10), in the
/// SDK's units and arithmetic: position 1e-4 rev, velocity 2.5e-4 rev/s, τ (τ − torque_offset_nm)
/// / torque_per_unit, gains kp / gain_factor × 10 × 2π saturated at ±32700 (NaN fields leave
/// the slot's "unset" value: position 0x8000, the rest 0).
class BoardSlotBuffer {
 public:
  /// A port whose highest motor id is `motor_count` (1…kMaxMotorId; otherwise every update fails).
  explicit BoardSlotBuffer(int motor_count) noexcept;
  /// This cycle's payload (valid until the next call), or empty — leaving the slots as they
  /// were — if the command has no slot form or a slot names a motor outside 1…motor_count or
  /// without scaling. `scaling_by_motor_id` is indexed by motor id (element 0 unused).
  std::span<const std::uint8_t> update(BoardCommand command, std::span<const BlockSlot> slots,
                                       std::span<const MotorScaling> scaling_by_motor_id) noexcept;
  /// Forgets the kept slots (a reconnected board starts from unset slots too).
  void reset() noexcept { has_command_ = false; }

 private:
  int motor_count_;
  bool has_command_ = false;
  BoardCommand command_ = BoardCommand::kPosition;
  std::array<std::uint8_t, kMaxBoardPayload> payload_{};
};

/// A motor's state record in a kMotorState2 packet: id, mode, fault, pos, vel, τ (int16);
/// kMotorState records lack mode and fault.
struct BoardMotorState {
  int motor = 0;
  std::uint8_t mode = 0;
  std::uint8_t fault = 0;
  double position_rad = 0;
  double velocity_rad_s = 0;
  double torque_nm = 0;
};
inline constexpr std::size_t kBoardStateRecordSize = 9;       // kMotorState2: id, mode, fault + 3 × int16
inline constexpr std::size_t kBoardShortStateRecordSize = 7;  // kMotorState: id + 3 × int16
/// Decodes the records of a kMotorState or kMotorState2 payload into `out` (mode and fault 0
/// for kMotorState); returns how many. Stops at a truncated record or when `out` is full; skips
/// records of motor 0 or of a motor without scaling; 0 for any other command.
std::size_t decode_board_states(BoardCommand command, std::span<const std::uint8_t> payload,
                                std::span<const MotorScaling> scaling_by_motor_id,
                                std::span<BoardMotorState> out) noexcept;
/// The board's side, for the simulator: the payload size, or 0 if it does not fit `out`, the
/// command is not a state command, or a state names a motor without scaling.
std::size_t encode_board_states(BoardCommand command, std::span<const BoardMotorState> states,
                                std::span<const MotorScaling> scaling_by_motor_id,
                                std::span<std::uint8_t> out) noexcept;
/// The board's answer to kResetZero, kSave and kReloadConfig: the ids of the motors that did it,
/// one byte each. Writes a successful CommandResult per id (id 0 skipped) into `out` and returns
/// how many; 0 for any other command.
std::size_t decode_board_acknowledgements(BoardCommand command, std::span<const std::uint8_t> payload,
                                          std::span<CommandResult> out) noexcept;
/// A kVersion answer: one [id, major, minor, patch] record per motor. Decodes into `out` and
/// returns how many; stops at a truncated record or when `out` is full; skips motor 0.
inline constexpr std::size_t kBoardVersionRecordSize = 4;
std::size_t decode_board_versions(std::span<const std::uint8_t> payload, std::span<FirmwareVersion> out) noexcept;
/// The board's side: the payload size, or 0 if it does not fit `out` or a field exceeds a byte.
std::size_t encode_board_versions(std::span<const FirmwareVersion> versions, std::span<std::uint8_t> out) noexcept;
/// The board's side: slots back into per-motor commands, one per slot in id order (kind
/// kCommand, width kInt16, query kNone; a 0x8000 position leaves has_position false, the other
/// fields are always set since the board sends 0 for them). Returns how many were written.
std::size_t decode_board_slots(BoardCommand command, std::span<const std::uint8_t> payload,
                               std::span<const MotorScaling> scaling_by_motor_id, std::span<MotorRequest> out) noexcept;

struct BoardFrame {
  BoardCommand command{};
  std::uint16_t length = 0;
  std::array<std::uint8_t, kMaxBoardPayload> payload{};
  std::span<const std::uint8_t> bytes() const { return {payload.data(), length}; }
};

/// Reassembles board packets from a byte stream (a USB-CDC tty). Skips bytes until a header,
/// drops a packet whose CRC-8 or CRC-16 fails (counted; a stray 0xF7 in garbage can count too)
/// or whose length exceeds kMaxBoardPayload, re-scans the dropped bytes for the next header, and
/// never allocates. Every byte ends up either in a packet or in skipped_bytes().
class BoardFrameSplitter {
 public:
  /// Consumes up to all of `bytes`; returns how many were consumed. It stops after a whole
  /// packet (and consumes nothing while one waits): take it with next(), then feed the rest.
  std::size_t feed(std::span<const std::uint8_t> bytes) noexcept;
  bool next(BoardFrame& out) noexcept;
  std::uint64_t crc_errors() const noexcept { return crc_errors_; }
  std::uint64_t skipped_bytes() const noexcept { return skipped_bytes_; }

 private:
  std::size_t wanted() const noexcept;       // bytes still missing from the packet being read
  void settle() noexcept;                    // checks what is buffered; may complete a packet
  void discard(std::size_t count) noexcept;  // drops `count` bytes, then up to the next header

  std::array<std::uint8_t, kBoardHeaderSize + kMaxBoardPayload> buffer_{};
  std::size_t filled_ = 0;
  bool ready_ = false;
  BoardFrame frame_{};
  std::uint64_t crc_errors_ = 0;
  std::uint64_t skipped_bytes_ = 0;
};

}  // namespace robotd::hightorque
