#include "driver/controller_link.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <ctime>
#include <future>
#include <memory>
#include <poll.h>
#include <span>
#include <sys/socket.h>
#include <system_error>
#include <unistd.h>

#include "driver/arm_fault.hpp"
#include "robotd/kinematics/rotation.hpp"

namespace robotd::realman {
namespace {

constexpr auto kIdleWake = std::chrono::milliseconds(50);
constexpr auto kPushCycleUnit = std::chrono::milliseconds(5);
/// Slack beyond the link thread's own deadlines before a waiting caller gives up by itself.
constexpr auto kCallerSlack = std::chrono::seconds(1);
/// Pass-through frames stay this far inside the controller's per-frame limits (§3.3).
constexpr double kStepMargin = 0.9;

std::string errno_text(int error) { return std::generic_category().message(error); }

driver::FaultInfo fault_of(std::int32_t code, const std::string& text) {
  driver::FaultInfo fault;
  fault.set(code, text.c_str());
  return fault;
}

}  // namespace

Result<void> ControllerLink::open(const LinkSettings& settings, const driver::AbortFlag* abort) {
  close();
  settings_ = settings;
  auto tcp = transport::connect_tcp(settings.controller, settings.connect_timeout, abort);
  if (!tcp) return tcp.error();
  tcp_ = std::move(tcp).value();
  if (settings.push) {
    transport::Endpoint local = settings.push_local;
    if (local.host.empty()) {
      auto own = transport::local_endpoint(tcp_.fd());
      if (!own) return own.error();
      local.host = own.value().host;
    }
    auto udp = transport::bind_udp(local);
    if (!udp) return udp.error();
    udp_ = std::move(udp).value();
    auto bound = transport::local_endpoint(udp_.fd());
    if (!bound) return bound.error();
    push_endpoint_ = bound.value();
  }

  tracker_ = RequestTracker{};
  splitter_.clear();
  tcp_out_.clear();
  link_counters_ = LinkCounters{};
  counters_.store(link_counters_);
  latest_ = ArmFeedback{};
  feedback_.store(latest_);
  health_.store(LinkHealth{});
  target_.store(StreamTarget{});
  target_read_ = StreamTarget{};
  restart_stream_.store(true);
  stopping_.store(false);
  feedback_sequence_ = 0;
  last_feedback_at_ = {};
  poll_in_flight_ = false;
  streaming_ = false;
  estop_sent_ = false;
  lost_ = false;
  const Clock::time_point now = Clock::now();
  next_stream_at_ = now;
  next_poll_at_ = now;
  last_stream_at_ = {};
  return io_.start("realman-link", settings.io_priority, [this] { run(); });
}

void ControllerLink::close() noexcept {
  io_.stop();
  std::vector<Outgoing> abandoned;
  {
    const std::lock_guard lock(queue_mutex_);
    abandoned.swap(queue_);
  }
  for (Outgoing& outgoing : abandoned) {
    outgoing.request.on_reply(make_error(ErrorCode::kNotAvailable, "the link to the controller was closed"));
  }
  tcp_.reset();
  udp_.reset();
}

Result<ControllerLink::Reply> ControllerLink::request(const nlohmann::json& message, const RequestOptions& options) {
  const std::string command = message.value("command", "");
  const auto shape = reply_shape(command);
  if (!shape) return make_error(ErrorCode::kInvalidArgument, "no reply shape known for command '" + command + "'");
  if (!is_open() || health().lost) {
    return make_error(ErrorCode::kNotAvailable, "not connected to the controller");
  }
  auto replied = std::make_shared<std::promise<Result<nlohmann::json>>>();
  auto completed = std::make_shared<std::promise<Result<TrajectoryEvent>>>();
  auto reply_future = replied->get_future();
  auto completion_future = completed->get_future();
  Request request{
      .command = command,
      .shape = *shape,
      .reply_timeout = options.reply_timeout,
      .completion = options.completion,
      .completion_timeout = options.completion_timeout,
      .deadline = {},
      .on_reply = [replied](Result<nlohmann::json> result) { replied->set_value(std::move(result)); },
      .on_completion = [completed](Result<TrajectoryEvent> result) { completed->set_value(std::move(result)); },
  };
  {
    const std::lock_guard lock(queue_mutex_);
    queue_.push_back(Outgoing{frame(message), std::move(request)});
  }
  wake();
  const auto aborted = [&] { return options.abort != nullptr && options.abort->requested(); };
  if (!driver::wait_ready(reply_future, options.reply_timeout + kCallerSlack, options.abort)) {
    if (aborted()) return driver::aborted_error("waiting for the reply to " + command);
    return make_error(ErrorCode::kTimeout, "no reply to " + command + " from the controller");
  }
  Result<nlohmann::json> body = reply_future.get();
  if (!body) return body.error();
  Reply reply{std::move(body).value(), std::nullopt};
  if (!options.completion) return reply;
  if (!driver::wait_ready(completion_future, options.completion_timeout + kCallerSlack, options.abort)) {
    if (aborted()) return driver::aborted_error("waiting for " + command + " to complete");
    return make_error(ErrorCode::kTimeout, command + " did not complete");
  }
  Result<TrajectoryEvent> event = completion_future.get();
  if (!event) return event.error();
  reply.completion = event.value();
  return reply;
}

void ControllerLink::send_unawaited(const nlohmann::json& message) {
  const std::string command = message.value("command", "");
  const auto shape = reply_shape(command);
  if (!shape) return;
  Request request{.command = command,
                  .shape = *shape,
                  .reply_timeout = std::chrono::milliseconds(1000),
                  .completion = std::nullopt,
                  .completion_timeout = {},
                  .deadline = {},
                  .on_reply = [](const Result<nlohmann::json>&) {},
                  .on_completion = [](const Result<TrajectoryEvent>&) {}};
  {
    const std::lock_guard lock(queue_mutex_);
    queue_.push_back(Outgoing{frame(message), std::move(request)});
  }
  wake();
}

std::string ControllerLink::last_arm_status() const {
  const std::lock_guard lock(status_mutex_);
  return arm_status_;
}

void ControllerLink::run() noexcept {
  try {
    while (!io_.stopping() && !lost_) {
      const Clock::time_point now = Clock::now();
      serve(now);
      if (!lost_) wait_for_io(Clock::now());
    }
    tracker_.fail_all(lost_ ? "the link to the controller was lost" : "the link to the controller was closed");
  } catch (const std::exception& error) {
    lose_link(std::string("link thread failed: ") + error.what());
    tracker_.fail_all("the link to the controller failed");
  }
}

void ControllerLink::serve(Clock::time_point now) {
  io_.drain();
  take_requests(now);
  read_tcp(now);
  if (udp_.is_open()) read_push();
  if (lost_) return;
  if (!settings_.push && now >= next_poll_at_) poll_state(now);
  follow_estop();
  if (now >= next_stream_at_) stream(now);
  tracker_.expire(now);
  if (last_feedback_at_ != Clock::time_point{} && now - last_feedback_at_ > settings_.feedback_timeout) {
    const auto silent_ms = std::chrono::duration_cast<std::chrono::milliseconds>(now - last_feedback_at_).count();
    lose_link(settings_.push
                  ? "no real-time push from the controller for " + std::to_string(silent_ms) + " ms (expected every " +
                        std::to_string(5 * settings_.push_cycle) + " ms on " + push_endpoint_.to_string() + ")"
                  : "no arm state from the controller for " + std::to_string(silent_ms) + " ms");
    return;
  }
  flush_tcp();
  counters_.store(link_counters_);
}

void ControllerLink::wait_for_io(Clock::time_point now) {
  Clock::time_point until = now + kIdleWake;
  until = std::min(until, next_stream_at_);
  if (!settings_.push) until = std::min(until, next_poll_at_);
  if (const auto deadline = tracker_.next_deadline()) until = std::min(until, *deadline);
  std::array<pollfd, 3> fds{{
      {.fd = io_.wake_fd(), .events = POLLIN, .revents = 0},
      {.fd = tcp_.fd(), .events = static_cast<short>(POLLIN | (tcp_out_.empty() ? 0 : POLLOUT)), .revents = 0},
      {.fd = udp_.fd(), .events = POLLIN, .revents = 0},  // fd −1 (no push) is ignored by ppoll
  }};
  const auto wait_ns =
      std::max<std::int64_t>(0, std::chrono::duration_cast<std::chrono::nanoseconds>(until - now).count());
  const timespec timeout{.tv_sec = wait_ns / 1'000'000'000, .tv_nsec = wait_ns % 1'000'000'000};
  ::ppoll(fds.data(), fds.size(), &timeout, nullptr);
}

void ControllerLink::take_requests(Clock::time_point now) {
  std::vector<Outgoing> taken;
  {
    const std::lock_guard lock(queue_mutex_);
    taken.swap(queue_);
  }
  for (Outgoing& outgoing : taken) {
    tcp_out_ += outgoing.bytes;
    ++link_counters_.requests;
    tracker_.sent(std::move(outgoing.request), now);
  }
}

void ControllerLink::read_tcp(Clock::time_point now) {
  std::array<char, 4096> buffer{};
  for (;;) {
    const ssize_t n = ::recv(tcp_.fd(), buffer.data(), buffer.size(), 0);
    if (n == 0) {
      lose_link("the controller closed the TCP connection (" + settings_.controller.to_string() + ")");
      return;
    }
    if (n < 0) {
      if (errno == EINTR) continue;
      if (errno == EAGAIN || errno == EWOULDBLOCK) break;
      // A controller that closes with robotd's frames still unread in its socket sends a reset.
      if (errno == ECONNRESET) {
        lose_link("the controller closed the TCP connection (" + settings_.controller.to_string() + ", reset)");
        return;
      }
      lose_link("TCP connection to " + settings_.controller.to_string() + " failed (" + errno_text(errno) + ")");
      return;
    }
    const std::uint64_t oversized_before = splitter_.oversized();
    splitter_.append(std::string_view(buffer.data(), static_cast<std::size_t>(n)));
    link_counters_.bad_lines += splitter_.oversized() - oversized_before;
    while (auto line = splitter_.next()) handle_line(*line, now);
  }
}

void ControllerLink::handle_line(const std::string& line, Clock::time_point now) {
  auto message = parse_message(line);
  if (!message) {
    ++link_counters_.bad_lines;
    return;
  }
  switch (message.value().kind) {
    case MessageKind::kReply:
      if (!tracker_.on_reply(message.value(), now)) ++link_counters_.unmatched;
      break;
    case MessageKind::kTrajectoryEvent: {
      const auto event = parse_trajectory_event(message.value());
      if (!event || !tracker_.on_event(event.value())) ++link_counters_.unmatched;
      break;
    }
    case MessageKind::kRealtimePush:
    case MessageKind::kOther:
      ++link_counters_.unmatched;
      break;
  }
}

void ControllerLink::read_push() {
  std::array<char, std::size_t{16} * 1024> datagram{};
  for (;;) {
    const ssize_t n = ::recv(udp_.fd(), datagram.data(), datagram.size(), 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    const Clock::time_point now = Clock::now();
    auto push =
        parse_realtime_push(std::string_view(datagram.data(), static_cast<std::size_t>(n)), settings_.speed_unit);
    if (!push) {
      ++link_counters_.bad_pushes;
      continue;
    }
    const RealtimePush& pushed = push.value();
    if (pushed.dof != settings_.dof) {
      lose_link("the controller pushes " + std::to_string(pushed.dof) + " joints but the configured model has " +
                std::to_string(settings_.dof) + "; set \"model\" to the arm's model");
      return;
    }
    ++link_counters_.pushes;
    Sample sample{.position_rad = pushed.position_rad,
                  .velocity_rad_s = std::nullopt,
                  .enabled = pushed.enabled,
                  .pose = std::nullopt,
                  .errors = pushed.errors,
                  .joint_errors = pushed.joint_errors};
    if (settings_.push_joint_speed && pushed.has_speed) sample.velocity_rad_s = pushed.speed_rad_s;
    if (pushed.has_pose) {
      const auto& q = pushed.quaternion_wxyz;
      sample.pose = driver::Pose{.position_m = pushed.position_m, .orientation_xyzw = {q[1], q[2], q[3], q[0]}};
    }
    if (!pushed.arm_status.empty()) {
      const std::lock_guard lock(status_mutex_);
      arm_status_ = pushed.arm_status;
    }
    publish(sample, now);
  }
}

void ControllerLink::poll_state(Clock::time_point now) {
  next_poll_at_ = std::max(next_poll_at_ + settings_.poll_period, now);
  if (poll_in_flight_) return;
  poll_in_flight_ = true;
  ++link_counters_.polls;
  const auto shape = reply_shape("get_current_arm_state");
  Request request{
      .command = "get_current_arm_state",
      .shape = *shape,
      .reply_timeout = settings_.feedback_timeout,
      .completion = std::nullopt,
      .completion_timeout = {},
      .deadline = {},
      .on_reply =
          [this](Result<nlohmann::json> reply) {
            poll_in_flight_ = false;
            if (!reply) {
              if (reply.error().code == ErrorCode::kTimeout) lose_link(reply.error().message);
              return;
            }
            const Message message{MessageKind::kReply, "current_arm_state", std::move(reply).value()};
            auto state = parse_current_arm_state(message);
            if (!state || state.value().dof != settings_.dof) {
              ++link_counters_.bad_pushes;
              return;
            }
            Sample sample;
            sample.position_rad = state.value().joints_rad;
            sample.errors = state.value().errors;
            sample.enabled.fill(true);  // get_current_arm_state carries no enable flags
            if (state.value().has_pose) {
              sample.pose =
                  driver::Pose{.position_m = state.value().pose.position_m,
                               .orientation_xyzw = kinematics::quaternion_xyzw_from_rpy(state.value().pose.euler_rad)};
            }
            publish(sample, Clock::now());
          },
      .on_completion = [](const Result<TrajectoryEvent>&) {},
  };
  tcp_out_ += frame(plain_request("get_current_arm_state"));
  tracker_.sent(std::move(request), now);
}

void ControllerLink::publish(const Sample& sample, Clock::time_point now) {
  ArmFeedback out;
  out.position_rad = sample.position_rad;
  out.enabled = sample.enabled;
  if (sample.velocity_rad_s) {
    out.velocity_rad_s = *sample.velocity_rad_s;
  } else if (last_feedback_at_ != Clock::time_point{}) {
    double dt_s = std::chrono::duration<double>(now - last_feedback_at_).count();
    if (settings_.push) {
      // Datagrams leave the controller every cycle; arrival jitter is not motion.
      const double cycle_s = std::chrono::duration<double>(kPushCycleUnit).count() * settings_.push_cycle;
      dt_s = std::max(1.0, std::round(dt_s / cycle_s)) * cycle_s;
    }
    if (dt_s > 0) {
      for (std::size_t j = 0; j < settings_.dof; ++j) {
        out.velocity_rad_s[j] = (sample.position_rad[j] - previous_position_[j]) / dt_s;
      }
    }
  }
  previous_position_ = sample.position_rad;
  if (sample.pose) {
    out.has_pose = true;
    out.pose = *sample.pose;
  }
  out.joint_errors = sample.joint_errors;
  out.fault = arm_fault(sample.errors, std::span(sample.joint_errors.data(), settings_.dof));
  out.sequence = ++feedback_sequence_;
  latest_ = out;
  feedback_.store(out);
  if (stopping_.load(std::memory_order_acquire) && at_rest(out, nullptr)) {
    stopping_.store(false, std::memory_order_release);
  }
  last_feedback_at_ = now;
}

void ControllerLink::follow_estop() {
  // On every pass, not every command period: the RT thread wakes this thread when an e-stop
  // begins. Never wait for the RT thread's store: with io_priority at or above the loop's (or a
  // loop without SCHED_FIFO) the writer may not get the CPU back while this thread waits. A store
  // in progress means the previous target, one pass longer.
  (void)target_.try_load(target_read_);
  if (target_read_.estop && !estop_sent_) {
    send_unawaited(plain_request("set_arm_stop"));
    streaming_ = false;
  }
  estop_sent_ = target_read_.estop;
}

void ControllerLink::stream(Clock::time_point now) {
  next_stream_at_ += settings_.command_period;
  if (next_stream_at_ <= now) next_stream_at_ = now + settings_.command_period;  // late: skip, do not burst
  const StreamTarget target = target_read_;                                      // follow_estop() read it on this pass
  if (target.estop) return;
  const ArmFeedback& measured = latest_;
  if (measured.fault.code != 0) {
    // A controller in error rejects every frame and keeps the last one it took: streaming on
    // would leave it behind, and the first frame after clear_system_err would be a jump from
    // there (over-speed, in error again). Resume from where the arm is once it is clear.
    streaming_ = false;
    return;
  }
  if (!target.active) {
    // The session ended or timed out while the arm was still on its way (low follow, filtering):
    // decelerate and stop on the path. Planned moves wait until it is at rest (stopping()).
    if (streaming_ && !at_rest(measured, &last_sent_)) {
      send_unawaited(plain_request("set_arm_slow_stop"));
      stopping_.store(true, std::memory_order_release);
    }
    streaming_ = false;
    return;
  }
  if (measured.sequence == 0) return;  // nothing to start from yet
  if (!streaming_ || restart_stream_.exchange(false)) last_sent_ = measured.position_rad;
  streaming_ = true;
  const double period_s = std::chrono::duration<double>(settings_.command_period).count();
  const double max_step = kStepMargin * std::min(kPassThroughMaxStepRad, kPassThroughMaxSpeedRadS * period_s);
  bool clipped = false;
  for (std::size_t j = 0; j < settings_.dof; ++j) {
    const double step = std::clamp(target.joints_rad[j] - last_sent_[j], -max_step, max_step);
    clipped = clipped || step != target.joints_rad[j] - last_sent_[j];
    last_sent_[j] += step;
  }
  tcp_out_ += frame(movej_canfd_request(std::span(last_sent_.data(), settings_.dof), settings_.pass_through));
  ++link_counters_.stream_frames;
  if (clipped) ++link_counters_.clipped_frames;
  if (last_stream_at_ != Clock::time_point{}) {
    const auto interval = std::chrono::duration_cast<std::chrono::nanoseconds>(now - last_stream_at_).count();
    link_counters_.stream_interval_max_ns = std::max(link_counters_.stream_interval_max_ns, interval);
  }
  last_stream_at_ = now;
}

bool ControllerLink::at_rest(const ArmFeedback& measured, const JointValues* target) const {
  constexpr double kAtTargetRad = 2e-3;
  constexpr double kAtRestRadS = 0.01;
  for (std::size_t j = 0; j < settings_.dof; ++j) {
    if (std::fabs(measured.velocity_rad_s[j]) > kAtRestRadS) return false;
    if (target != nullptr && std::fabs((*target)[j] - measured.position_rad[j]) > kAtTargetRad) return false;
  }
  return true;
}

void ControllerLink::flush_tcp() {
  if (tcp_out_.empty()) return;
  std::size_t sent = 0;
  const transport::SendResult result = transport::send_some(tcp_.fd(), tcp_out_, sent);
  tcp_out_.erase(0, sent);
  if (result == transport::SendResult::kClosed) {
    lose_link("the controller closed the TCP connection (" + settings_.controller.to_string() + ")");
  }
}

void ControllerLink::lose_link(const std::string& why) {
  if (lost_) return;
  lost_ = true;
  health_.store(LinkHealth{.lost = true, .reason = fault_of(kLinkLostFault, why)});
  tracker_.fail_all("the link to the controller was lost: " + why);
  counters_.store(link_counters_);
}

}  // namespace robotd::realman
