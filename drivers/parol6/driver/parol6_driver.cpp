// Parol6Driver: configuration, the serial link's lifecycle and the RT read/write path.
#include "driver/parol6_driver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <utility>

#include "codec/joint_units.hpp"
#include "driver/parol6_ops.hpp"
#include "kinematics/parol6_kinematics.hpp"
#include "robotd/driver/monotonic_clock.hpp"

namespace robotd::parol6 {
namespace {

using driver::monotonic_now_ns;

using namespace std::chrono_literals;

constexpr std::size_t kTrajectoryCapacity = 12'000;  // 120 s at 100 Hz
constexpr std::size_t kSettleFrames = 30;            // a finished move holds its end point this long
constexpr int kMaxReadsPerTick = 8;                  // 4 KiB: far more than a 10 ms exchange carries

}  // namespace

// --- configuration ------------------------------------------------------------------------------

Result<void> Parol6Driver::configure(const nlohmann::json& params) {
  auto parsed = parse_parol6_params(params);
  if (!parsed) return parsed.error();
  params_ = std::move(parsed.value());
  port_ = std::make_unique<transport::SerialPort>(params_.serial);
  std::snprintf(link_name_.data(), link_name_.size(), "%s", port_->describe().c_str());
  exchange_period_ns_ = static_cast<std::int64_t>(std::llround(1e9 / params_.exchange_rate_hz));
  planner_.set_period(1.0 / params_.exchange_rate_hz);
  trajectory_.reserve(kTrajectoryCapacity);
  Peripherals peripherals;
  peripherals.gripper_id = static_cast<std::uint8_t>(params_.gripper_id);
  peripherals.gripper_speed = static_cast<std::int16_t>(params_.gripper_speed);
  peripherals.gripper_current_ma = static_cast<std::int16_t>(std::lround(params_.gripper_current_a * 1000));
  peripherals_.store(peripherals);
  rt_peripherals_ = peripherals;
  not_connected_fault_.set(kNotConnectedFault, "not connected (connect() or recover() first)");
  configured_ = true;
  return {};
}

driver::DeviceDescription Parol6Driver::describe() const {
  driver::DeviceDescription description;
  description.model = params_.model;
  description.kinematic_model = kArmModelName;
  description.native_rate_hz = params_.exchange_rate_hz;
  for (int j = 0; j < kJoints; ++j) {
    description.joints.push_back(
        {"joint" + std::to_string(j + 1), params_.limits[static_cast<std::size_t>(j)], 0.0, 0.0});
  }
  // Steppers under position control: no torque, no damping, no letting go (they stay energised).
  description.supports_torque = false;
  description.supports_damping = false;
  description.supports_zero_torque = false;
  description.has_end_pose = true;
  description.ops = op_descriptions();
  return description;
}

// --- link lifecycle (non-RT) ------------------------------------------------------------------

Result<void> Parol6Driver::connect() {
  if (!configured_) return make_error(ErrorCode::kRefused, "connect: the parol6 driver is not configured");
  abort_.clear();
  const std::lock_guard lock(link_mutex_);
  return connect_locked();
}

Result<void> Parol6Driver::connect_locked() {
  auto connected = open_and_check_link();
  if (!connected) {
    const std::string text = "not connected: " + connected.error().message;
    not_connected_fault_.set(kNotConnectedFault, text.c_str());
  }
  return connected;
}

Result<void> Parol6Driver::open_and_check_link() {
  connected_.store(false);
  port_->close();
  if (auto opened = port_->open(); !opened) return opened.error();
  port_->flush();
  parser_.reset();
  have_reply_ = false;
  have_previous_reply_ = false;
  velocity_rad_s_.fill(0);
  if (auto answered = await_first_reply(std::chrono::milliseconds(params_.connect_timeout_ms)); !answered) {
    port_->close();
    return answered.error();
  }
  planner_.reset();
  trajectory_.abort();
  one_shot_.store(params_.home_on_connect ? OneShot::kHome : OneShot::kNone);
  next_exchange_ns_ = 0;
  last_reply_ns_ = monotonic_now_ns();
  last_frame_ns_ = last_reply_ns_;
  reply_pending_delivery_ = true;  // the first read() hands over the reply connect() received
  link_lost_.store(false);
  connected_.store(true);
  publish_snapshot();
  return {};
}

Result<void> Parol6Driver::await_first_reply(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  HostFrame idle;  // IDLE: the board moves nothing and answers
  while (std::chrono::steady_clock::now() < deadline) {
    if (!send_frame(idle)) {
      return make_error(ErrorCode::kNotAvailable, std::string(link_name_.data()) + " closed while connecting");
    }
    if (!abort_.sleep_for(10ms)) return driver::aborted_error("waiting for the board's first reply");
    bool closed = false;
    if (drain_replies(monotonic_now_ns(), closed)) return {};
    if (closed) {
      return make_error(ErrorCode::kNotAvailable, std::string(link_name_.data()) + " closed while connecting");
    }
  }
  return make_error(ErrorCode::kNotAvailable,
                    "no answer from the PAROL6 board on " + std::string(link_name_.data()) + " within " +
                        std::to_string(timeout.count()) +
                        " ms: is the board powered (its 24 V supply, not only USB) and running its firmware?");
}

void Parol6Driver::send_final_idle() noexcept {
  // The board keeps its last command forever: leave it one that moves nothing.
  HostFrame idle;
  if (have_reply_) idle.position_steps = reply_.position_steps;
  (void)send_frame(idle);
}

void Parol6Driver::disconnect() noexcept {
  const std::lock_guard lock(link_mutex_);
  if (connected_.load() && !link_lost_.load()) send_final_idle();
  connected_.store(false);
  if (port_) port_->close();
}

Result<void> Parol6Driver::recover() {
  if (!configured_) return make_error(ErrorCode::kRefused, "recover: the parol6 driver is not configured");
  abort_.clear();
  const std::lock_guard lock(link_mutex_);
  if (!connected_.load() || link_lost_.load()) return abort_.verdict(connect_locked(), "recover");
  return {};  // the board reports no faults to clear; clear_error resets its homing state
}

Result<void> Parol6Driver::reset_zero(std::span<const int> /*joints*/) {
  return make_error(ErrorCode::kRefused,
                    "the PAROL6 has no settable zero: homing sets every joint's counter from its limit switch "
                    "(robotctl call <device> home)");
}

// --- RT path ------------------------------------------------------------------------------------

driver::IoResult Parol6Driver::link_lost(driver::FaultInfo& fault, const char* why) noexcept {
  if (!link_lost_.load(std::memory_order_relaxed)) {
    std::array<char, 144> text{};  // fits FaultInfo::text
    std::snprintf(text.data(), text.size(), "%.80s on %.50s", why, link_name_.data());
    lost_fault_.set(kLinkLostFault, text.data());
    link_lost_.store(true);
    publish_snapshot();
  }
  fault = lost_fault_;  // the first reason, until the link is back
  return driver::IoResult::kDisconnected;
}

bool Parol6Driver::drain_replies(std::int64_t now_ns, bool& closed) noexcept {
  const std::uint64_t before = replies_;
  std::array<std::uint8_t, 512> bytes{};
  closed = false;
  for (int i = 0; i < kMaxReadsPerTick; ++i) {
    std::size_t count = 0;
    const transport::SerialIo result = port_->read(bytes, count);
    closed = result == transport::SerialIo::kClosed;
    if (result != transport::SerialIo::kDone) break;
    parser_.feed(std::span<const std::uint8_t>(bytes.data(), count),
                 [&](std::span<const std::uint8_t> body) { apply_reply(body, now_ns); });
  }
  return replies_ != before;
}

void Parol6Driver::apply_reply(std::span<const std::uint8_t> body, std::int64_t now_ns) noexcept {
  // Without a CRC, a damaged LEN can make a longer false frame pass the end-byte check: only
  // a body of the board's own length is a reply.
  if (body.size() != kRobotLength) return;
  const auto decoded = decode_robot_body(body);
  if (!decoded) return;
  previous_reply_ = reply_;
  have_previous_reply_ = have_reply_;
  reply_ = *decoded;
  have_reply_ = true;
  last_reply_ns_ = now_ns;
  ++replies_;
  // Speed from the change of the step counters over the board's own measure of the time
  // between the two frames they were sampled at (the reported speed is only a set point).
  const double dt_s = reply_.timing_ticks * kTimingTickSeconds;
  if (!have_previous_reply_ || dt_s <= 0) return;
  for (int j = 0; j < kJoints; ++j) {
    const auto index = static_cast<std::size_t>(j);
    const double steps = reply_.position_steps[index] - previous_reply_.position_steps[index];
    velocity_rad_s_[index] = steps_to_rad(j, steps) / dt_s;
  }
}

driver::IoResult Parol6Driver::read(driver::Feedback& out, driver::FaultInfo& fault) noexcept {
  if (!connected_.load(std::memory_order_acquire)) {
    fault = not_connected_fault_;
    return driver::IoResult::kDisconnected;
  }
  if (link_lost_.load(std::memory_order_relaxed)) return link_lost(fault, "");
  const std::int64_t now_ns = monotonic_now_ns();
  // The board only ever answers: while robotd does not call write() (before its first feedback,
  // during a fault), keep the exchange going with IDLE frames.
  if (now_ns - last_frame_ns_ > 2 * exchange_period_ns_) {
    HostFrame idle;
    if (have_reply_) idle.position_steps = reply_.position_steps;
    if (!send_frame(idle)) return link_lost(fault, "serial line closed");
    last_frame_ns_ = now_ns;
  }
  bool closed = false;
  bool fresh = drain_replies(now_ns, closed);
  if (closed) return link_lost(fault, "serial line closed");
  fresh = fresh || std::exchange(reply_pending_delivery_, false);
  const std::int64_t silence_ns = now_ns - last_reply_ns_;
  if (silence_ns > static_cast<std::int64_t>(params_.reply_timeout_ms) * 1'000'000) {
    std::array<char, 80> why{};
    std::snprintf(why.data(), why.size(), "no reply from the board for %lld ms",
                  static_cast<long long>(silence_ns / 1'000'000));
    return link_lost(fault, why.data());
  }
  publish_snapshot();
  if (!fresh) return driver::IoResult::kNoNewData;
  fill_feedback(out);
  return driver::IoResult::kOk;
}

void Parol6Driver::fill_feedback(driver::Feedback& out) noexcept {
  out.joint_count = kJoints;
  JointVector q{};
  for (int j = 0; j < kJoints; ++j) {
    const auto index = static_cast<std::size_t>(j);
    q[index] = steps_to_rad(j, reply_.position_steps[index]);
    out.joints[index] = {q[index], velocity_rad_s_[index], 0.0};  // steppers report no torque
  }
  out.estop_input = reply_.estop_pressed();
  const Pose pose = forward_kinematics(q);
  const Eigen::Quaterniond orientation(transform_of(pose).rotation());
  out.has_end_pose = true;
  out.end_pose.position_m = {pose.x_m, pose.y_m, pose.z_m};
  out.end_pose.orientation_xyzw = {orientation.x(), orientation.y(), orientation.z(), orientation.w()};
}

driver::IoResult Parol6Driver::write(const driver::CommandFrame& command, driver::FaultInfo& fault) noexcept {
  if (!connected_.load(std::memory_order_acquire)) {
    fault = not_connected_fault_;
    return driver::IoResult::kDisconnected;
  }
  const std::int64_t now_ns = command.tick_deadline_ns;
  // robotd counts an e-stop frame as delivered when write() returns: it goes out now, not at
  // the next exchange (up to a period later).
  if (command.estop && !estop_) next_exchange_ns_ = std::min(next_exchange_ns_, now_ns);
  estop_ = command.estop;
  if (now_ns < next_exchange_ns_) return driver::IoResult::kOk;
  next_exchange_ns_ = std::max(next_exchange_ns_ + exchange_period_ns_, now_ns + exchange_period_ns_ / 2);

  PlannerInput input;
  input.command = &command;
  input.board = have_reply_ ? &reply_ : nullptr;
  input.one_shot = one_shot_.exchange(OneShot::kNone, std::memory_order_acq_rel);
  Peripherals peripherals;
  if (peripherals_.try_load(peripherals)) rt_peripherals_ = peripherals;
  input.peripherals = rt_peripherals_;
  input.peripherals.gripper_mode = gripper_mode_once_.exchange(0, std::memory_order_acq_rel);
  const bool session =
      std::any_of(command.joints.begin(), command.joints.begin() + static_cast<std::ptrdiff_t>(command.joint_count),
                  [](const driver::JointCommand& joint) { return joint.owned; });
  const bool board_estop = have_reply_ && reply_.estop_pressed();
  if (session || command.estop || board_estop) {
    trajectory_.abort();  // a session or an e-stop ends an op's move
  } else {
    input.trajectory = trajectory_.next(kSettleFrames);
  }
  const HostFrame frame = planner_.plan(input);
  if (!send_frame(frame)) return link_lost(fault, "serial line closed");
  last_frame_ns_ = now_ns;
  return driver::IoResult::kOk;
}

bool Parol6Driver::send_frame(const HostFrame& frame) noexcept {
  const auto bytes = encode(frame);
  std::size_t written = 0;
  const transport::SerialIo result = port_->write(bytes, written);
  if (result == transport::SerialIo::kClosed) return false;
  // A full kernel buffer drops this frame (the board then skips one exchange); nothing to retry.
  ++frames_sent_;
  last_command_sent_ = frame.command;
  return true;
}

void Parol6Driver::publish_snapshot() noexcept {
  BoardSnapshot snapshot;
  snapshot.link_up = connected_.load(std::memory_order_relaxed) && !link_lost_.load(std::memory_order_relaxed);
  snapshot.have_reply = have_reply_;
  snapshot.reply = reply_;
  snapshot.last_command_sent = last_command_sent_;
  snapshot.session_streaming = planner_.streaming_session();
  snapshot.estop = estop_;
  snapshot.frames_sent = frames_sent_;
  snapshot.replies = replies_;
  snapshot.rejected = parser_.rejected();
  snapshot.discarded = parser_.discarded();
  snapshot_.store(snapshot);
}

}  // namespace robotd::parol6
