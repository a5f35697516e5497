// cart_jog: the commander's Cartesian jog (its X/Y/Z and Rx/Ry/Rz buttons in the world (WRF) or
// tool (TRF) frame) as a timed straight-line move of the tool: like the joint jog it is planned
// as positions, so it ends where planned even if robotd stops.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "driver/parol6_ops.hpp"
#include "robotd/motion/cartesian_move.hpp"

namespace robotd::parol6 {
namespace {

// The commander's Cartesian jog maxima (PAROL6_ROBOT.py): 60 mm/s and 25°/s.
constexpr double kMaxLinearJogMps = 0.06;
constexpr double kMaxAngularJogRadS = 25.0 * std::numbers::pi / 180.0;

/// `pose` moved by `amount` (m, or rad for the rotations) along or about axis `axis` (0 … 5, the
/// order of the op's "axis" choices) of the base frame (about the tool point) or of the tool frame.
Eigen::Isometry3d jogged(const Eigen::Isometry3d& pose, std::size_t axis, double amount, bool tool_frame) {
  const Eigen::Vector3d direction = Eigen::Vector3d::Unit(static_cast<Eigen::Index>(axis % 3));
  Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
  if (axis < 3) {
    delta.translate(direction * amount);
  } else {
    delta.rotate(Eigen::AngleAxisd(amount, direction));
  }
  if (tool_frame) return pose * delta;
  Eigen::Isometry3d moved = pose;
  moved.linear() = delta.linear() * pose.linear();
  moved.translation() += delta.translation();
  return moved;
}

}  // namespace

Result<nlohmann::json> Parol6Ops::cart_jog(const nlohmann::json& args) {
  OpArguments arguments("cart_jog", args);
  JsonReader& reader = arguments.reader();
  reader.require("axis", R"("x", "y", "z" (velocity in m/s) or "rx", "ry", "rz" (rad/s))");
  reader.require("velocity", "a signed speed: m/s along x/y/z, rad/s about rx/ry/rz");
  const std::vector<std::string> axes{"x", "y", "z", "rx", "ry", "rz"};  // indices as jogged() takes them
  const auto axis_name = reader.string("axis", axes);
  const auto velocity = reader.number("velocity");
  const double duration = reader.number_or("duration_s", 1.0, NumberRange{.min = 0.05, .max = 10});
  const std::string frame = reader.string_or("frame", "base", {"base", "tool"});
  const auto axis = static_cast<std::size_t>(std::find(axes.begin(), axes.end(), axis_name.value_or("")) -
                                             axes.begin());  // axes.size() if none
  if (velocity && axis < axes.size()) {
    const double limit = axis < 3 ? kMaxLinearJogMps : kMaxAngularJogRadS;
    if (std::fabs(*velocity) > limit) {
      reader.error("velocity", "expected at most " + std::to_string(limit) + (axis < 3 ? " m/s" : " rad/s") +
                                   " in magnitude (the commander's jog maximum), got " + std::to_string(*velocity));
    }
  }
  if (auto error = arguments.finish()) return *error;
  if (auto refused = check_can_move("cart_jog", /*needs_homed=*/true)) return *refused;
  const JointVector from = measured();
  const Eigen::Isometry3d target = jogged(tool_transform(from), axis, *velocity * duration, frame == "tool");
  motion::MoveTiming timing;
  timing.duration_s = duration;
  timing.shape = motion::Shape::kTrapezoid;
  motion::LineOptions line;
  line.linear_speed_m_s = kMaxLinearJogMps;
  return run("cart_jog", motion::plan_line_move(parol6_model(), {from.begin(), from.end()}, target, timing, limits(),
                                                period_s(), line));
}

}  // namespace robotd::parol6
