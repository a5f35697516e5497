// The AgileX PiPER CAN protocol (V2, docs/drivers/piper.md, ../shared/protocols/piper_can.md)
// as plain values: one struct per frame, in SI units (m, rad, rad/s, N·m, A, V, °C). Vendor
// units (0.001°, µm, 0.1°, …), byte order and bit packing exist only in piper_codec.cpp.
//
// Frames that carry values for a pair of joints (0x155–0x157, 0x2A5–0x2A7) or a part of a pose
// (0x152–0x154, 0x2A2–0x2A4) are one struct each with the index of the part they carry.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>

#include "robotd/transport/can_message.hpp"

namespace robotd::piper {

using transport::CanMessage;

inline constexpr int kArmJoints = 6;

// --- CAN identifiers ------------------------------------------------------------------------

namespace can_id {
inline constexpr std::uint32_t kMotionControl = 0x150;    // e-stop / resume, trajectory, drag-teach
inline constexpr std::uint32_t kModeControl = 0x151;      // ctrl mode, move mode, speed, MIT flag
inline constexpr std::uint32_t kEndPoseTarget = 0x152;    // … 0x154
inline constexpr std::uint32_t kJointTarget = 0x155;      // … 0x157
inline constexpr std::uint32_t kMoveCPoint = 0x158;       //
inline constexpr std::uint32_t kGripperControl = 0x159;   //
inline constexpr std::uint32_t kMitControl = 0x15A;       // … 0x15F, joint 1 … 6
inline constexpr std::uint32_t kMasterArmHome = 0x191;    // a leader arm (and its follower) to zero
inline constexpr std::uint32_t kArmStatus = 0x2A1;        //
inline constexpr std::uint32_t kEndPoseFeedback = 0x2A2;  // … 0x2A4
inline constexpr std::uint32_t kJointFeedback = 0x2A5;    // … 0x2A7
inline constexpr std::uint32_t kGripperFeedback = 0x2A8;  //
inline constexpr std::uint32_t kHighSpeedInfo = 0x251;    // … 0x256, joint 1 … 6
inline constexpr std::uint32_t kLowSpeedInfo = 0x261;     // … 0x266, joint 1 … 6
inline constexpr std::uint32_t kMasterSlaveConfig = 0x470;
inline constexpr std::uint32_t kMotorEnable = 0x471;
inline constexpr std::uint32_t kJointLimitQuery = 0x472;
inline constexpr std::uint32_t kJointLimitReply = 0x473;
inline constexpr std::uint32_t kJointLimitSet = 0x474;
inline constexpr std::uint32_t kJointConfig = 0x475;
inline constexpr std::uint32_t kSetAck = 0x476;
inline constexpr std::uint32_t kParamEnquiry = 0x477;
inline constexpr std::uint32_t kEndVelAccReply = 0x478;
inline constexpr std::uint32_t kEndVelAccSet = 0x479;
inline constexpr std::uint32_t kCrashProtectionSet = 0x47A;
inline constexpr std::uint32_t kCrashProtectionReply = 0x47B;
inline constexpr std::uint32_t kJointAccReply = 0x47C;
inline constexpr std::uint32_t kGripperParamSet = 0x47D;
inline constexpr std::uint32_t kGripperParamReply = 0x47E;
inline constexpr std::uint32_t kFirmware = 0x4AF;
}  // namespace can_id

// --- options the spec leaves open (⚠ in the spec; chosen per device in config) -----------------

/// MIT frame layout and mode code, which changed with firmware S-V1.8-8.
enum class MitLayout : std::uint8_t {
  kTorque8Crc,  // firmware ≤ S-V1.8-7 (SDK 0.6.1): 8-bit torque ±8, CRC nibble; move mode 0x04
  kTorque12,    // firmware ≥ S-V1.8-8 (pyAgxArm V188): 12-bit torque ±16 N·m, no CRC; move mode 0x06
};

struct CodecOptions {
  MitLayout mit_layout = MitLayout::kTorque8Crc;
  double max_speed_unit_rad_s = 0.001;  // 0x473/0x474 max joint speed (SDK; pyAgxArm says 0.01)
  double max_acc_unit_rad_s2 = 0.01;    // 0x475/0x47C max joint acc (0x475 doc, pyAgxArm; SDK's 0x47C doc says 0.001)
  double motor_position_unit_rad = 0.001;  // 0x251–0x256 position (pyAgxArm; SDK doc says rad)
  // Where MasterSlaveConfig (0x470) moved the ids (0x00, 0x10, 0x20; see id_offsets.cpp):
  std::uint8_t feedback_id_offset = 0;  // 0x2A1–0x2A8 are at 0x2B1–0x2B8 / 0x2C1–0x2C8
  std::uint8_t control_id_offset = 0;   // 0x150–0x15F are at 0x160–0x16F / 0x170–0x17F
};

// --- enumerations (wire values) ---------------------------------------------------------------

enum class ControlMode : std::uint8_t {  // 0x151 byte 0 (host) and 0x2A1 byte 0 (arm)
  kStandby = 0x00,
  kCanCommand = 0x01,
  kTeach = 0x02,  // feedback only
  kEthernet = 0x03,
  kWifi = 0x04,
  kRemote = 0x05,        // feedback only
  kLinkageTeach = 0x06,  // feedback only: a master (leader) arm
  kOfflineTrajectory = 0x07,
};

enum class MoveMode : std::uint8_t {  // 0x151 byte 1, 0x2A1 byte 2; kMit is 0x04 or 0x06 by layout
  kP = 0x00,
  kJ = 0x01,
  kL = 0x02,
  kC = 0x03,
  kMit = 0x04,
  kCpv = 0x05,
  kUnknown = 0xFF,  // decoded only: a code the configured MIT layout does not define (as the SDK)
};

enum class EmergencyStop : std::uint8_t { kNone = 0x00, kStop = 0x01, kResume = 0x02 };

enum class GripperEnable : std::uint8_t {  // 0x159 byte 6
  kDisable = 0x00,
  kEnable = 0x01,
  kDisableClearError = 0x02,
  kEnableClearError = 0x03,
};

inline constexpr std::uint8_t kMagic = 0xAE;         // "do it" flag in 0x159, 0x475, 0x477
inline constexpr std::uint8_t kMitFlag = 0xAD;       // 0x151 byte 3: MIT / high-follow
inline constexpr std::uint8_t kAllJoints = 7;        // 0x471 / 0x475 "all joints"
inline constexpr std::uint16_t kUnchanged = 0x7FFF;  // 0x474/0x475/0x479: leave this field as it is

// --- host → arm ---------------------------------------------------------------------------------

struct MotionControl {  // 0x150
  EmergencyStop emergency_stop = EmergencyStop::kNone;
  std::uint8_t track_ctrl = 0;       // 0x00 … 0x08
  std::uint8_t drag_teach_ctrl = 0;  // 0x00 … 0x07
  std::uint8_t trajectory_index = 0;
  std::uint16_t name_index = 0;
  std::uint16_t crc16 = 0;
};

struct ModeControl {  // 0x151 (also sent by a master arm)
  ControlMode ctrl_mode = ControlMode::kCanCommand;
  MoveMode move_mode = MoveMode::kJ;
  std::uint8_t speed_percent = 100;  // 0 … 100
  bool mit = false;                  // byte 3: 0xAD (MIT / high-follow) or 0x00 (position-velocity)
  std::uint8_t residence_time_s = 0;
  std::uint8_t installation = 0;  // 0 no change, 1 horizontal, 2 side left, 3 side right
};

/// Cartesian pose: position in m, orientation as roll (rx), pitch (ry), yaw (rz) in rad with
/// R = Rz(rz)·Ry(ry)·Rx(rx).
struct CartesianPose {
  double x_m = 0, y_m = 0, z_m = 0;
  double rx_rad = 0, ry_rad = 0, rz_rad = 0;
};

/// Part `part` (0: x, y; 1: z, rx; 2: ry, rz) of a pose; `first` and `second` in m or rad.
struct EndPoseTargetPart {  // 0x152 + part
  int part = 0;
  double first = 0, second = 0;
};

struct JointTargetPair {  // 0x155 + pair: joints 2·pair+1 and 2·pair+2
  int pair = 0;
  double first_rad = 0, second_rad = 0;
};

struct MoveCPoint {        // 0x158
  std::uint8_t index = 0;  // 1 start, 2 middle, 3 end
};

struct GripperControl {  // 0x159 (also sent by a master arm)
  double stroke_m = 0;   // 0.001 mm on the wire
  double effort_nm = 0;  // 0.001 N·m, 0 … 65.535 on the wire (the SDK validates 0 … 5)
  GripperEnable enable = GripperEnable::kDisable;
  bool set_zero = false;  // byte 7 = 0xAE
};

/// One joint's MIT command: torque = kp·(p − q) + kd·(v − dq) + t. `torque` is in wire units
/// (±8 for kTorque8Crc; N·m ±16 for kTorque12); the driver applies the firmware's scale.
/// Values outside the ranges below saturate at the range ends; a joint outside 1 … 6 is refused.
struct MitControl {           // 0x159 + joint
  int joint = 1;              // 1 … 6
  double position_rad = 0;    // ±12.5, 16 bit
  double velocity_rad_s = 0;  // ±45, 12 bit
  double kp = 0;              // 0 … 500, 12 bit
  double kd = 0;              // −5 … 5, 12 bit
  double torque = 0;          // 8 or 12 bit, see above
};

struct MasterSlaveConfig {           // 0x470
  std::uint8_t linkage = 0;          // 0xFA master (teach input), 0xFC slave (motion output)
  std::uint8_t feedback_offset = 0;  // 0x00, 0x10, 0x20
  std::uint8_t control_offset = 0;
  std::uint8_t linkage_offset = 0;
};

struct MotorEnable {                // 0x471
  std::uint8_t motor = kAllJoints;  // 1 … 6, 7 all
  bool enable = true;               // wire: 0x02 enable, 0x01 disable
};

struct JointLimitQuery {      // 0x472
  std::uint8_t joint = 1;     // 1 … 6
  bool acceleration = false;  // false: angle limits + max speed (→ 0x473); true: max acc (→ 0x47C)
};

/// 0x474. nullopt fields go out as 0x7FFF (unchanged); present values use the whole field, as
/// in the SDK (a present value of 0x7FFF counts reads as "unchanged" there too).
struct JointLimitSet {
  std::uint8_t joint = 1;
  std::optional<double> max_angle_rad{};  // 0.1° on the wire
  std::optional<double> min_angle_rad{};
  std::optional<double> max_speed_rad_s{};  // CodecOptions::max_speed_unit_rad_s
};

/// Bytes 3–4 always carry max_acc_rad_s2, as the SDK sends its max_joint_acc whatever the flag
/// says; byte 2 (0xAE) tells the arm to apply it.
struct JointConfig {                // 0x475
  std::uint8_t joint = kAllJoints;  // 1 … 6, 7 all
  bool set_zero = false;
  bool apply_max_acc = false;   // byte 2 = 0xAE
  double max_acc_rad_s2 = 5.0;  // bytes 3–4; the SDK's default 500 counts of 0.01 rad/s²
  bool clear_error = false;
};

struct ParamEnquiry {  // 0x477
  std::uint8_t query =
      0;  // 1 end vel/acc (→0x478), 2 crash levels (→0x47B), 3 trajectory index, 4 gripper params (→0x47E)
  std::uint8_t setting = 0;               // 1 reset end vel/acc, 2 reset all joint limits
  std::uint8_t feedback_48x = 0;          // 0 no change, 1 enable, 2 disable (pyAgxArm's code; docs/drivers/piper.md)
  std::optional<std::uint8_t> payload{};  // 0 empty, 1 half, 2 full; nullopt: byte 3 = 0, byte 4 = 0x03 (SDK default)
};

/// 0x478 (reply) and 0x479 (set): uint16 in 0.001 units. In a set, nullopt fields go out as
/// 0x7FFF and present values use the whole field (65.535 → FF FF), as in the SDK.
inline constexpr double kEndLimitUnit = 0.001;  // one count of an EndVelAcc field
struct EndVelAcc {
  std::optional<double> max_linear_velocity_m_s{};
  std::optional<double> max_angular_velocity_rad_s{};
  std::optional<double> max_linear_acceleration_m_s2{};
  std::optional<double> max_angular_acceleration_rad_s2{};
};
struct EndVelAccSet {  // 0x479
  EndVelAcc values;
};
struct EndVelAccReply {  // 0x478
  EndVelAcc values;
};

struct CrashProtectionSet {                       // 0x47A
  std::array<std::uint8_t, kArmJoints> levels{};  // 0 off, 1 … 8
};
struct CrashProtectionReply {  // 0x47B
  std::array<std::uint8_t, kArmJoints> levels{};
};

struct GripperParams {
  std::uint8_t teaching_range_percent = 100;  // 100 … 200
  std::uint8_t max_range_mm = 70;             // 0, 70, 100
  std::uint8_t teaching_friction = 1;         // 1 … 10
};
struct GripperParamSet {  // 0x47D
  GripperParams params;
};
struct GripperParamReply {  // 0x47E
  GripperParams params;
};

/// 0x191: what a leader (master) arm is asked to do, byte for byte the SDK's
/// ReqMasterArmMoveToHome modes 0, 1, 2.
enum class MasterArmHome : std::uint8_t {
  kRestoreLinkage = 0,  // 01 00 00: back to leader/follower operation
  kLeaderToZero = 1,    // 01 01 01: the leader arm moves to zero
  kBothToZero = 2,      // 01 00 01: leader and follower move to zero together
};
struct MasterArmHomeRequest {  // 0x191
  MasterArmHome mode = MasterArmHome::kRestoreLinkage;
};

/// 0x4AF both ways: the request is `01 00 …`; the reply is a burst of ASCII chunks.
struct FirmwareChunk {
  std::array<char, 8> text{};
  std::uint8_t length = 8;
};

// --- arm → host -----------------------------------------------------------------------------------

struct ArmStatus {  // 0x2A1
  ControlMode ctrl_mode = ControlMode::kStandby;
  std::uint8_t arm_status = 0;  // 0x00 normal … 0x0F (see arm_status_text)
  MoveMode mode_feed = MoveMode::kP;
  std::uint8_t teach_status = 0;
  std::uint8_t motion_status = 0;  // 0 target reached, 1 moving
  std::uint8_t trajectory_index = 0;
  std::uint8_t angle_limit_bits = 0;  // bit j-1: joint j beyond its angle limit
  std::uint8_t comm_error_bits = 0;   // bit j-1: joint j communication error
};

struct EndPoseFeedbackPart {  // 0x2A2 + part
  int part = 0;
  double first = 0, second = 0;
};

struct JointFeedbackPair {  // 0x2A5 + pair
  int pair = 0;
  double first_rad = 0, second_rad = 0;
};

struct GripperFeedback {  // 0x2A8
  double stroke_m = 0;
  double effort_nm = 0;
  std::uint8_t status_bits = 0;  // bit6 enabled, bit7 homed, bits 0–5 faults (see gripper_status_text)
  std::uint8_t reserved = 0;     // pyAgxArm: 0x01 = bytes 0–3 are an angle (0.001°)
};

struct HighSpeedInfo {  // 0x250 + joint
  int joint = 1;
  double speed_rad_s = 0;
  double current_a = 0;
  double position_rad = 0;  // CodecOptions::motor_position_unit_rad
};

struct LowSpeedInfo {  // 0x260 + joint
  int joint = 1;
  double voltage_v = 0;
  int driver_temperature_c = 0;
  int motor_temperature_c = 0;
  std::uint8_t status_bits = 0;  // bit6 enabled; see driver_status_text
  double bus_current_a = 0;
};

struct JointLimitReply {  // 0x473
  std::uint8_t joint = 1;
  double max_angle_rad = 0;
  double min_angle_rad = 0;
  double max_speed_rad_s = 0;
};

struct SetAck {              // 0x476
  std::uint8_t command = 0;  // low byte of the acknowledged ID (0x71, 0x74, …) or 0x50
  bool zero_set = false;     // byte 1 = 0x01
  std::uint8_t trajectory_index = 0;
};

struct JointAccReply {  // 0x47C
  std::uint8_t joint = 1;
  double max_acc_rad_s2 = 0;
};

// --- one decoded frame ----------------------------------------------------------------------------

using Frame =
    std::variant<MotionControl, ModeControl, EndPoseTargetPart, JointTargetPair, MoveCPoint, GripperControl, MitControl,
                 MasterSlaveConfig, MasterArmHomeRequest, MotorEnable, JointLimitQuery, JointLimitSet, JointConfig,
                 ParamEnquiry, EndVelAccSet, CrashProtectionSet, GripperParamSet, FirmwareChunk, ArmStatus,
                 EndPoseFeedbackPart, JointFeedbackPair, GripperFeedback, HighSpeedInfo, LowSpeedInfo, JointLimitReply,
                 SetAck, EndVelAccReply, CrashProtectionReply, JointAccReply, GripperParamReply>;

/// Every frame type has `CanMessage encode(const T&, const CodecOptions& = {})`: 8 data bytes,
/// standard 11-bit id, values outside their wire range saturated (never wrapped).
CanMessage encode(const MotionControl& frame, const CodecOptions& options = {});
CanMessage encode(const ModeControl& frame, const CodecOptions& options = {});
CanMessage encode(const EndPoseTargetPart& frame, const CodecOptions& options = {});
CanMessage encode(const JointTargetPair& frame, const CodecOptions& options = {});
CanMessage encode(const MoveCPoint& frame, const CodecOptions& options = {});
CanMessage encode(const GripperControl& frame, const CodecOptions& options = {});
/// Throws std::invalid_argument for a joint outside 1 … 6 (there is no frame for it).
CanMessage encode(const MitControl& frame, const CodecOptions& options = {});
CanMessage encode(const MasterSlaveConfig& frame, const CodecOptions& options = {});
/// Throws std::invalid_argument for a mode that is not one of MasterArmHome's.
CanMessage encode(const MasterArmHomeRequest& frame, const CodecOptions& options = {});
CanMessage encode(const MotorEnable& frame, const CodecOptions& options = {});
CanMessage encode(const JointLimitQuery& frame, const CodecOptions& options = {});
CanMessage encode(const JointLimitSet& frame, const CodecOptions& options = {});
CanMessage encode(const JointConfig& frame, const CodecOptions& options = {});
CanMessage encode(const ParamEnquiry& frame, const CodecOptions& options = {});
CanMessage encode(const EndVelAccSet& frame, const CodecOptions& options = {});
CanMessage encode(const CrashProtectionSet& frame, const CodecOptions& options = {});
CanMessage encode(const GripperParamSet& frame, const CodecOptions& options = {});
CanMessage encode(const FirmwareChunk& frame, const CodecOptions& options = {});
CanMessage encode(const ArmStatus& frame, const CodecOptions& options = {});
CanMessage encode(const EndPoseFeedbackPart& frame, const CodecOptions& options = {});
CanMessage encode(const JointFeedbackPair& frame, const CodecOptions& options = {});
CanMessage encode(const GripperFeedback& frame, const CodecOptions& options = {});
CanMessage encode(const HighSpeedInfo& frame, const CodecOptions& options = {});
CanMessage encode(const LowSpeedInfo& frame, const CodecOptions& options = {});
CanMessage encode(const JointLimitReply& frame, const CodecOptions& options = {});
CanMessage encode(const SetAck& frame, const CodecOptions& options = {});
CanMessage encode(const EndVelAccReply& frame, const CodecOptions& options = {});
CanMessage encode(const CrashProtectionReply& frame, const CodecOptions& options = {});
CanMessage encode(const JointAccReply& frame, const CodecOptions& options = {});
CanMessage encode(const GripperParamReply& frame, const CodecOptions& options = {});

/// Why the arm would not take this frame (the argument ranges the vendor SDK refuses), or nullptr
/// when it may be sent: a static text naming the field and what it accepts. encode() does not
/// check (it saturates); callers refuse with this text where values enter. No allocation.
const char* refusal(const MotionControl& frame, const CodecOptions& options = {});
const char* refusal(const ModeControl& frame, const CodecOptions& options = {});
const char* refusal(const MoveCPoint& frame, const CodecOptions& options = {});
const char* refusal(const GripperControl& frame, const CodecOptions& options = {});
const char* refusal(const MasterSlaveConfig& frame, const CodecOptions& options = {});
const char* refusal(const MotorEnable& frame, const CodecOptions& options = {});
const char* refusal(const JointLimitQuery& frame, const CodecOptions& options = {});
const char* refusal(const JointLimitSet& frame, const CodecOptions& options = {});
const char* refusal(const JointConfig& frame, const CodecOptions& options = {});
const char* refusal(const ParamEnquiry& frame, const CodecOptions& options = {});
const char* refusal(const EndVelAccSet& frame, const CodecOptions& options = {});
const char* refusal(const GripperParamSet& frame, const CodecOptions& options = {});

/// The frame a message carries, or nullopt for an unknown id, an extended or FD or error frame,
/// a payload shorter than the frame needs, or an MIT frame whose CRC does not match, or an id of
/// a range moved to another offset than `options` say (from_wire_id). Longer
/// payloads are read up to what the frame needs. Never throws, never allocates.
std::optional<Frame> decode(const CanMessage& message, const CodecOptions& options = {});

/// False for feedback that cannot be real, which the SDK drops (its abnormal-data filter, on by
/// default): an end pose beyond 1 m on an axis (|x|, |y|, |z| > 1e6 µm) or an angle beyond
/// 361° (0x2A2–0x2A4), a joint beyond 3000° (|q| > 3 000 000 m°, 0x2A5–0x2A7), a gripper stroke
/// beyond 150 mm (0x2A8). True for every other frame. No allocation.
bool plausible(const Frame& frame) noexcept;

// --- ids moved by MasterSlaveConfig offsets (id_offsets.cpp) ---------------------------------

/// True for the id offsets 0x470 takes: 0x00, 0x10, 0x20.
bool id_offset_valid(std::uint8_t offset) noexcept;
/// `message` with the id it has on a bus whose ids were moved by `options`' offsets: a control id
/// (0x150–0x15F) moved by control_id_offset, a feedback id (0x2A1–0x2A8) by feedback_id_offset.
/// Every frame goes through this on its way to the bus; decode() undoes it.
CanMessage to_wire(CanMessage message, const CodecOptions& options) noexcept;
/// The protocol id of a received id, or nullopt for an id of a moved range at another offset
/// (another arm's frame on a shared bus, or one whose offsets robotd was not told).
std::optional<std::uint32_t> from_wire_id(std::uint32_t wire_id, const CodecOptions& options) noexcept;
/// The offset that would make `wire_id` one of the arm's feedback (0x2A1–0x2A8) / control
/// (0x150–0x15F) ids, or nullopt: for naming the offset a silent-looking arm uses.
std::optional<std::uint8_t> feedback_offset_of(std::uint32_t wire_id) noexcept;
std::optional<std::uint8_t> control_offset_of(std::uint32_t wire_id) noexcept;

/// The firmware request (0x4AF `01 00 00 00 00 00 00 00`), which decodes as a FirmwareChunk too.
CanMessage firmware_request();
bool is_firmware_request(const CanMessage& message);

/// The three frames of a pose / of six joint targets, in bus order.
std::array<CanMessage, 3> encode_end_pose_target(const CartesianPose& pose);
std::array<CanMessage, 3> encode_joint_targets(const std::array<double, kArmJoints>& positions_rad);
std::array<CanMessage, 3> encode_end_pose_feedback(const CartesianPose& pose);
std::array<CanMessage, 3> encode_joint_feedback(const std::array<double, kArmJoints>& positions_rad);

/// Extracts the software version ("S-V1.8-2") from the concatenated 0x4AF reply text as the SDK
/// does: the 8 characters from "S-V", or fewer while the rest has not arrived; cut at the first
/// character that is not printable ASCII. nullopt while the text holds no "S-V".
std::optional<std::string> software_version(const std::string& firmware_text);
/// The MIT layout a software version implies: kTorque12 from S-V1.8-8 on.
MitLayout mit_layout_for(const std::string& software_version);

// --- text for status values -------------------------------------------------------------------------

const char* control_mode_text(ControlMode mode);
const char* move_mode_text(MoveMode mode);
const char* arm_status_text(std::uint8_t arm_status);  // "normal", "emergency stop", "collision", …
const char* teach_status_text(std::uint8_t teach_status);
/// "under-voltage, over-current" or "" for the fault bits (0–5, 7) of a 0x261–0x266 status byte.
std::string driver_status_text(std::uint8_t status_bits);
/// Same for the fault bits (0–5) of the gripper's status byte.
std::string gripper_status_text(std::uint8_t status_bits);
/// The name of one bit (0–7) of those status bytes, for code that must not allocate.
const char* driver_status_bit_text(int bit);
const char* gripper_status_bit_text(int bit);

}  // namespace robotd::piper
