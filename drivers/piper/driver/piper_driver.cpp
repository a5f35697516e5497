// PiperDriver: configuration, the link's lifecycle and the RT read/write path.
#include "driver/piper_driver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>

#include "driver/piper_ops.hpp"
#include "kinematics/piper_kinematics.hpp"
#include "robotd/driver/monotonic_clock.hpp"
#include "robotd/transport/can_interface_check.hpp"

namespace robotd::piper {
namespace {

using driver::monotonic_now_ns;

using namespace std::chrono_literals;

constexpr int kMaxFramesPerRead = 512;  // ~1 ms of a saturated bus; the rest waits a tick
constexpr std::uint32_t kPiperBitrate = 1'000'000;
constexpr std::int64_t kNsPerSecond = 1'000'000'000;
constexpr std::size_t kFirmwareReplyBytes = 88;  // 11 frames (spec §5.14)

bool is_reply(std::uint32_t id) {
  switch (id) {
    case can_id::kJointLimitReply:
    case can_id::kSetAck:
    case can_id::kEndVelAccReply:
    case can_id::kCrashProtectionReply:
    case can_id::kJointAccReply:
    case can_id::kGripperParamReply:
    case can_id::kFirmware:
      return true;
    default:
      return false;
  }
}

}  // namespace

// --- configuration ------------------------------------------------------------------------------

Result<void> PiperDriver::configure(const nlohmann::json& params) {
  auto parsed = parse_piper_params(params);
  if (!parsed) return parsed.error();
  params_ = std::move(parsed.value());
  codec_ = params_.codec;
  for (std::size_t j = 0; j < kArmJoints; ++j) configured_limits_[j] = params_.joints[j].limits;
  transport_ = transport::make_can_transport(params_.can);
  const std::string name = transport_->describe();
  std::snprintf(link_name_.data(), link_name_.size(), "%s", name.c_str());
  streamer_.configure(params_, codec_);
  configured_ = true;
  return {};
}

driver::DeviceDescription PiperDriver::describe() const {
  driver::DeviceDescription description;
  description.model = params_.model;
  description.kinematic_model = arm_model_name(params_.dh);
  description.native_rate_hz = params_.command_rate_hz;
  const std::lock_guard lock(limits_mutex_);
  for (std::size_t j = 0; j < params_.joint_count(); ++j) {
    const PiperJointParams& joint = params_.joint(j);
    description.joints.push_back({joint.name, joint.limits, joint.default_kp, joint.default_kd});
  }
  // MIT mode gives torque, damping (kp = 0) and zero torque (kp = kd = 0) on J1–J6.
  description.supports_torque = true;
  description.supports_damping = true;
  description.supports_zero_torque = true;
  description.has_end_pose = true;
  description.ops = op_descriptions();
  if (params_.leader()) {
    description.supports_torque = false;
    description.supports_damping = false;
    description.supports_zero_torque = false;
    description.read_only_reason = kLeaderIsReadOnly;
  }
  return description;
}

// --- link lifecycle (non-RT) ------------------------------------------------------------------

Result<void> PiperDriver::connect() {
  if (!configured_) return make_error(ErrorCode::kRefused, "connect: the piper driver is not configured");
  abort_.clear();
  const std::lock_guard lock(link_mutex_);
  return connect_locked();
}

Result<void> PiperDriver::connect_locked() {
  auto connected = open_and_check_link();
  if (!connected) {
    // What read() reports until a connect succeeds; the loop is not running now.
    const std::string text = "not connected: " + connected.error().message;
    not_connected_fault_.set(kNotConnectedFault, text.c_str());
  }
  return connected;
}

Result<void> PiperDriver::open_and_check_link() {
  connected_.store(false);
  transport_->close();
  if (params_.can.kind == transport::CanLinkConfig::Kind::kSocketCan && params_.check_interface) {
    if (auto checked = transport::check_can_interface(params_.can.interface, kPiperBitrate); !checked) {
      return checked.error();
    }
  }
  if (auto opened = transport_->open(); !opened) return opened.error();
  arm_ = ArmState{};
  if (auto fed = await_arm_frames(std::chrono::milliseconds(params_.connect_timeout_ms)); !fed) {
    transport_->close();
    return fed.error();
  }
  // A leader is only listened to: no queries, and its firmware and limits do not matter.
  if (params_.firmware == "auto" && !params_.leader()) detect_firmware();
  if (!abort_.requested() && !params_.leader()) read_arm_limits();
  if (abort_.requested()) {
    transport_->close();
    return driver::aborted_error("reading the arm's firmware version and limits");
  }
  streamer_.configure(params_, codec_);
  replies_.clear();
  rate_window_start_ns_ = 0;
  link_lost_.store(false);
  connected_.store(true);
  publish_snapshot();
  return {};
}

void PiperDriver::drain_link_blocking_free(std::int64_t now_ns) {
  CanMessage message;
  while (transport_->receive(message) == transport::CanIo::kDone) {
    ++rx_frames_;
    if (is_reply(message.id)) (void)replies_.push(message);
    if (message.id == can_id::kFirmware && !is_firmware_request(message)) {
      firmware_text_.append(reinterpret_cast<const char*>(message.data.data()), message.length);  // NOLINT
    }
    if (const auto frame = decode(message, codec_)) {
      apply_frame(arm_, *frame, now_ns);
    } else {
      note_moved_ids(message.id);
    }
  }
}

void PiperDriver::detect_firmware() {
  firmware_text_.clear();
  firmware_note_.clear();
  if (send(firmware_request()) != transport::CanIo::kDone) {
    firmware_note_ = "could not send the firmware query (0x4AF)";
    return;
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(params_.reply_timeout_ms);
  while (std::chrono::steady_clock::now() < deadline && firmware_text_.size() < kFirmwareReplyBytes) {
    drain_link_blocking_free(monotonic_now_ns());
    if (!abort_.sleep_for(1ms)) return;
  }
  if (const auto version = software_version(firmware_text_)) {
    codec_.mit_layout = mit_layout_for(*version);
    return;
  }
  codec_.mit_layout = MitLayout::kTorque8Crc;
  firmware_note_ =
      "no answer to the firmware query (0x4AF): MIT frames use the S-V1.8-7 layout; set "
      "params.firmware if the arm runs S-V1.8-8 or newer";
}

void PiperDriver::disconnect() noexcept {
  const std::lock_guard lock(link_mutex_);
  connected_.store(false);
  if (transport_) transport_->close();
}

Result<void> PiperDriver::recover() {
  if (!configured_) return make_error(ErrorCode::kRefused, "recover: the piper driver is not configured");
  abort_.clear();
  const std::lock_guard lock(link_mutex_);
  if (!connected_.load() || link_lost_.load()) return abort_.verdict(connect_locked(), "recover");
  if (params_.leader()) return {};  // a leader reports no errors, and robotd sends it nothing
  return abort_.verdict(clear_arm_errors(), "recover");
}

Result<void> PiperDriver::clear_arm_errors() {
  drain_link_blocking_free(monotonic_now_ns());
  const bool gripper_enabled = (arm_.gripper.status_bits & 0x40U) != 0;
  const bool arm_estop = arm_.status.arm_status == 0x01;
  send(encode(JointConfig{.joint = kAllJoints, .clear_error = true}, codec_));
  if (params_.gripper) {
    send(encode(GripperControl{.stroke_m = arm_.gripper.stroke_m,
                               .effort_nm = params_.gripper_effort_nm,
                               .enable = gripper_enabled ? GripperEnable::kEnableClearError
                                                         : GripperEnable::kDisableClearError},
                codec_));
  }
  // An e-stop someone else triggered (pendant, another program) is resumed here; robotd's own
  // e-stop is resumed by robotd's reset.
  if (arm_estop && !estop_) send(encode(MotionControl{.emergency_stop = EmergencyStop::kResume}, codec_));
  streamer_.reset();

  // Wait for status frames sent after the clear.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(params_.reply_timeout_ms);
  driver::FaultInfo fault;
  while (std::chrono::steady_clock::now() < deadline) {
    if (!abort_.sleep_for(10ms)) return driver::aborted_error("waiting for the arm to clear its errors");
    drain_link_blocking_free(monotonic_now_ns());
    fault = arm_fault(arm_, estop_, params_.gripper);
    if (fault.code == 0) return {};
  }
  return make_error(ErrorCode::kRefused,
                    std::string("the arm still reports a fault after clearing its errors: ") + fault.text.data());
}

Result<void> PiperDriver::reset_zero(std::span<const int> joints) {
  if (params_.leader()) return make_error(ErrorCode::kRefused, std::string("reset_zero: ") + kLeaderIsReadOnly);
  abort_.clear();
  std::vector<int> targets(joints.begin(), joints.end());
  if (targets.empty()) targets = {0, 1, 2, 3, 4, 5};
  for (const int joint : targets) {
    if (joint < 0 || joint >= kArmJoints) {
      return make_error(ErrorCode::kInvalidArgument, "reset_zero: joint index " + std::to_string(joint) +
                                                         " is not an arm joint (0-5); the gripper is zeroed with "
                                                         "the gripper op {\"set_zero\": true}");
    }
  }
  // The loop is paused: the acknowledges are read here, not by read().
  const std::lock_guard lock(ops_mutex_);
  for (const int joint : targets) {
    auto acked = set_and_await_ack(
        encode(JointConfig{.joint = static_cast<std::uint8_t>(joint + 1), .set_zero = true}, codec_), 0x75,
        /*maintenance=*/true);
    if (!acked) return abort_.verdict(acked.error(), "reset_zero");
    if (!acked.value().zero_set) {
      return make_error(ErrorCode::kRefused, "joint " + std::to_string(joint + 1) +
                                                 ": the arm did not confirm the new zero (0x476 byte 1 = 0)");
    }
  }
  return {};
}

// --- RT path ------------------------------------------------------------------------------------

driver::IoResult PiperDriver::link_lost(driver::FaultInfo& fault, const char* why) noexcept {
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

driver::IoResult PiperDriver::read(driver::Feedback& out, driver::FaultInfo& fault) noexcept {
  if (!connected_.load(std::memory_order_acquire)) {
    fault = not_connected_fault_;
    return driver::IoResult::kDisconnected;
  }
  if (link_lost_.load(std::memory_order_relaxed)) return link_lost(fault, "");
  const std::int64_t now_ns = monotonic_now_ns();
  bool joints_complete = false;
  const std::uint64_t leader_sets_before = arm_.master_joint_sets;
  CanMessage message;
  for (int i = 0; i < kMaxFramesPerRead; ++i) {
    const transport::CanIo result = transport_->receive(message);
    if (result == transport::CanIo::kNone) break;
    if (result == transport::CanIo::kClosed) return link_lost(fault, "CAN link closed");
    if (result == transport::CanIo::kBusError) {
      std::array<char, 120> words{};
      transport::describe_bus_error(message, words);
      std::array<char, 144> text{};  // fits FaultInfo::text
      std::snprintf(text.data(), text.size(), "CAN bus error on %.40s: %.80s", link_name_.data(), words.data());
      fault.set(kBusErrorFault, text.data());
      publish_snapshot();
      return driver::IoResult::kFault;
    }
    ++rx_frames_;
    if (is_reply(message.id)) (void)replies_.push(message);
    const auto frame = decode(message, codec_);
    if (!frame) {
      ++arm_.unknown_frames;
      continue;
    }
    joints_complete = apply_frame(arm_, *frame, now_ns) || joints_complete;
  }
  update_rates(now_ns);
  const std::int64_t timeout_ns = static_cast<std::int64_t>(params_.feedback_timeout_ms) * 1'000'000;
  if (params_.leader()) {
    // The leader's joint commands are its only steady stream: they are its link.
    if (now_ns - arm_.last_master_joints_ns > timeout_ns) {
      std::array<char, 96> why{};
      std::snprintf(why.data(), why.size(), "no leader joint commands (0x155-0x157) for %lld ms",
                    static_cast<long long>((now_ns - arm_.last_master_joints_ns) / 1'000'000));
      return link_lost(fault, why.data());
    }
    joints_complete = arm_.master_joint_sets != leader_sets_before;
  } else if (now_ns - arm_.last_status_ns > timeout_ns || now_ns - arm_.last_joints_ns > timeout_ns) {
    std::array<char, 96> why{};
    std::snprintf(why.data(), why.size(), "no arm feedback (0x2A1 / 0x2A5-0x2A7) for %lld ms",
                  static_cast<long long>((now_ns - std::min(arm_.last_status_ns, arm_.last_joints_ns)) / 1'000'000));
    return link_lost(fault, why.data());
  }
  publish_snapshot();
  if (!joints_complete) return driver::IoResult::kNoNewData;
  fill_feedback(out, now_ns);
  return driver::IoResult::kOk;
}

void PiperDriver::fill_feedback(driver::Feedback& out, std::int64_t now_ns) noexcept {
  out.joint_count = params_.joint_count();
  const bool leader = params_.leader();
  std::array<double, kArmJoints> q{};
  for (std::size_t j = 0; j < kArmJoints; ++j) {
    const JointReport& joint = arm_.joints[j];
    // A leader sends its joints' positions only: no speed, no current.
    q[j] = leader ? arm_.master_joints_rad[j] : joint.position_rad;
    out.joints[j] = leader ? driver::JointFeedback{q[j], 0.0, 0.0}
                           : driver::JointFeedback{joint.position_rad, joint.speed_rad_s,
                                                   joint.current_a * params_.joints[j].effort_nm_per_a};
  }
  if (params_.gripper) {
    // The gripper reports no speed: differentiate its stroke between joint sets.
    const double stroke = leader ? arm_.master_gripper.stroke_m : arm_.gripper.stroke_m;
    const double dt = static_cast<double>(now_ns - gripper_last_ns_) * 1e-9;
    const double speed = gripper_last_ns_ > 0 && dt > 0 ? (stroke - gripper_last_m_) / dt : 0.0;
    gripper_last_m_ = stroke;
    gripper_last_ns_ = now_ns;
    out.joints[kArmJoints] = {stroke, speed, leader ? arm_.master_gripper.effort_nm : arm_.gripper.effort_nm};
  }
  out.has_end_pose = fk_enabled_.load(std::memory_order_relaxed);
  if (!out.has_end_pose) return;
  const CartesianPose pose = forward_kinematics(q, params_.dh);
  out.end_pose.position_m = {pose.x_m, pose.y_m, pose.z_m};
  out.end_pose.orientation_xyzw = quaternion_xyzw(pose);
}

driver::IoResult PiperDriver::write(const driver::CommandFrame& command, driver::FaultInfo& fault) noexcept {
  if (!connected_.load(std::memory_order_acquire)) {
    fault = not_connected_fault_;
    return driver::IoResult::kDisconnected;
  }
  if (params_.leader()) return driver::IoResult::kOk;  // robotd never commands a leader arm
  const std::int64_t now_ns = monotonic_now_ns();
  if (estop_ && !command.estop) {
    resume_deadline_ns_ = now_ns + static_cast<std::int64_t>(params_.reply_timeout_ms) * 1'000'000;
  }
  if (arm_.status.arm_status != 0x01) resume_deadline_ns_ = 0;  // resumed
  estop_ = command.estop;
  if (const DisableRequest* disable = disable_.take()) disable_.answer(decide_disable(command, disable->motor));
  const bool hold = hold_for_ops_.load(std::memory_order_acquire);
  streamer_.plan(command, arm_, hold, outgoing_);
  if (hold && streamer_.any_owned()) hold_for_ops_.store(false, std::memory_order_release);
  for (std::size_t i = 0; i < outgoing_.count; ++i) {
    const transport::CanIo result = send(outgoing_.frames[i]);
    if (result == transport::CanIo::kClosed) return link_lost(fault, "CAN link closed");
  }
  const driver::FaultInfo reported = arm_fault(arm_, estop_ || now_ns < resume_deadline_ns_, params_.gripper);
  if (reported.code != 0) {
    fault = reported;
    return driver::IoResult::kFault;
  }
  return driver::IoResult::kOk;
}

DisableOutcome PiperDriver::decide_disable(const driver::CommandFrame& command, std::uint8_t motor) noexcept {
  using Verdict = DisableOutcome::Verdict;
  if (command.estop) return {.verdict = Verdict::kEstop};
  // The joint stream holds every arm joint once it runs, so any joint robotd drives blocks a
  // disable of any of them.
  const bool streaming = !hold_for_ops_.load(std::memory_order_acquire);
  for (std::size_t j = 0; j < std::min<std::size_t>(command.joint_count, kArmJoints); ++j) {
    const driver::JointCommand& joint = command.joints[j];
    if (joint.owned) return {.verdict = Verdict::kOwned, .joint = j};
    if (streaming && joint.holds()) return {.verdict = Verdict::kHeld, .joint = j};
  }
  if (send(encode(MotorEnable{.motor = motor, .enable = false}, codec_)) != transport::CanIo::kDone) {
    return {.verdict = Verdict::kNotSent};
  }
  hold_for_ops_.store(true, std::memory_order_release);  // robotd does not hold a disabled arm
  return {.verdict = Verdict::kSent};
}

transport::CanIo PiperDriver::send(const CanMessage& message) noexcept {
  const transport::CanIo result = transport_->send(to_wire(message, codec_));
  if (result == transport::CanIo::kDone) {
    tx_frames_.fetch_add(1, std::memory_order_relaxed);
  } else if (result == transport::CanIo::kNone) {
    tx_dropped_.fetch_add(1, std::memory_order_relaxed);
  }
  return result;
}

void PiperDriver::update_rates(std::int64_t now_ns) noexcept {
  const std::uint64_t tx = tx_frames_.load(std::memory_order_relaxed);
  if (rate_window_start_ns_ == 0) {
    rate_window_start_ns_ = now_ns;
    rate_window_rx_ = rx_frames_;
    rate_window_tx_ = tx;
    return;
  }
  const std::int64_t elapsed_ns = now_ns - rate_window_start_ns_;
  if (elapsed_ns < kNsPerSecond) return;
  const double seconds = static_cast<double>(elapsed_ns) * 1e-9;
  rx_fps_ = static_cast<double>(rx_frames_ - rate_window_rx_) / seconds;
  tx_fps_ = static_cast<double>(tx - rate_window_tx_) / seconds;
  rate_window_start_ns_ = now_ns;
  rate_window_rx_ = rx_frames_;
  rate_window_tx_ = tx;
}

void PiperDriver::publish_snapshot() noexcept {
  ArmSnapshot snapshot;
  snapshot.arm = arm_;
  snapshot.link_up = connected_.load(std::memory_order_relaxed) && !link_lost_.load(std::memory_order_relaxed);
  snapshot.any_owned = streamer_.any_owned();
  snapshot.estop = estop_;
  snapshot.rx_frames = rx_frames_;
  snapshot.tx_frames = tx_frames_.load(std::memory_order_relaxed);
  snapshot.tx_dropped = tx_dropped_.load(std::memory_order_relaxed);
  snapshot.rx_fps = rx_fps_;
  snapshot.tx_fps = tx_fps_;
  snapshot_.store(snapshot);
}

ArmSnapshot PiperDriver::snapshot() const { return snapshot_.load_non_rt(); }

}  // namespace robotd::piper
