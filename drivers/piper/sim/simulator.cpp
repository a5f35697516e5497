#include "simulator.hpp"

#include <utility>

#include <spdlog/spdlog.h>

#include "feedback.hpp"
#include "garbage_frames.hpp"
#include "robotd/transport/can_bus.hpp"
#include "robotd/transport/unix_socket.hpp"

namespace robotd::piper::sim {
namespace {

constexpr std::int64_t kLoopPeriodNs = 1'000'000;
constexpr std::int64_t kStepNs = 1'000'000;  // kStepS
constexpr int kMaxStepsPerLoop = 50;         // behind by more: the arm's clock slips instead
constexpr int kMaxLateFeedbackPeriods = 4;   // behind by more: skip, do not burst
constexpr int kLowRateDivider = 5;           // 0x261–0x266 at a fifth of the 0x2Ax rate (40 of 200 Hz)
constexpr int kMaxFramesPerPoll = 1000;
constexpr int kGarbagePerLoop = 10;  // spread out, so feedback keeps flowing between them
constexpr std::int64_t kReopenRetryNs = 100'000'000;
constexpr std::uint8_t kLinkageLeader = 0xFA;  // 0x470 byte 0
constexpr std::uint8_t kLinkageFollower = 0xFC;

}  // namespace

Simulator::Simulator(SimOptions options)
    : options_(std::move(options)),
      codec_{.mit_layout = mit_layout_for(options_.firmware),
             .feedback_id_offset = options_.feedback_id_offset,
             .control_id_offset = options_.control_id_offset},
      leader_(options_.leader),
      arm_(options_.initial_rad, options_.dh, codec_.mit_layout),
      controller_(arm_, codec_, options_.firmware),
      bus_(transport::make_can_bus(options_.bus)) {
  high_rate_period_ns_ = static_cast<std::int64_t>(1e9 / options_.feedback_rate_hz);
  low_rate_period_ns_ = high_rate_period_ns_ * kLowRateDivider;
  outgoing_.reserve(64);
  logged_ = summary();
}

Result<void> Simulator::open() {
  if (options_.bus.kind == transport::CanLinkConfig::Kind::kStandIn &&
      transport::unix_socket_in_use(options_.bus.path)) {
    return make_error(ErrorCode::kNotAvailable,
                      "the stand-in bus " + options_.bus.path + " is in use: another simulator listens there");
  }
  if (auto opened = bus_->open(); !opened) return opened;
  bus_open_ = true;
  if (!options_.control_path.empty()) {
    control_server_.emplace(options_.control_path);
    if (auto opened = control_server_->open(); !opened) {
      bus_->close();
      bus_open_ = false;
      return opened;
    }
  }
  return {};
}

void Simulator::run(const volatile std::sig_atomic_t& stop) {
  const std::int64_t start = monotonic_ns();
  physics_ns_ = start;
  next_high_rate_ns_ = start;
  next_low_rate_ns_ = start;
  std::int64_t wake_ns = start;
  const sim_control::ControlServer::Handler handler = [this](const nlohmann::json& request) {
    return control(request);
  };
  while (stop == 0) {
    const std::int64_t now = monotonic_ns();
    if (control_server_) control_server_->poll(handler);
    reopen_bus_if_due(now);
    poll_bus();
    step_physics(now);
    send_feedback(now);
    send_garbage();
    if (!options_.quiet) log_changes();

    wake_ns = sim_control::sleep_until_next_pass(wake_ns, now, kLoopPeriodNs, stop);
  }
  if (control_server_) control_server_->close();
  bus_->close();
  bus_open_ = false;
}

void Simulator::poll_bus() {
  if (!bus_open_) return;
  CanMessage message;
  std::vector<CanMessage>& replies = outgoing_;
  for (int i = 0; i < kMaxFramesPerPoll; ++i) {
    const transport::CanIo result = bus_->receive(message);
    if (result == transport::CanIo::kNone) return;
    if (result == transport::CanIo::kClosed) {
      spdlog::warn("{} closed; reopening", bus_->describe());
      bus_->close();
      bus_open_ = false;
      reopen_bus_at_ns_ = monotonic_ns() + kReopenRetryNs;
      return;
    }
    if (result == transport::CanIo::kBusError) continue;
    ++frames_received_[message.extended ? message.id | 0x80000000U : message.id];
    replies.clear();
    // A leader is moved by hand and drives its follower: of the host's frames it takes only
    // 0x470 (its role for the next start), which has no reply.
    if (leader_ && (message.extended || message.id != can_id::kMasterSlaveConfig)) continue;
    const bool was_estopped = arm_.estop();
    controller_.handle(message, replies);
    if (arm_.estop() && !was_estopped) estop_since_ns_ = monotonic_ns();
    if (!drop_replies_) {
      for (const CanMessage& reply : replies) send(reply);
    }
  }
}

void Simulator::step_physics(std::int64_t now_ns) {
  int steps = 0;
  while (physics_ns_ + kStepNs <= now_ns) {
    if (++steps > kMaxStepsPerLoop) {
      physics_ns_ = now_ns;  // descheduled for long: the simulated arm loses that time
      break;
    }
    arm_.step(kStepS);
    physics_ns_ += kStepNs;
  }
}

void Simulator::send_feedback(std::int64_t now_ns) {
  const bool silent = now_ns < silent_until_ns_;
  if (now_ns >= next_high_rate_ns_) {
    if (!silent) {
      outgoing_.clear();
      if (leader_) {
        append_leader_commands(arm_, codec_, outgoing_);
      } else {
        append_high_rate_feedback(arm_, codec_, outgoing_);
      }
      for (const CanMessage& frame : outgoing_) send(frame);
    }
    next_high_rate_ns_ += high_rate_period_ns_;
    if (now_ns - next_high_rate_ns_ > kMaxLateFeedbackPeriods * high_rate_period_ns_) {
      next_high_rate_ns_ = now_ns + high_rate_period_ns_;
    }
  }
  if (now_ns >= next_low_rate_ns_) {
    if (!silent && !leader_) {
      outgoing_.clear();
      append_low_rate_feedback(arm_, codec_, outgoing_);
      for (const CanMessage& frame : outgoing_) send(frame);
    }
    next_low_rate_ns_ += low_rate_period_ns_;
    if (now_ns - next_low_rate_ns_ > kMaxLateFeedbackPeriods * low_rate_period_ns_) {
      next_low_rate_ns_ = now_ns + low_rate_period_ns_;
    }
  }
}

void Simulator::send_garbage() {
  for (int i = 0; i < kGarbagePerLoop && garbage_pending_ > 0; ++i, --garbage_pending_) send(garbage_frame(random_));
}

void Simulator::reopen_bus_if_due(std::int64_t now_ns) {
  if (!reopen_bus_at_ns_ || now_ns < *reopen_bus_at_ns_) return;
  if (auto opened = bus_->open(); !opened) {
    spdlog::warn("cannot reopen {}: {}; retrying", bus_->describe(), opened.error().message);
    reopen_bus_at_ns_ = now_ns + kReopenRetryNs;
    return;
  }
  reopen_bus_at_ns_.reset();
  bus_open_ = true;
  if (!options_.quiet) spdlog::info("{} open again", bus_->describe());
}

void Simulator::send(const CanMessage& message) {
  if (bus_open_ && bus_->send(to_wire(message, codec_)) == transport::CanIo::kDone) ++frames_sent_;
}

void Simulator::restart() {
  const ArmSettings kept = arm_.settings();
  arm_ = ArmModel(arm_.positions(), options_.dh, codec_.mit_layout);
  arm_.settings() = kept;
  const MasterSlaveConfig& config = kept.master_slave;
  if (config.linkage == kLinkageLeader || config.linkage == kLinkageFollower) {
    leader_ = config.linkage == kLinkageLeader;
    codec_.feedback_id_offset = config.feedback_offset;
    // A leader sends its commands at the linkage offset; a follower takes them at its control offset.
    codec_.control_id_offset = leader_ ? config.linkage_offset : config.control_offset;
  }
  if (!options_.quiet) {
    spdlog::info("restarted as {}, id offsets feedback 0x{:02X} control 0x{:02X}", leader_ ? "leader" : "follower",
                 codec_.feedback_id_offset, codec_.control_id_offset);
  }
}

Simulator::Summary Simulator::summary() const {
  unsigned enabled = 0;
  for (std::size_t i = 0; i < arm_.joints().size(); ++i) {
    if (arm_.joints()[i].enabled) enabled |= 1U << i;
  }
  return Summary{.ctrl_mode = arm_.ctrl_mode(),
                 .move_mode = arm_.move_mode(),
                 .mit = arm_.mit(),
                 .estop = arm_.estop(),
                 .enabled_bits = static_cast<std::uint8_t>(enabled),
                 .arm_status = arm_.arm_status()};
}

void Simulator::log_changes() {
  const Summary now = summary();
  if (now == logged_) return;
  spdlog::info("arm: ctrl_mode {} ({}), move_mode {} ({}){}, enabled joints 0x{:02X}, status {} ({}){}",
               static_cast<int>(now.ctrl_mode), control_mode_text(now.ctrl_mode), static_cast<int>(now.move_mode),
               move_mode_text(now.move_mode), now.mit ? " 0xAD" : "", now.enabled_bits, now.arm_status,
               arm_status_text(now.arm_status), now.estop ? ", EMERGENCY STOP" : "");
  logged_ = now;
}

}  // namespace robotd::piper::sim
