// Moves planned by ops: jog, move_joints (MoveJoint), move_pose (MovePose), move_cart
// (MoveCart); and stop, fk.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include "codec/joint_units.hpp"
#include "driver/parol6_ops.hpp"
#include "robotd/motion/cartesian_move.hpp"

namespace robotd::parol6 {
namespace {

using namespace std::chrono_literals;

constexpr auto kCancelTimeout = 200ms;
constexpr auto kSessionEndWait = 300ms;  // three exchanges at the slowest exchange_rate_hz, 10 Hz

nlohmann::json pose_json(const Pose& pose) {
  return {{"x_m", pose.x_m},
          {"y_m", pose.y_m},
          {"z_m", pose.z_m},
          {"roll_rad", pose.roll_rad},
          {"pitch_rad", pose.pitch_rad},
          {"yaw_rad", pose.yaw_rad}};
}

motion::Joints as_joints(const JointVector& q) { return {q.begin(), q.end()}; }

std::optional<JointVector> joints_argument(JsonReader& reader, bool required) {
  if (required) reader.require("joints_rad", "6 joint angles in rad");
  const auto given = reader.number_array("joints_rad");
  if (!given) return std::nullopt;
  if (given->size() != kJoints) {
    reader.error("joints_rad", "expected 6 numbers, got " + std::to_string(given->size()));
    return std::nullopt;
  }
  JointVector q{};
  std::copy(given->begin(), given->end(), q.begin());
  return q;
}

}  // namespace

JointVector Parol6Ops::measured() const {
  const BoardSnapshot snapshot = driver_.snapshot();
  JointVector q{};
  for (int j = 0; j < kJoints; ++j) {
    q[static_cast<std::size_t>(j)] = steps_to_rad(j, snapshot.reply.position_steps[static_cast<std::size_t>(j)]);
  }
  return q;
}

JointVector Parol6Ops::joint_min() const {
  JointVector q{};
  for (std::size_t j = 0; j < kJoints; ++j) q[j] = driver_.params_.limits[j].position_min_rad;
  return q;
}

JointVector Parol6Ops::joint_max() const {
  JointVector q{};
  for (std::size_t j = 0; j < kJoints; ++j) q[j] = driver_.params_.limits[j].position_max_rad;
  return q;
}

motion::JointLimits Parol6Ops::limits() const {
  motion::JointLimits limits;
  for (const auto& joint : driver_.params_.limits) {
    limits.min_rad.push_back(joint.position_min_rad);
    limits.max_rad.push_back(joint.position_max_rad);
    limits.max_speed_rad_s.push_back(joint.velocity_max_rad_s);
    limits.max_acceleration_rad_s2.push_back(joint.acceleration_max_rad_s2);
  }
  return limits;
}

double Parol6Ops::period_s() const { return 1.0 / driver_.params_.exchange_rate_hz; }

std::optional<Error> Parol6Ops::check_no_session_streams(std::string_view op) const {
  // robotd runs the ops that need free motors with no session on the device and grants none
  // meanwhile; one released just before may still stream until the next exchange.
  const auto deadline = std::chrono::steady_clock::now() + kSessionEndWait;
  while (driver_.snapshot().session_streaming && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(1ms);
  }
  if (!driver_.snapshot().session_streaming) return std::nullopt;
  return make_error(ErrorCode::kRefused, std::string(op) + ": a session is driving the arm; release it first");
}

std::optional<Error> Parol6Ops::check_can_move(std::string_view op, bool needs_homed) const {
  const BoardSnapshot snapshot = driver_.snapshot();
  const std::string name(op);
  if (!snapshot.link_up || !snapshot.have_reply) {
    return make_error(ErrorCode::kNotAvailable, name + ": the board is not connected");
  }
  if (snapshot.estop || snapshot.reply.estop_pressed()) {
    return make_error(ErrorCode::kRefused, name + ": an e-stop is engaged (robotd's or the board's input)");
  }
  if (auto refused = check_no_session_streams(op)) return refused;
  if (needs_homed && !snapshot.reply.all_homed()) {
    return make_error(ErrorCode::kRefused, name +
                                               ": the arm is not homed, so its joint positions mean nothing yet "
                                               "(robotctl call <device> home)");
  }
  return std::nullopt;
}

Result<nlohmann::json> Parol6Ops::run(std::string_view op, const std::vector<JointVector>& samples) {
  if (samples.size() > driver_.trajectory_.capacity()) {
    return make_error(ErrorCode::kInvalidArgument, std::string(op) + ": the move takes " +
                                                       std::to_string(samples.size() / 100) + " s; at most 120 s fit");
  }
  if (!driver_.trajectory_.cancel(kCancelTimeout)) {
    return make_error(ErrorCode::kTimeout, std::string(op) + ": the device loop is not running");
  }
  // Each frame asks for the next sample with the speed that reaches it by the next frame.
  const double period_s = this->period_s();
  std::vector<StepTarget> targets(samples.size());
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const JointVector& next = samples[std::min(k + 1, samples.size() - 1)];
    for (int j = 0; j < kJoints; ++j) {
      const auto index = static_cast<std::size_t>(j);
      targets[k].position_steps[index] = rad_to_steps(j, next[index]);
      targets[k].speed_steps_s[index] = rad_per_s_to_steps_per_s(j, (next[index] - samples[k][index]) / period_s);
    }
  }
  driver_.trajectory_.load(targets);
  driver_.trajectory_.publish();
  return nlohmann::json{{"started", op}, {"duration_s", static_cast<double>(samples.size() - 1) * period_s}};
}

Result<nlohmann::json> Parol6Ops::run(std::string_view op, const Result<motion::Trajectory>& plan) {
  if (!plan) return make_error(ErrorCode::kRefused, std::string(op) + ": " + plan.error().message);
  std::vector<JointVector> samples(plan.value().positions.size());
  for (std::size_t k = 0; k < samples.size(); ++k) {
    std::copy_n(plan.value().positions[k].begin(), kJoints, samples[k].begin());
  }
  return run(op, samples);
}

Result<nlohmann::json> Parol6Ops::jog(const nlohmann::json& args) {
  OpArguments arguments("jog", args);
  JsonReader& reader = arguments.reader();
  reader.require("joint", "1 … 6");
  reader.require("velocity_rad_s", "a signed speed in rad/s");
  const auto joint = reader.integer("joint", 1, kJoints);
  const auto velocity = reader.number("velocity_rad_s");
  const double duration = reader.number_or("duration_s", 1.0, NumberRange{.min = 0.01, .max = 10});
  if (joint && velocity) {
    const auto index = static_cast<std::size_t>(*joint - 1);
    const double jog_max = steps_per_s_to_rad_per_s(static_cast<int>(index), joint_units()[index].jog_max_steps_s);
    if (std::fabs(*velocity) > jog_max) {
      reader.error("velocity_rad_s", "expected at most " + std::to_string(jog_max) + " rad/s in magnitude for joint " +
                                         std::to_string(*joint) + ", got " + std::to_string(*velocity));
    }
  }
  if (auto error = arguments.finish()) return *error;
  if (auto refused = check_can_move("jog", /*needs_homed=*/false)) return *refused;
  // A jog is planned as positions, never sent as JOG (123): if robotd stops, it stops.
  const auto index = static_cast<std::size_t>(*joint - 1);
  const BoardSnapshot snapshot = driver_.snapshot();
  const bool homed = snapshot.reply.all_homed();
  JointVector to = measured();
  to[index] += *velocity * duration;
  if (homed) {
    to[index] = std::clamp(to[index], joint_min()[index], joint_max()[index]);  // never past a limit, like CMD
  }
  motion::MoveTiming timing;
  timing.duration_s = std::max(duration, period_s() * 3);
  timing.shape = motion::Shape::kTrapezoid;
  return run("jog", motion::plan_joint_move(as_joints(measured()), as_joints(to), timing, limits(), period_s()));
}

Result<nlohmann::json> Parol6Ops::move_joints(const nlohmann::json& args) {
  OpArguments arguments("move_joints", args);
  const auto target = joints_argument(arguments.reader(), /*required=*/true);
  const motion::MoveTiming timing = arguments.timing();
  if (target) {
    for (std::size_t j = 0; j < kJoints; ++j) {
      if ((*target)[j] < joint_min()[j] || (*target)[j] > joint_max()[j]) {
        arguments.reader().error("joints_rad", "joint " + std::to_string(j + 1) + " at " +
                                                   std::to_string((*target)[j]) + " rad is outside its limits [" +
                                                   std::to_string(joint_min()[j]) + ", " +
                                                   std::to_string(joint_max()[j]) + "]");
      }
    }
  }
  if (auto error = arguments.finish()) return *error;
  if (auto refused = check_can_move("move_joints", /*needs_homed=*/true)) return *refused;
  return run("move_joints",
             motion::plan_joint_move(as_joints(measured()), as_joints(*target), timing, limits(), period_s()));
}

Result<nlohmann::json> Parol6Ops::move_pose(const nlohmann::json& args) {
  OpArguments arguments("move_pose", args);
  const auto target = arguments.pose();
  const motion::MoveTiming timing = arguments.timing();
  if (auto error = arguments.finish()) return *error;
  if (auto refused = check_can_move("move_pose", /*needs_homed=*/true)) return *refused;
  const auto plan = motion::plan_pose_move(parol6_model(), as_joints(measured()), transform_of(*target), timing,
                                           limits(), period_s());
  auto started = run("move_pose", plan);
  if (started) started.value()["joints_rad"] = plan.value().positions.back();
  return started;
}

Result<nlohmann::json> Parol6Ops::move_cart(const nlohmann::json& args) {
  OpArguments arguments("move_cart", args);
  const auto target = arguments.pose();
  motion::MoveTiming timing = arguments.timing();
  motion::LineOptions line;
  line.linear_speed_m_s = arguments.reader().number_or("linear_speed_m_s", motion::kDefaultLinearSpeedMS,
                                                       NumberRange{.min = 0.001, .max = 0.2});
  if (auto error = arguments.finish()) return *error;
  if (auto refused = check_can_move("move_cart", /*needs_homed=*/true)) return *refused;
  // A line takes t or its tool speed; the fractions time joint moves only.
  timing.speed_percent.reset();
  timing.acceleration_percent.reset();
  return run("move_cart", motion::plan_line_move(parol6_model(), as_joints(measured()), transform_of(*target), timing,
                                                 limits(), period_s(), line));
}

Result<nlohmann::json> Parol6Ops::stop(const nlohmann::json& args) {
  OpArguments arguments("stop", args);
  if (auto error = arguments.finish()) return *error;
  const bool was_running = driver_.trajectory_.running();
  if (!driver_.trajectory_.cancel(kCancelTimeout)) {
    return make_error(ErrorCode::kTimeout, "stop: the device loop is not running");
  }
  return nlohmann::json{{"stopped", was_running}};
}

Result<nlohmann::json> Parol6Ops::fk(const nlohmann::json& args) {
  OpArguments arguments("fk", args);
  const auto given = joints_argument(arguments.reader(), /*required=*/false);
  if (auto error = arguments.finish()) return *error;
  const JointVector q = given ? *given : measured();
  return nlohmann::json{
      {"joints_rad", q}, {"source", given ? "given" : "measured"}, {"tool", pose_json(forward_kinematics(q))}};
}

}  // namespace robotd::parol6
