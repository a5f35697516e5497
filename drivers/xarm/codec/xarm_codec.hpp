// The UFACTORY xArm controller's private TCP protocol (../shared/protocols/xarm_tcp.md) as plain
// values: the Modbus-TCP-style frames of the command port (502), the status byte, the requests
// robotd sends and the replies it reads (and the other direction, for the simulator), the
// unsolicited motion-feedback frames, the report ports' packets (30000, 30001, 30003), the error
// and warning tables, and the arm models.
//
// Everything here is in robotd's units (m, rad, m/s, rad/s, s, N·m); the wire's millimetres exist
// only inside this codec. Byte order as the spec says: headers, counts and report sizes
// big-endian; fp32 parameters little-endian. Pure functions with no I/O. Not real-time: they
// allocate; the driver calls them from its link thread, never from robotd's RT loop.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "robotd/result.hpp"

namespace robotd::xarm {

inline constexpr std::size_t kMaxDof = 7;
/// Joint arrays always carry 7 values on the wire; xArm 5 and 6 (and Lite 6, 850) leave the tail 0.
using JointValues = std::array<double, kMaxDof>;
using Bytes = std::vector<std::uint8_t>;
using ByteView = std::span<const std::uint8_t>;

// ---- Wire primitives -----------------------------------------------------------------------

/// Appends values in wire order. f32 rounds a double to IEEE-754 single (inf and NaN pass).
class ByteWriter {
 public:
  ByteWriter& u8(std::uint8_t value);
  ByteWriter& u16_be(std::uint16_t value);
  ByteWriter& u32_be(std::uint32_t value);
  ByteWriter& u64_be(std::uint64_t value);
  ByteWriter& f32_le(double value);
  ByteWriter& bytes(ByteView data);
  const Bytes& data() const { return bytes_; }
  Bytes take() { return std::move(bytes_); }

 private:
  Bytes bytes_;
};

/// Reads values in wire order from the front; nullopt (and nothing consumed) past the end.
class ByteReader {
 public:
  explicit ByteReader(ByteView data) : data_(data) {}
  std::optional<std::uint8_t> u8();
  std::optional<std::uint16_t> u16_be();
  std::optional<std::uint32_t> u32_be();
  std::optional<std::uint64_t> u64_be();
  std::optional<double> f32_le();
  std::size_t remaining() const { return data_.size() - offset_; }
  std::size_t offset() const { return offset_; }

 private:
  ByteView data_;
  std::size_t offset_ = 0;
};

// ---- Registers (§4) ------------------------------------------------------------------------

enum class Register : std::uint8_t {
  kGetVersion = 1,
  kGetRobotSn = 2,
  kMotionEnable = 11,
  kSetState = 12,
  kGetState = 13,
  kGetCmdnum = 14,
  kGetErrCode = 15,
  kCleanErr = 16,
  kCleanWar = 17,
  kSetBrake = 18,
  kSetMode = 19,
  kMoveLine = 21,
  kMoveLineB = 22,
  kMoveJoint = 23,
  kMoveJointB = 24,
  kMoveGohome = 25,
  kSleepInstruction = 26,
  kMoveCircle = 27,
  kMoveLineTool = 28,
  kServoJ = 29,
  kServoCartesian = 30,
  kSetTcpJerk = 31,
  kSetTcpMaxAcc = 32,
  kSetJointJerk = 33,
  kSetJointMaxAcc = 34,
  kSetTcpOffset = 35,
  kSetLoadParam = 36,
  kSetCollisionSensitivity = 37,
  kSetTeachSensitivity = 38,
  kCleanConf = 39,
  kSaveConf = 40,
  kGetTcpPose = 41,
  kGetJointPos = 42,
  kGetIk = 43,
  kGetFk = 44,
  kIsJointLimit = 45,
  kIsTcpLimit = 46,
  kGetReducedMode = 49,  // fw ≥ 1.2.0
  kSetReducedMode = 50,
  kServoGetDbmsg = 106,
  kToolModbus = 124,  // RS485_RTU: a Modbus RTU frame to a device on the tool's RS-485 bus
  kToolGpioError = 125,
  kToolWrite16 = 127,  // TGPIO_W16B: a 16-bit register of the tool board or the gripper
  kToolRead16 = 128,   // TGPIO_R16B
  kToolWrite32 = 129,  // TGPIO_W32B
  kToolRead32 = 130,   // TGPIO_R32B
  kFeedbackCheck = 253,
  kSetFeedbackType = 254,
  kMotionFeedback = 255,  // unsolicited frames only (§2.5)
};

/// "move_line", "get_err_code" …; "register 99" for a number this table does not name.
std::string register_name(std::uint8_t reg);
/// Planned and servo motions (21–30): they succeed only when the arm can move (§2.3).
bool is_motion_register(std::uint8_t reg);
/// Registers whose success puts the arm into state 5 "system reset" (motion stopped, cache
/// cleared) until set_state(0): 11, 16, 18, 19, 35, 37, 38 (§3.2, seed [Reset System]).
bool resets_system(std::uint8_t reg);
/// Planned motions that queue in the command cache and answer with its count (21–28).
bool is_queued_motion(std::uint8_t reg);

// ---- Framing (§2) --------------------------------------------------------------------------

inline constexpr std::uint16_t kProtocolPrivate = 2;
inline constexpr std::uint16_t kProtocolKeepAlive = 3;  // fw ≥ 1.8.6; framing identical
inline constexpr std::size_t kHeaderBytes = 6;          // transaction id, protocol id, length
/// No request or reply of this protocol comes near this; a larger length field means the stream
/// lost its framing.
inline constexpr std::size_t kMaxFrameBytes = 2048;

/// One frame in either direction. `body` is what follows the register byte: a request's
/// parameters, or a reply's status byte and data.
struct Frame {
  std::uint16_t transaction_id = 0;
  std::uint16_t protocol = kProtocolPrivate;
  std::uint8_t reg = 0;
  Bytes body;
};

/// Header + register + body; the length field = 1 + body size.
Bytes encode_frame(const Frame& frame);

/// Re-frames a TCP byte stream (§2.2 rule: when ≥ 6 bytes, frame size = length + 6). A length
/// field of 0 or one that would exceed kMaxFrameBytes cannot be resynchronised: next() returns
/// kInvalidArgument saying so, and keeps returning it until clear().
class FrameSplitter {
 public:
  void append(ByteView bytes);
  /// The next complete frame, nullopt until one is complete, or the framing error.
  Result<std::optional<Frame>> next();
  /// Forgets buffered bytes and any framing error (a new connection).
  void clear();
  std::size_t buffered() const { return buffer_.size(); }

 private:
  Bytes buffer_;
  std::optional<std::string> broken_;
};

// ---- Status byte (§2.3) and execution states (seed Appendix I, spec §6.4) -------------------

struct StatusBits {
  bool invalid = false;    // 0x08: result invalid / execution failed
  bool not_ready = false;  // 0x10: the arm cannot move (not enabled, stopped, reset)
  bool warning = false;    // 0x20: a warning is active
  bool error = false;      // 0x40: an error is active
};
StatusBits decode_status(std::uint8_t byte);
std::uint8_t encode_status(const StatusBits& bits);

/// A reply from the command port.
struct Reply {
  std::uint16_t transaction_id = 0;
  std::uint16_t protocol = kProtocolPrivate;
  std::uint8_t reg = 0;
  std::uint8_t status_byte = 0;
  StatusBits status;
  Bytes data;  // after the status byte
};
/// kInvalidArgument when the frame has no status byte, or is a motion-feedback frame (0xFF).
Result<Reply> parse_reply(const Frame& frame);
/// The simulator's side: a reply frame with `status_byte` then `data`.
Frame reply_frame(std::uint16_t transaction_id, std::uint16_t protocol, std::uint8_t reg, std::uint8_t status_byte,
                  ByteView data = {});

/// Execution state codes as the SDK computes them (Appendix I of the seed; §6.4).
enum ExecutionState : int {
  kExecOk = 0,
  kExecErrorActive = 1,
  kExecWarningActive = 2,
  kExecTimeout = 3,
  kExecLengthError = 4,
  kExecTransactionMismatch = 5,
  kExecProtocolMismatch = 6,
  kExecRegisterMismatch = 7,
  kExecSendFailed = 8,
  kExecNotReady = 9,
  kExecInvalidResult = 10,
  kExecOther = 11,
  kExecParameterError = 12,
};
/// The code for a reply (§2.3 order): invalid → 10; error → 1; warning → 2; for a motion
/// register, not_ready → 9; else 0.
int execution_state(const Reply& reply);
/// "normal", "xArm has an error code", "xArm has a warning code", "communication timed out",
/// "instruction parsing error (length)" …, "not ready to move (not enabled, stopped or reset)";
/// "unknown execution state 42".
std::string execution_state_text(int code);
/// Whether the SDK counts `code` as success for this register: motion registers only 0 (and 2,
/// a warning); other registers 0, 1, 2 and 9 (the status bits are information only there).
bool execution_succeeded(std::uint8_t reg, int code);

// ---- Motion states and modes (§3) ----------------------------------------------------------

enum MotionState : int {
  kStateStart = 0,  // set only: ready for motion commands
  kStateMoving = 1,
  kStateSleeping = 2,
  kStatePaused = 3,
  kStateStopped = 4,
  kStateReset = 5,     // configuration changed: not ready until set_state(0)
  kStateSlowStop = 6,  // set only, newer firmware: decelerate to stop
};
enum Mode : int {
  kModePosition = 0,
  kModeServo = 1,
  kModeJointTeach = 2,
  kModeCartesianTeach = 3,
  kModeJointVelocity = 4,
  kModeCartesianVelocity = 5,
  kModeJointOnline = 6,
  kModeCartesianOnline = 7,
};
/// "moving", "sleeping", "paused", "stopped", "system reset (set state 0 to continue)";
/// "unknown state 9".
std::string motion_state_text(int state);
/// "position", "servo", "joint teaching", … ; "unknown mode 12".
std::string mode_text(int mode);

// ---- Poses ---------------------------------------------------------------------------------

/// A TCP pose: position (m) and roll, pitch, yaw (rad), fixed axes X-Y-Z
/// (R = Rz(yaw)·Ry(pitch)·Rx(roll)), in the base frame. On the wire: mm and rad.
struct Pose {
  std::array<double, 3> position_m{};
  std::array<double, 3> rpy_rad{};
};

// ---- Requests robotd sends (reg + parameters) ----------------------------------------------
// Each returns the frame's register and body; the caller sets transaction id and protocol.
// They encode what they are given; argument range checks live in check_* below.

struct Request {
  std::uint8_t reg = 0;
  Bytes params;
};
/// Registers without parameters: get_version, get_robot_sn, get_state, get_cmdnum, get_err_code,
/// clean_err, clean_war, clean_conf, save_conf, get_tcp_pose, get_joint_pos, get_reduced_mode,
/// servo_get_dbmsg, feedback_check.
Request plain_request(Register reg);
Request motion_enable_request(int joint, bool enable);  // joint 1–7, 8 = all
Request set_state_request(int state);                   // 0, 3, 4, 6
Request set_mode_request(int mode);
/// release: true = brake released (motor detached; the joint can fall), false = brake engaged.
/// Wire value 1 = release, 0 = engage (both SDKs; the seed calls 1 "enable the joint brake").
Request set_brake_request(int joint, bool release);

struct LineMove {
  Pose pose;
  double speed_m_s = 0.1;
  double acc_m_s2 = 2.0;
  double mvtime_s = 0;        // "currently not meaningful" (seed): 0
  double blend_radius_m = 0;  // move_lineb only
};
Request move_line_request(const LineMove& move);   // legacy 9-float form (the seed's)
Request move_lineb_request(const LineMove& move);  // 10 floats

struct JointMove {
  JointValues joints_rad{};
  double speed_rad_s = 0.35;
  double acc_rad_s2 = 8.0;
  double mvtime_s = 0;
};
Request move_joint_request(const JointMove& move);
/// Only speed, acc and mvtime are used.
Request move_gohome_request(const JointMove& move);
Request sleep_instruction_request(double seconds);
/// Reduced mode on or off (the controller's reduced TCP and joint speeds, boundary and ranges).
Request set_reduced_mode_request(bool on);
/// The motion feedback (§2.5) this connection wants for the commands it sends next: a bitmask of
/// the kFeedback* types (0 none). The controller binds the mask to each command as it arrives.
Request set_feedback_type_request(std::uint8_t types);
/// servo_j: 7 joint angles + 3 reserved zeros (speed, acc, time).
Request servo_j_request(const JointValues& joints_rad);

Request set_tcp_jerk_request(double jerk_m_s3);
Request set_tcp_maxacc_request(double acc_m_s2);
Request set_joint_jerk_request(double jerk_rad_s3);
Request set_joint_maxacc_request(double acc_rad_s2);
Request set_tcp_offset_request(const Pose& offset);
Request get_fk_request(const JointValues& joints_rad);
Request is_joint_limit_request(const JointValues& joints_rad);

// ---- Requests as the controller reads them (the simulator's side) ---------------------------
// Each takes a request frame's body; kInvalidArgument names the register, the byte count found
// and the count expected. Longer bodies (newer firmware's trailing flags) are accepted.

struct JointSwitch {
  int joint = 0;  // 1–7, 8 = all
  bool on = false;
};
Result<JointSwitch> parse_motion_enable(ByteView params);
Result<JointSwitch> parse_set_brake(ByteView params);  // on = brake released
/// One u8 parameter (set_state, set_mode; set_mode's optional detection byte is ignored).
Result<int> parse_u8_param(std::uint8_t reg, ByteView params);
/// move_line (9 floats, or the 10-float common form with its radius) and move_lineb (10).
Result<LineMove> parse_line_move(std::uint8_t reg, ByteView params);
/// move_joint (10 floats: 7 joints, speed, acc, mvtime).
Result<JointMove> parse_joint_move(ByteView params);
/// move_gohome (3 floats: speed, acc, mvtime).
Result<JointMove> parse_gohome(ByteView params);
/// servo_j, get_fk, is_joint_limit: the first 7 floats.
Result<JointValues> parse_joint_params(std::uint8_t reg, ByteView params);
/// set_tcp_offset: 6 floats.
Result<Pose> parse_pose_params(std::uint8_t reg, ByteView params);
/// One float in robotd's units: sleep_instruction (s), set_tcp_jerk (m/s³), set_tcp_maxacc
/// (m/s²), set_joint_jerk (rad/s³), set_joint_maxacc (rad/s²).
Result<double> parse_scalar_param(std::uint8_t reg, ByteView params);

// ---- Reply data (both sides) ---------------------------------------------------------------
// parse_* take a Reply's data; kInvalidArgument names the register and the sizes. encode_* make
// the data a simulator sends. Text fields come back as printable ASCII, other bytes as '?'.

struct Version {
  int axes = 0;
  int type = 0;  // device type code (§7)
  std::string robot_sn;
  std::string control_box_sn;
  std::string firmware;  // "2.3.0" (without the leading 'v')
};
/// 40 bytes, NUL padded: "axis,type,robotSN,controlboxSN,vMAJ.MIN.REV" (SDK order, §8).
Result<Version> parse_version(ByteView data);
Bytes encode_version(const Version& version);

/// 40 bytes: the robot's SN, NUL, the control box's SN, NUL padded (§4.1).
struct SerialNumbers {
  std::string robot_sn;
  std::string control_box_sn;
};
Result<SerialNumbers> parse_robot_sn(ByteView data);
/// Cut at 40 bytes, as encode_version.
Bytes encode_robot_sn(const SerialNumbers& serials);

Result<int> parse_state(ByteView data);  // get_state
Bytes encode_state(int state);
Result<std::uint16_t> parse_cmdnum(ByteView data);  // get_cmdnum; also the count after a queued motion
Bytes encode_cmdnum(std::uint16_t count);
struct ErrorWarning {
  int error = 0;
  int warning = 0;
};
Result<ErrorWarning> parse_err_code(ByteView data);
Bytes encode_err_code(const ErrorWarning& codes);
Result<Pose> parse_pose(ByteView data);  // get_tcp_pose, get_fk: 6 floats, mm → m
Bytes encode_pose(const Pose& pose);
Result<JointValues> parse_joints(ByteView data);  // get_joint_pos: 7 floats
Bytes encode_joints(const JointValues& joints_rad);
Result<bool> parse_limit_flag(ByteView data);  // is_joint_limit: 1 = outside the limits
Bytes encode_limit_flag(bool outside);
Result<bool> parse_reduced_mode(ByteView data);  // get_reduced_mode: 1 = on
Bytes encode_reduced_mode(bool on);

struct ServoStatus {
  int state = 0;  // 0 normal, 1 error detected, 3 communication failure
  int error = 0;  // servo error code (§6.3)
};
/// Joints 1–7 then the gripper. Accepts the SDKs' 16 bytes and the doc example's 17 (a leading
/// execution-status byte, skipped) — §8.
Result<std::array<ServoStatus, 8>> parse_servo_dbmsg(ByteView data);
Bytes encode_servo_dbmsg(const std::array<ServoStatus, 8>& servos);  // the SDKs' 16 bytes

// ---- The tool's RS-485 bus and the xArm gripper (registers 124–130) -----------------------
// Register 124 carries a Modbus RTU frame without its CRC, after the tool board's host id; the
// reply carries the host id and the device's Modbus reply (UFACTORY xArm Gripper user manual
// §3.4.3, "Private TCP"). Registers 127–130 read and write one register of the tool board (host id
// 9) or the gripper (id 8) directly: u8 id, u16 address, and for a write an fp32 value; a read
// answers a 4-byte big-endian integer.

inline constexpr std::uint8_t kToolHostId = 9;
inline constexpr std::uint8_t kGripperId = 8;
inline constexpr std::uint8_t kModbusReadHolding = 0x03;
inline constexpr std::uint8_t kModbusWriteMultiple = 0x10;
/// The tool board's RS-485 baud rate register (read with 128 at host id 9): an index into
/// kToolBaudRates.
inline constexpr std::uint16_t kToolBaudRateAddress = 0x0A0B;
inline constexpr std::array<int, 13> kToolBaudRates = {4800,   9600,   19200,   38400,   57600,   115200, 230400,
                                                       460800, 921600, 1000000, 1500000, 2000000, 2500000};

/// The xArm gripper's Modbus registers (16-bit; positions take two, high word first).
enum class GripperRegister : std::uint16_t {
  kStatus = 0x0000,  // bits 0–1: 0 stopped, 1 moving, 2 gripping (firmware ≥ 3.4.3)
  kErrorCode = 0x000F,
  kEnable = 0x0100,
  kMode = 0x0101,  // 0 position
  kResetError = 0x0109,
  kSpeed = 0x0303,  // r/min
  kTargetPosition = 0x0700,
  kPosition = 0x0702,
  kVersionMajor = 0x0801,  // then minor 0x0802, patch 0x0803
};
/// The status register's bits 0–1 (the SDK tests `status & 0x03`; its check_catch_gripper_status
/// waits for 2).
enum GripperStatus : int {
  kGripperStopped = 0,  // at its target (or never moved)
  kGripperMoving = 1,
  kGripperGripping = 2,  // stopped short of its target on an object
};
inline constexpr std::uint16_t kGripperStatusBits = 0x03;
/// Gripper positions in pulses: 0 closed, 850 open (the SDK's and Studio's range: -10 … 850).
inline constexpr int kGripperMinPulses = -10;
inline constexpr int kGripperMaxPulses = 850;
inline constexpr int kGripperMaxSpeedRpm = 5000;

/// A Modbus function a device on the tool's bus is asked to run.
struct ToolModbusRequest {
  std::uint8_t host_id = kToolHostId;
  std::uint8_t slave = kGripperId;
  std::uint8_t function = kModbusReadHolding;
  std::uint16_t address = 0;
  std::uint16_t count = 0;            // registers read or written
  std::vector<std::uint16_t> values;  // written (function 0x10)
};
/// Read `count` holding registers from `address` (function 0x03).
Request tool_modbus_read_request(std::uint8_t slave, std::uint16_t address, std::uint16_t count);
/// Write `values` from `address` (function 0x10).
Request tool_modbus_write_request(std::uint8_t slave, std::uint16_t address, std::span<const std::uint16_t> values);
/// The registers a read returned; kInvalidArgument for a Modbus exception (naming its code), a
/// reply from another device or function, or a wrong byte count.
Result<std::vector<std::uint16_t>> parse_tool_modbus_read_reply(ByteView data, std::uint8_t slave, std::uint16_t count);
/// kInvalidArgument unless the reply echoes the write (device, function, address, count).
Result<void> parse_tool_modbus_write_reply(ByteView data, std::uint8_t slave, std::uint16_t address,
                                           std::uint16_t count);
/// The simulator's side: the request in register 124's parameters (functions 0x03 and 0x10).
Result<ToolModbusRequest> parse_tool_modbus_request(ByteView params);
Bytes encode_tool_modbus_read_reply(std::uint8_t slave, std::span<const std::uint16_t> values);
Bytes encode_tool_modbus_write_reply(std::uint8_t slave, std::uint16_t address, std::uint16_t count);
/// Modbus exception `code` (1 function, 2 address, 3 value) for `function`.
Bytes encode_tool_modbus_exception(std::uint8_t slave, std::uint8_t function, std::uint8_t code);

/// Registers 127–130: one register of the tool board or the gripper.
struct ToolRegisterAccess {
  std::uint8_t id = kToolHostId;
  std::uint16_t address = 0;
  double value = 0;  // writes only
};
/// Register 128: read one 16-bit register of device `id` (the tool board 9, the gripper 8).
Request tool_register_read_request(std::uint8_t id, std::uint16_t address);
/// 128 / 130: id and address. 127 / 129: id, address and the fp32 value (a trailing byte, the
/// SDK's "sync" flag, is accepted).
Result<ToolRegisterAccess> parse_tool_register_access(std::uint8_t reg, ByteView params);
Bytes encode_tool_register_value(std::int32_t value);
Result<std::int32_t> parse_tool_register_value(ByteView data);

// ---- Unsolicited motion feedback (§2.5) ----------------------------------------------------

/// set_feedback_type's bits (the SDK's FeedbackType): a motion started / finished or was discarded,
/// a non-motion task triggered, a non-motion task (trajectory save, load, play) started / finished.
inline constexpr std::uint8_t kFeedbackMotionStart = 0x01;
inline constexpr std::uint8_t kFeedbackMotionFinish = 0x02;
inline constexpr std::uint8_t kFeedbackTrigger = 0x04;
inline constexpr std::uint8_t kFeedbackOtherStart = 0x20;
inline constexpr std::uint8_t kFeedbackOtherFinish = 0x40;
inline constexpr std::uint8_t kFeedbackTypes =
    kFeedbackMotionStart | kFeedbackMotionFinish | kFeedbackTrigger | kFeedbackOtherStart | kFeedbackOtherFinish;

struct MotionFeedback {
  std::uint16_t transaction_id = 0;  // of the command it refers to
  int type = 0;                      // 1 started, 2 finished or discarded, 4 non-motion task triggered
  std::uint8_t command_reg = 0;
  std::uint16_t task_id = 0;
  int code = 0;  // 0 ok, 2 discarded
  std::uint64_t controller_time_us = 0;
};
bool is_motion_feedback(const Frame& frame);  // register byte 0xFF
Result<MotionFeedback> parse_motion_feedback(const Frame& frame);
Frame motion_feedback_frame(const MotionFeedback& feedback, std::uint16_t protocol = kProtocolPrivate);

// ---- Report ports (§5) ---------------------------------------------------------------------

enum class ReportKind : std::uint8_t {
  kReal,      // port 30003, 100 Hz, 87 or 135 bytes
  kNormal,    // port 30001, 5 Hz, 133 or 145 bytes
  kRealtime,  // port 30000, fw ≥ 2.1.0, 250 Hz, 784 bytes (the SDK's 804 accepted)
  kRich,      // port 30002, 5 Hz, the SDK's default: normal + 100 bytes; 245 bytes or more
};
/// "real", "normal", "realtime", "rich"; parse_report_kind is its inverse (nullopt otherwise).
std::string_view report_kind_name(ReportKind kind);
std::optional<ReportKind> parse_report_kind(std::string_view name);
std::uint16_t default_report_port(ReportKind kind);  // 30003, 30001, 30000

inline constexpr std::size_t kMaxReportBytes = 4096;

/// Splits a report stream at its u32 big-endian size prefix (which counts itself). A size
/// below 8 or above kMaxReportBytes cannot be resynchronised: kInvalidArgument until clear().
class ReportSplitter {
 public:
  void append(ByteView bytes);
  Result<std::optional<Bytes>> next();
  void clear();

 private:
  Bytes buffer_;
  std::optional<std::string> broken_;
};

/// A rich report's motion limits, in robotd's units (TCP: m/s³, m/s², m/s; joints: rad/s³,
/// rad/s², rad/s).
struct MotionLimits {
  double jerk = 0;
  double min_acc = 0;
  double max_acc = 0;
  double min_speed = 0;
  double max_speed = 0;
};

/// What the rich report (port 30002) adds to the normal one, offsets 145–244 (§5.3).
struct RichFields {
  int device_type = 0;  // §7, as get_version's
  int axes = 0;
  std::string firmware;  // "2.3.0", NUL padded to 30 bytes on the wire
  MotionLimits tcp;
  MotionLimits joint;
  double rotation_jerk = 0;
  double rotation_max_acc = 0;
  std::array<ServoStatus, 8> servos{};  // joints 1–7, then the tool (servo_get_dbmsg's order)
};

struct Report {
  int state = 0;  // low nibble of state_mode
  int mode = 0;   // high nibble
  std::uint16_t cmd_num = 0;
  JointValues position_rad{};
  bool has_velocity = false;  // kRealtime only
  JointValues velocity_rad_s{};
  JointValues effort{};  // kReal, kNormal: joint torques (N·m) or currents (A) after reg 70;
                         // kRealtime: estimated torques (N·m)
  Pose tcp_pose;
  bool has_codes = false;  // kNormal only: the fields below
  int error_code = 0;
  int warning_code = 0;
  std::uint8_t brake_mask = 0;   // bit i = joint i+1's brake released
  std::uint8_t enable_mask = 0;  // bit i = joint i+1 enabled
  bool has_settings = false;     // kNormal only: the fields below
  Pose tcp_offset;               // from the flange
  double payload_kg = 0;
  std::array<double, 3> payload_centre_m{};   // centre of mass
  int collision_sensitivity = 0;              // 0 (off) … 5
  int teach_sensitivity = 0;                  // 0 … 5
  bool has_gravity_direction = false;         // kNormal 145-byte packets only
  std::array<double, 3> gravity_direction{};  // in the base frame; (0, 0, -1) on a floor
  bool has_timestamp = false;                 // kRealtime only
  std::uint64_t timestamp_us = 0;
  bool has_force_torque = false;         // kReal 135-byte packets, kRealtime
  std::array<double, 6> force_torque{};  // filtered external wrench (N, N·m)
  bool has_targets = false;              // kRealtime only: the joint targets the arm follows
  JointValues target_position_rad{};
  JointValues target_velocity_rad_s{};
  bool has_rich = false;  // kRich only
  RichFields rich;
};
/// One whole packet (its size prefix included). kInvalidArgument when the size field disagrees
/// with the packet, the size is not one this kind has, or state ≥ 10 / mode ≥ 12 (the SDK's
/// sanity checks).
Result<Report> parse_report(ByteView packet, ReportKind kind);
/// The simulator's side: kReal 135 bytes when with_force_torque else 87; kNormal 145 (with the
/// gravity direction); kRealtime 784; kRich 245 (what follows on newer firmware is not encoded). Fields a kind does not
/// carry are ignored, whatever the has_* flags say.
Bytes encode_report(const Report& report, ReportKind kind, bool with_force_torque = false);

// ---- Error tables (§6) ---------------------------------------------------------------------

/// "C23 joint angle exceeds limit"; "C99 unknown controller error"; "" for 0.
std::string controller_error_text(int code);
/// "W11 command cache full"; "W99 unknown warning"; "" for 0.
std::string controller_warning_text(int code);
/// "joint over-current"; "servo error 99" when unknown; "" for 0.
std::string servo_error_text(int code);
/// Errors 1–3 are e-stops (box button, e-stop IO, enabling switch): clean_err does not end them
/// while the input is held.
bool is_estop_error(int code);

// ---- Arm models (§7) -----------------------------------------------------------------------

struct ArmModel {
  std::string_view name;     // "xarm5", "xarm6", "xarm7", "lite6", "uf850", "xarm6-x8" …
  std::string_view display;  // "xArm 6", "Lite 6", "UFACTORY 850"
  std::size_t dof = 0;
  int type_code = 0;  // the device type the controller reports (§7)
  JointValues min_rad{};
  JointValues max_rad{};
  double max_tcp_speed_m_s = 1.0;  // Lite 6: 0.5
  /// Its geometry (robotd::kinematics::find_arm_model): "xarm5", "xarm6" (every 6-joint type but
  /// Lite 6 and 850), "xarm7", "lite6", "uf850".
  std::string_view kinematic_model;
};
/// By robotd's name (case-insensitive); nullopt for a name §7 does not list.
std::optional<ArmModel> find_model(std::string_view name);
/// By the controller's axis count and type code (get_version, rich report).
std::optional<ArmModel> model_for_type(int axes, int type_code);
std::span<const ArmModel> known_models();

/// Joint speed limit of every model (§7: 180 °/s); servo_j steps beyond it fail on the arm.
inline constexpr double kMaxJointSpeedRadS = 3.14159265358979323846;

// ---- Argument checks (clear errors, nothing sent) ------------------------------------------
// kInvalidArgument with a message naming the argument, its value and the accepted range.

Result<void> check_joint_selector(int joint, std::size_t dof);          // 1..dof, or 8 (all)
Result<void> check_tcp_speed(double speed_m_s, const ArmModel& model);  // (0, max_tcp_speed]
Result<void> check_tcp_acc(double acc_m_s2);                            // (0, 50] m/s²
Result<void> check_tcp_jerk(double jerk_m_s3);                          // (0, 100] m/s³
Result<void> check_joint_speed(double speed_rad_s);                     // (0, π] rad/s
Result<void> check_joint_acc(double acc_rad_s2);                        // (0, 20] rad/s² (1145 °/s²)
Result<void> check_joint_jerk(double jerk_rad_s3);                      // (0, 500] rad/s³ (28647 °/s³)
Result<void> check_sleep(double seconds);                               // [0, 3600] s
/// The model's limits, forgiving 1e-6 rad beyond them: a value sent exactly at a limit arrives
/// (or is read back) a hair beyond it after the wire's fp32 rounding.
Result<void> check_joints_within(const JointValues& joints_rad, const ArmModel& model);

}  // namespace robotd::xarm
