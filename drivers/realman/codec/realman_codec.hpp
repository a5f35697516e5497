// The RealMan arm controller's JSON protocol (../shared/protocols/realman_json.md) as plain
// values: the "\r\n" framing, the requests robotd sends, the replies and events the controller
// sends back, the UDP real-time push, the error tables, and the arm models.
//
// Everything here is in robotd's units (rad, m, rad/s, A, V, °C); the wire's integers
// (0.001°, 0.001 mm, 0.001 rad, ×1e6 quaternions, 0.001 mA …) exist only inside this codec.
// Pure functions with no I/O. Not real-time: they allocate; the driver calls them from its
// link thread, never from robotd's RT loop.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "robotd/result.hpp"

namespace robotd::realman {

inline constexpr std::size_t kMaxDof = 7;
using JointValues = std::array<double, kMaxDof>;  // the first `dof` entries are used

// ---- Units (the only place wire integers meet SI) -------------------------------------------

// The *_from_* integer conversions round to nearest; beyond int64 (or NaN) they saturate.
std::int64_t millidegrees_from_rad(double rad);  // rounds to nearest
double rad_from_millidegrees(std::int64_t millidegrees);
std::int64_t micrometres_from_m(double m);  // the wire's "0.001 mm"
double m_from_micrometres(std::int64_t micrometres);
std::int64_t milliradians_from_rad(double rad);  // Euler angles of poses
double rad_from_milliradians(std::int64_t milliradians);

// ---- Framing -------------------------------------------------------------------------------

/// What ends every message on the TCP link, and a UDP push datagram if present.
inline constexpr std::string_view kMessageTerminator = "\r\n";

/// One message as sent: compact JSON followed by "\r\n".
std::string frame(const nlohmann::json& message);

/// Splits a TCP byte stream into messages at "\r\n" (a bare "\n" inside an object is
/// whitespace, as the controller treats it). Lines longer than max_line_bytes are dropped whole
/// and counted; empty lines are skipped.
class LineSplitter {
 public:
  explicit LineSplitter(std::size_t max_line_bytes = std::size_t{64} * 1024) : max_line_bytes_(max_line_bytes) {}
  void append(std::string_view bytes);
  /// The next complete line without its "\r\n", or nullopt until one is complete.
  std::optional<std::string> next();
  std::uint64_t oversized() const { return oversized_; }
  /// Forgets any partial line (a new connection); the oversized count stays.
  void clear();

 private:
  std::string buffer_;
  std::size_t max_line_bytes_;
  bool discarding_ = false;    // inside an oversized line: drop until its "\r\n"
  bool discarded_cr_ = false;  // the last dropped byte was '\r' (its '\n' may come next)
  std::uint64_t oversized_ = 0;
};

// ---- Poses ---------------------------------------------------------------------------------

/// A pose as the controller takes it: position (m) and Euler angles rx, ry, rz (rad) in the
/// work frame (wire: µm and 0.001 rad).
struct EulerPose {
  std::array<double, 3> position_m{};
  std::array<double, 3> euler_rad{};
};

// ---- Requests (robotd → controller) --------------------------------------------------------
// Each returns the JSON object to pass to frame(). Joint arrays are sized to `joints.size()`
// (the arm's DOF). Range checks live in check_* below; these encode what they are given.

struct PlannedMove {
  int speed_percent = 20;  // "v", 1..100
  int blend_percent = 0;   // "r", 0..100
  bool trajectory_connect = false;
};

nlohmann::json movej_request(std::span<const double> joints_rad, const PlannedMove& move);
nlohmann::json movel_request(const EulerPose& pose, const PlannedMove& move);
nlohmann::json movej_p_request(const EulerPose& pose, const PlannedMove& move);

struct PassThrough {
  bool follow = true;                  // high follow (period must be ≤ 10 ms)
  std::optional<int> trajectory_mode;  // newer firmware, high follow only: 0 raw, 1 fit, 2 filter
  std::optional<int> radio;            // smoothing for trajectory_mode 1 (0..100) or 2 (0..1000)
};
nlohmann::json movej_canfd_request(std::span<const double> joints_rad, const PassThrough& pass_through);

/// {"command": name} and nothing else: queries, stops, clear_system_err.
nlohmann::json plain_request(std::string_view command);
nlohmann::json set_joint_en_state_request(int joint_number, bool enable);  // joint_number 1-based
nlohmann::json set_joint_clear_err_request(int joint_number);
nlohmann::json set_arm_power_request(bool on);

struct RealtimePushConfig {
  int cycle = 1;  // × 5 ms
  bool enable = true;
  int port = 8089;
  std::string ip;  // where the controller sends the datagrams
  bool joint_speed = false;
  bool arm_current_status = true;
  bool hand = false;
};
nlohmann::json set_realtime_push_request(const RealtimePushConfig& config);

nlohmann::json set_gripper_route_request(int min, int max);
nlohmann::json set_gripper_release_request(int speed, bool block);
nlohmann::json set_gripper_pick_request(int speed, int force, bool block);
nlohmann::json set_gripper_pick_on_request(int speed, int force, bool block);
nlohmann::json set_gripper_position_request(int position, bool block);

nlohmann::json set_hand_posture_request(int posture_number, bool block);
nlohmann::json set_hand_seq_request(int sequence_number, bool block);
nlohmann::json set_hand_angle_request(const std::array<int, 6>& angles, bool block);  // -1 = keep
nlohmann::json set_hand_speed_request(int speed);
nlohmann::json set_hand_force_request(int force);

// ---- Argument checks (clear errors, nothing sent) ------------------------------------------
// Each returns kInvalidArgument with a message naming the argument, its value and the range.

Result<void> check_speed_percent(int v);                            // 1..100
Result<void> check_blend_percent(int r);                            // 0..100
Result<void> check_gripper_route(int min, int max);                 // 0..1000 each, min ≤ max
Result<void> check_gripper_speed(int speed);                        // 1..1000
Result<void> check_gripper_force(int force);                        // 50..1000
Result<void> check_gripper_position(int position);                  // 1..1000
Result<void> check_hand_preset(std::string_view name, int number);  // 1..40
Result<void> check_hand_angles(const std::array<int, 6>& angles);   // each 0..1000 or -1
Result<void> check_hand_speed(int speed);                           // 1..1000
Result<void> check_hand_force(int force);                           // 1..1000

// ---- What comes back -----------------------------------------------------------------------

/// How a reply to `command` is recognised and judged. Replies carry no request id: they are
/// matched by the value of their "command" or "state" key.
struct ReplyShape {
  std::vector<std::string> keys;  // any of these values of "command" or "state" answers it
  std::string result_field;       // bool field that says success ("" for queries: any reply is data)
  bool has_reply = true;          // false: the controller stays silent (movej_canfd on gen 3+)
  bool completes_later = false;   // planned motions: a current_trajectory_state event follows
};
/// The shape for a command robotd sends; nullopt for a command this codec does not know.
std::optional<ReplyShape> reply_shape(std::string_view command);

enum class MessageKind {
  kReply,            // an answer to a request: key = the "command" or "state" value
  kTrajectoryEvent,  // "state": "current_trajectory_state"
  kRealtimePush,     // "state": "realtime_arm_joint_state" (UDP; the TCP port never carries it)
  kOther,            // JSON object without either key (counted, logged)
};

struct Message {
  MessageKind kind = MessageKind::kOther;
  std::string key;
  nlohmann::json body;
};
/// Parses one line. Not JSON, or JSON that is not an object → kInvalidArgument saying so with
/// the start of the text.
Result<Message> parse_message(std::string_view line);

/// The success flag of a reply: body[shape.result_field] as bool (also accepts 0/1 integers);
/// kRefused "controller refused <command>" when false; kInvalidArgument when the field is
/// missing or of another type.
Result<void> reply_success(const Message& reply, const ReplyShape& shape, std::string_view command);

enum class Device : int { kArm = 0, kGripper = 1, kHand = 2, kLift = 3, kExtension = 4 };

struct TrajectoryEvent {
  bool reached = false;  // trajectory_state
  Device device = Device::kArm;
  bool more_segments = false;  // trajectory_connect == 1 (absent = 0)
};
Result<TrajectoryEvent> parse_trajectory_event(const Message& message);

/// The controller's error codes as one list: "err" as a list or a scalar, or "arm_err" and
/// "sys_err" (every shape of §4.1). Zeros dropped; an empty list means healthy.
std::vector<std::uint16_t> collect_errors(const nlohmann::json& object);

struct ArmState {
  std::size_t dof = 0;
  JointValues joints_rad{};
  bool has_pose = false;
  EulerPose pose;
  std::vector<std::uint16_t> errors;
};
/// get_current_arm_state's reply ("arm_state": {joint, pose, errors in any shape}).
Result<ArmState> parse_current_arm_state(const Message& reply);

/// The UDP real-time push (§6.2), one datagram with or without its trailing "\r\n".
struct RealtimePush {
  std::size_t dof = 0;
  JointValues position_rad{};
  bool has_speed = false;
  JointValues speed_rad_s{};  // custom.joint_speed (unit per push_speed_unit)
  JointValues current_a{};
  JointValues voltage_v{};
  JointValues temperature_c{};
  std::array<bool, kMaxDof> enabled{};
  std::array<std::uint16_t, kMaxDof> joint_errors{};  // bitmask per joint (§7.2)
  std::vector<std::uint16_t> errors;                  // controller errors, every shape
  bool has_pose = false;
  std::array<double, 3> position_m{};
  std::array<double, 4> quaternion_wxyz{1, 0, 0, 0};
  std::array<double, 3> euler_rad{};
  std::string arm_status;  // arm_current_status when pushed ("idle", "move_J", …), else ""
};
/// The unit of joint_speed, which the sources disagree on (spec §6.2 ⚠).
enum class SpeedUnit { kCentiDegreesPerSecond, kCentiRpm, kFiftiethDegreesPerSecond };
Result<RealtimePush> parse_realtime_push(std::string_view datagram,
                                         SpeedUnit speed_unit = SpeedUnit::kCentiDegreesPerSecond);

struct GripperState {
  bool enabled = false;
  bool online = false;
  std::uint16_t error_bits = 0;
  int mode = 0;  // 1..6 (§5.1)
  int force_g = 0;
  int temperature_c = 0;
  int opening = 0;  // 0..1000
};
Result<GripperState> parse_gripper_state(const Message& reply);
std::string gripper_mode_text(int mode);             // "fully open, idle", … ; "unknown mode 9"
std::string gripper_error_text(std::uint16_t bits);  // "stall, over-temperature"; "" for 0

/// get_arm_software_info (gen 3/4, "command": "arm_software_info") or get_arm_software_version
/// (gen 2, "state": "arm_software_version").
struct SoftwareInfo {
  std::string product_version;     // "RM65-B", "RM75-6F", "GEN72-B"
  std::string controller_version;  // robot_controller_version / ctrl_info.version / Plan_version; "" if none
};
Result<SoftwareInfo> parse_software_info(const Message& reply);

// ---- Error tables (§7) ---------------------------------------------------------------------

/// "0x1002 target angle beyond joint limit"; unknown codes: "0x1234 unknown controller error".
std::string system_error_text(std::uint16_t code);
/// Clearable by clear_system_err ("general") rather than hardware ("severe"), per §7.1.
bool system_error_is_severe(std::uint16_t code);
/// "over-temperature, encoder error" for a joint's bitmask; 0xF000 → "communication frame loss".
std::string joint_error_text(std::uint16_t bits);

// ---- Arm models (§8) -----------------------------------------------------------------------

struct ArmModel {
  std::string_view name;  // "RM65", "RM75", "RML63", "ECO65", "GEN72"
  std::size_t dof;
  JointValues min_rad;
  JointValues max_rad;
  /// Its geometry (robotd::kinematics::find_arm_model), standard and six-axis force ("-6F")
  /// versions (a longer flange); "" for ECO65, whose published DH table is inconsistent.
  std::string_view kinematic_model;
  std::string_view force_kinematic_model;
};
/// The model a Product_version names ("RM65-B", "RM75-6F", "ECO65-B", "GEN72-B" …; the model
/// part before '-'); nullopt for a model not in §8.
std::optional<ArmModel> find_model(std::string_view product_version);
/// The geometry of a Product_version ("RM65-B" → "rm65", "RM65-6F" → "rm65_6f"); "" when none.
std::string_view kinematic_model_of(std::string_view product_version);
std::span<const ArmModel> known_models();

/// Pass-through rule (§3.3): a joint may move at most 10° per frame and 180 °/s.
inline constexpr double kPassThroughMaxStepRad = 10.0 * 3.14159265358979323846 / 180.0;
inline constexpr double kPassThroughMaxSpeedRadS = 180.0 * 3.14159265358979323846 / 180.0;

}  // namespace robotd::realman
