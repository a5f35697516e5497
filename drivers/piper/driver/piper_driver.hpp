// The AgileX PiPER arm behind a CAN link (docs/drivers/piper.md).
//
// RT thread: read() drains the link (non-blocking), decodes every frame into ArmState, hands
// replies to queries over to the ops through a lock-free ring, and reports a lost link (link
// closed, CAN bus error, no arm feedback for feedback_timeout_ms). write() streams commands
// (command_streamer.hpp) and reports the faults the arm itself reports (arm_state.hpp), so
// joint states keep flowing while robotd holds the device in FAULT.
// A leader arm ("role": "leader") sends only its control frames: read() reports its commanded
// joints (0x155–0x157) and gripper (0x159) and supervises the link on them; robotd sends it
// nothing (write() is empty, describe() marks the device read-only, the ops that would move or
// configure it refuse).
// Other threads: connect()/recover() own the link while the loop is paused; call() ops send
// frames on the same link (one send is one system call, safe next to the RT thread's) and read
// the RT thread's published ArmSnapshot.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "codec/piper_frames.hpp"
#include "driver/arm_state.hpp"
#include "driver/command_streamer.hpp"
#include "driver/piper_params.hpp"
#include "robotd/driver/abort_flag.hpp"
#include "robotd/driver/driver.hpp"
#include "robotd/driver/rt_handoff.hpp"
#include "robotd/driver/seqlock.hpp"
#include "robotd/driver/spsc_ring.hpp"
#include "robotd/transport/can_transport.hpp"

namespace robotd::piper {

inline constexpr std::int32_t kNotConnectedFault = -1;
inline constexpr std::int32_t kLinkLostFault = -2;
inline constexpr std::int32_t kBusErrorFault = -3;

/// Why robotd commands nothing on a leader device: the refusal of control requests and ops.
inline constexpr const char* kLeaderIsReadOnly =
    "this PiPER is a leader arm (params.role \"leader\"): a person moves it by hand and it commands its follower; "
    "robotd only reads the joint and gripper commands it sends and sends it nothing";

/// What the RT thread publishes after every read() for diagnostics() and the ops.
struct ArmSnapshot {
  ArmState arm;
  bool link_up = false;
  bool any_owned = false;
  bool estop = false;
  std::uint64_t rx_frames = 0;
  std::uint64_t tx_frames = 0;
  std::uint64_t tx_dropped = 0;  // the transmit queue was full
  double rx_fps = 0;             // over the last full second
  double tx_fps = 0;
};

/// The disable op's request to write(), and write()'s decision, made from that tick's commands.
struct DisableRequest {
  std::uint8_t motor = kAllJoints;  // 1 … 6, kAllJoints
};
struct DisableOutcome {
  enum class Verdict : std::uint8_t { kSent, kEstop, kOwned, kHeld, kNotSent };
  Verdict verdict = Verdict::kSent;
  std::size_t joint = 0;  // kOwned, kHeld: the first arm joint in the way (0-based)
};

class PiperDriver final : public driver::Driver {
 public:
  Result<void> configure(const nlohmann::json& params) override;
  driver::DeviceDescription describe() const override;

  Result<void> connect() override;
  void disconnect() noexcept override;
  Result<void> recover() override;
  Result<void> reset_zero(std::span<const int> joints) override;
  void abort_maintenance() noexcept override { abort_.request(); }

  driver::IoResult read(driver::Feedback& out, driver::FaultInfo& fault) noexcept override;
  driver::IoResult write(const driver::CommandFrame& command, driver::FaultInfo& fault) noexcept override;

  Result<nlohmann::json> call(const std::string& op, const nlohmann::json& args) override;
  driver::Diagnostics diagnostics() const override;

 private:
  friend class PiperOps;

  // Link (non-RT, link_mutex_ held).
  Result<void> connect_locked();
  Result<void> open_and_check_link();
  /// Waits for the arm's own frames (link_check.cpp): a follower's feedback, a leader's joint
  /// commands; the error says what arrived instead.
  Result<void> await_arm_frames(std::chrono::milliseconds timeout);
  bool arm_frames_complete() const;
  std::string missing_frames_text(const std::string& waited, bool frames_arrived) const;
  /// Notes a frame of the arm's kind at ids moved by another offset than configured.
  void note_moved_ids(std::uint32_t wire_id);
  void detect_firmware();
  /// 0x472 → 0x473 for J1–J6 (the SDK's PiperInit): params_ limits = configured ∩ the arm's.
  void read_arm_limits();
  Result<void> clear_arm_errors();
  /// Receives what is waiting, applies it to arm_ and hands replies to the reply ring, as read()
  /// does (only while the RT loop does not run).
  void drain_link_blocking_free(std::int64_t now_ns);

  // RT helpers.
  driver::IoResult link_lost(driver::FaultInfo& fault, const char* why) noexcept;
  void fill_feedback(driver::Feedback& out, std::int64_t now_ns) noexcept;
  void update_rates(std::int64_t now_ns) noexcept;
  void publish_snapshot() noexcept;
  /// Sends the disable unless the e-stop is on or robotd drives an arm joint: a session, or the
  /// KEEP or DAMPING one left, while that stream reaches the arm (no op holds it off).
  DisableOutcome decide_disable(const driver::CommandFrame& command, std::uint8_t motor) noexcept;

  // Ops side (piper_ops*.cpp) shares these; exchanges run with ops_mutex_ held.
  transport::CanIo send(const CanMessage& message) noexcept;
  ArmSnapshot snapshot() const;
  /// Sends `requests` and returns the first `count` replies with id `reply_id` that arrive
  /// within reply_timeout_ms (replies left over from an earlier exchange are discarded first).
  Result<std::vector<CanMessage>> exchange(std::span<const CanMessage> requests, std::uint32_t reply_id,
                                           std::size_t count);
  /// Sends a setting and waits for its 0x476 acknowledge (`command`: the ack's byte 0). For
  /// `maintenance` (the loop paused) the wait reads the link itself and abort_ ends it.
  Result<SetAck> set_and_await_ack(const CanMessage& request, std::uint8_t command, bool maintenance = false);

  PiperParams params_;
  bool configured_ = false;
  CodecOptions codec_;  // params_.codec with the MIT layout detected at connect
  std::string firmware_text_;
  std::string firmware_note_;
  // params_ joint and gripper limits and configured_limits_: connect/recover (the arm's limits)
  // and the sdk_* ops write them, describe() and the gripper op read them. Never the RT thread.
  mutable std::mutex limits_mutex_;
  // The config's, narrowed by the sdk_joint_limit op: what the arm's limits narrow at a connect.
  std::array<driver::JointLimits, kArmJoints> configured_limits_{};
  std::string arm_limits_note_;       // what the arm's own limits narrowed at the last connect
  std::array<char, 96> link_name_{};  // "stand-in /tmp/piper.sock", for RT messages
  // Offsets of feedback / control frames seen at connect at ids moved otherwise than configured.
  std::optional<std::uint8_t> seen_feedback_offset_;
  std::optional<std::uint8_t> seen_control_offset_;

  std::unique_ptr<transport::CanTransport> transport_;
  std::mutex link_mutex_;    // connect / recover / disconnect; never taken by the RT thread
  std::mutex ops_mutex_;     // one op at a time (the reply ring has one consumer)
  driver::AbortFlag abort_;  // abort_maintenance(): connect, recover and reset_zero stop waiting

  std::atomic<bool> connected_{false};
  std::atomic<bool> link_lost_{false};
  std::atomic<bool> fk_enabled_{true};     // the fk_calculation op: rt/end_pose from the joints, or none
  std::atomic<bool> hold_for_ops_{false};  // a motion op drives the arm (see CommandStreamer::plan)
  driver::RtHandoff<DisableRequest, DisableOutcome> disable_;  // the disable op, decided by write()
  std::atomic<std::uint64_t> tx_frames_{0};
  std::atomic<std::uint64_t> tx_dropped_{0};
  // Frames the arm sends in answer to a query or setting, from the RT thread to the op waiting
  // for them; when full the newest are dropped and the op times out and says so.
  driver::SpscRing<transport::CanMessage, 256> replies_;
  driver::SeqLock<ArmSnapshot> snapshot_;

  // RT thread (and connect/recover while the loop is paused).
  ArmState arm_;
  CommandStreamer streamer_;
  OutgoingFrames outgoing_;
  bool estop_ = false;
  // After robotd's e-stop reset the arm reports its e-stop until it has taken the resume: until
  // then (at most reply_timeout_ms) that is still robotd's own e-stop, not a fault.
  std::int64_t resume_deadline_ns_ = 0;
  driver::FaultInfo lost_fault_;  // why the link was lost
  // Why the last connect failed (set while the loop is paused or not yet running).
  driver::FaultInfo not_connected_fault_ = [] {
    driver::FaultInfo fault;
    fault.set(kNotConnectedFault, "not connected (connect() or recover() first)");
    return fault;
  }();
  std::uint64_t rx_frames_ = 0;
  std::int64_t rate_window_start_ns_ = 0;
  std::uint64_t rate_window_rx_ = 0;
  std::uint64_t rate_window_tx_ = 0;
  double rx_fps_ = 0;
  double tx_fps_ = 0;
  double gripper_last_m_ = 0;
  std::int64_t gripper_last_ns_ = 0;
};

}  // namespace robotd::piper
