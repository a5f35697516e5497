#include "robotd/client/session.hpp"

#include <cerrno>
#include <ctime>
#include <sys/prctl.h>

#include "client_core.hpp"
#include "tick_link.hpp"

namespace robotd {
namespace {

std::int64_t clock_ns(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

}  // namespace

Session::Session(std::shared_ptr<detail::ClientCore> core, RequestControlResponse granted,
                 const SessionRequest& request)
    : core_(std::move(core)),
      uuid_(std::move(granted.uuid)),
      session_id_(std::move(granted.session_id)),
      device_(std::move(granted.device)),
      motor_ids_(std::move(granted.motor_ids)),
      mode_(request.mode),
      applied_behavior_(granted.applied_behavior),
      release_behavior_(request.on_release),
      timeout_(request.timeout),
      last_sent_(std::chrono::steady_clock::now()) {}

Session::Session(Session&& other) noexcept = default;

Session& Session::operator=(Session&& other) noexcept {
  if (this != &other) {
    if (active()) (void)release(release_behavior_);
    ticks_ = std::move(other.ticks_);
    core_ = std::move(other.core_);
    uuid_ = std::move(other.uuid_);
    session_id_ = std::move(other.session_id_);
    device_ = std::move(other.device_);
    motor_ids_ = std::move(other.motor_ids_);
    mode_ = other.mode_;
    applied_behavior_ = other.applied_behavior_;
    release_behavior_ = other.release_behavior_;
    timeout_ = other.timeout_;
    last_sent_ = other.last_sent_;
  }
  return *this;
}

Session::~Session() {
  if (active()) (void)release(release_behavior_);
}

Result<void> Session::command(const Command& command) { return publish(command, 0); }

Result<void> Session::publish(const Command& command, std::uint64_t answers_tick) {
  if (!active()) return make_error(ErrorCode::kInvalidArgument, "this session has been released");
  ControlCommand message;
  message.header.stamp = Time::from_ns(clock_ns(CLOCK_REALTIME));
  message.uuid = uuid_;
  message.device = device_;
  // Values without motor ids address the session's motors in order; no values at all is a keepalive.
  const bool has_values = !command.positions.empty() || !command.velocities.empty() || !command.kp.empty() ||
                          !command.kd.empty() || !command.torques.empty();
  message.motor_ids = command.motor_ids.empty() && has_values ? motor_ids_ : command.motor_ids;
  message.positions = command.positions;
  message.velocities = command.velocities;
  message.kp = command.kp;
  message.kd = command.kd;
  message.torques = command.torques;
  message.answers_tick = answers_tick;
  message.sent_steady_ns = clock_ns(CLOCK_MONOTONIC);
  auto written = core_->commands.write(message);
  if (written) last_sent_ = std::chrono::steady_clock::now();
  return written;
}

Result<detail::TickLink*> Session::tick_link() {
  if (!active()) return make_error(ErrorCode::kInvalidArgument, "this session has been released");
  if (ticks_ == nullptr) {
    auto link = detail::TickLink::create(core_, device_, session_id_);
    if (!link) return link.error();
    ticks_ = std::move(link.value());
  }
  return ticks_.get();
}

Result<TickState> Session::next_tick(std::chrono::milliseconds timeout) {
  auto link = tick_link();
  if (!link) return link.error();
  return link.value()->next_tick(timeout);
}

Result<void> Session::answer(const TickState& state, const Command& command) {
  if (state.header.frame_id != device_) {
    return make_error(ErrorCode::kInvalidArgument, "the TickState is of device '" + state.header.frame_id +
                                                       "': expected one of '" + device_ +
                                                       "', the device this session commands");
  }
  if (state.tick == 0) {
    return make_error(ErrorCode::kInvalidArgument,
                      "the TickState has tick 0: expected one from next_tick (ticks count from 1)");
  }
  return publish(command, state.tick);
}

Result<void> Session::send_aligned(const Command& command, std::chrono::microseconds lead) {
  if (lead.count() < 0) {
    return make_error(ErrorCode::kInvalidArgument,
                      "lead is " + std::to_string(lead.count()) + " µs: expected >= 0, how long before a tick to send");
  }
  auto link = tick_link();
  if (!link) return link.error();
  auto phase = link.value()->phase(core_->options.service_timeout);
  if (!phase) return phase.error();
  const std::int64_t send_at = detail::aligned_send_time_ns(
      phase.value(), clock_ns(CLOCK_MONOTONIC), std::chrono::duration_cast<std::chrono::nanoseconds>(lead).count());
  // The kernel wakes a normal thread up to its timer slack (50 µs by default) late, which would
  // eat most of the lead: this thread asks for 1 µs once.
  thread_local const bool precise_timers = prctl(PR_SET_TIMERSLACK, 1000UL, 0UL, 0UL, 0UL) == 0;
  (void)precise_timers;
  const timespec wake{.tv_sec = send_at / 1'000'000'000, .tv_nsec = send_at % 1'000'000'000};
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &wake, nullptr) == EINTR) {
  }
  return publish(command, 0);
}

Result<SessionInfo> Session::info(std::chrono::milliseconds timeout) {
  auto link = tick_link();
  if (!link) return link.error();
  return link.value()->info(timeout);
}

Result<void> Session::send_positions(const std::vector<float>& positions_rad) {
  return command(Command{motor_ids_, positions_rad, {}, {}, {}, {}});
}

Result<void> Session::keepalive() { return command(Command{}); }

std::chrono::milliseconds Session::time_left() const {
  const auto elapsed =
      std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - last_sent_);
  return elapsed >= timeout_ ? std::chrono::milliseconds(0) : timeout_ - elapsed;
}

Result<ReleaseControlResponse> Session::release(Behavior release_mode) {
  if (!active()) return make_error(ErrorCode::kInvalidArgument, "this session has already been released");
  ticks_.reset();
  auto core = std::move(core_);
  auto response = core->release_control.call(ReleaseControlRequest{core->options.node_name, uuid_, release_mode},
                                             core->options.service_timeout);
  if (!response) return response.error();
  if (!response.value().success) {
    return make_error(ErrorCode::kRefused, "robotd refused /release_control: " + response.value().message);
  }
  return response;
}

}  // namespace robotd
