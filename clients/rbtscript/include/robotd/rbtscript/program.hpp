// An RBTscript program as robotd runs it (docs/rbtscript.md): one statement per line, kept in
// the units the script was written in (degrees, mm, seconds, percent). Converting them for an
// arm, and checking them against it, is the executor's job.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace robotd::rbtscript {

/// Where a statement or an error is in the script text: 1-based line and column (in bytes).
struct SourceLocation {
  std::size_t line = 1;
  std::size_t column = 1;
  bool operator==(const SourceLocation&) const = default;
};

/// The most joint values MoveJoint takes: the arms robotd plans for have up to 7 joints. How many
/// a given arm needs is checked by the executor.
inline constexpr std::size_t kMaxJointValues = 7;

/// `func`: the velocity profile of a move.
enum class Profile { kPolynomial /* "poly" */, kTrapezoid /* "trap" */ };

/// The bare `speed` flag: follow the planned position curve (the default), or only its speed curve.
enum class Tracking { kPosition, kSpeedOnly };

/// The optional arguments of MoveJoint and MovePose, as written (v and a in percent of the
/// leading joint's maximum, t in seconds); unset when left out.
struct JointMotion {
  std::optional<double> speed_percent;         // v, in (0, 100]
  std::optional<double> acceleration_percent;  // a, in (0, 100]
  std::optional<double> duration_s;            // t, > 0; overrides v and a
  std::optional<Profile> profile;              // func
  Tracking tracking = Tracking::kPosition;     // speed
  bool operator==(const JointMotion&) const = default;
};

/// The optional arguments of MoveCart and MoveCartRelTRF (they take no v or a).
struct CartesianMotion {
  std::optional<double> duration_s;  // t, > 0
  std::optional<Profile> profile;    // func
  Tracking tracking = Tracking::kPosition;
  bool operator==(const CartesianMotion&) const = default;
};

/// A pose: position in mm, the three angles Rx, Ry, Rz in degrees (in the arm's own convention).
struct Pose {
  double x_mm = 0, y_mm = 0, z_mm = 0;
  double rx_deg = 0, ry_deg = 0, rz_deg = 0;
  bool operator==(const Pose&) const = default;
};

struct MoveJoint {
  std::vector<double> joints_deg;  // 1 … kMaxJointValues values
  JointMotion motion;
  bool operator==(const MoveJoint&) const = default;
};

struct MovePose {
  Pose pose;  // in the world frame; reached by a joint-space move
  JointMotion motion;
  bool operator==(const MovePose&) const = default;
};

struct MoveCart {
  Pose pose;  // in the world frame; reached along a straight line
  CartesianMotion motion;
  bool operator==(const MoveCart&) const = default;
};

struct MoveCartRelTrf {
  Pose delta;  // relative to the current tool frame; reached along a straight line
  CartesianMotion motion;
  bool operator==(const MoveCartRelTrf&) const = default;
};

struct Delay {
  double seconds = 0;  // >= 0
  bool operator==(const Delay&) const = default;
};

struct Begin {
  bool operator==(const Begin&) const = default;
};

struct End {
  bool operator==(const End&) const = default;
};

struct Loop {
  bool operator==(const Loop&) const = default;
};

enum class Level { kLow, kHigh };

struct Output {
  int number = 1;  // >= 1; which outputs exist is the device's business
  Level level = Level::kLow;
  bool operator==(const Output&) const = default;
};

/// Gripper_cal()
struct GripperCalibrate {
  bool operator==(const GripperCalibrate&) const = default;
};

struct Gripper {
  int position = 0;    // 0 (open) … 255 (closed)
  int speed = 0;       // 0 … 255
  int current_ma = 0;  // 0 … 1300
  bool operator==(const Gripper&) const = default;
};

using StatementKind = std::variant<MoveJoint, MovePose, MoveCart, MoveCartRelTrf, Delay, Begin, End, Loop, Output,
                                   GripperCalibrate, Gripper>;

struct Statement {
  StatementKind kind;
  SourceLocation location;  // of the statement's name
  std::string text;         // the statement as written, without surrounding blanks or comment
};

struct Program {
  std::vector<Statement> statements;
};

}  // namespace robotd::rbtscript
