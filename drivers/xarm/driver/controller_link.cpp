#include "driver/controller_link.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <ctime>
#include <future>
#include <memory>
#include <poll.h>
#include <sys/socket.h>
#include <system_error>
#include <unistd.h>

#include "driver/xarm_fault.hpp"
#include "robotd/kinematics/rotation.hpp"

namespace robotd::xarm {
namespace {

constexpr auto kIdleWake = std::chrono::milliseconds(50);
/// Slack beyond the link thread's own deadline before a waiting caller gives up by itself.
constexpr auto kCallerSlack = std::chrono::seconds(1);
constexpr auto kErrorPollTimeout = std::chrono::milliseconds(500);
/// How long the box must show a stop under a streaming session, with no error read, before it is
/// taken as stopped by somebody else (a few error polls and reports).
constexpr auto kUnexplainedStop = std::chrono::milliseconds(300);

std::string errno_text(int error) { return std::generic_category().message(error); }

std::chrono::nanoseconds report_period(ReportKind kind) {
  switch (kind) {
    case ReportKind::kReal:
      return std::chrono::milliseconds(10);
    case ReportKind::kNormal:
    case ReportKind::kRich:
      return std::chrono::milliseconds(200);
    case ReportKind::kRealtime:
      return std::chrono::milliseconds(4);
  }
  return std::chrono::milliseconds(10);
}

}  // namespace

Result<void> ControllerLink::open(const LinkSettings& settings, const driver::AbortFlag* abort) {
  close();
  settings_ = settings;
  auto command = transport::connect_tcp(settings.controller, settings.connect_timeout, abort);
  if (!command) return command.error();
  command_ = std::move(command).value();
  auto report = transport::connect_tcp(settings.report, settings.connect_timeout, abort);
  if (!report) {
    command_.reset();
    return make_error(report.error().code, "the command port answers but the " +
                                               std::string(report_kind_name(settings.report_kind)) +
                                               " report port does not: " + report.error().message);
  }
  report_ = std::move(report).value();

  transactions_ = TransactionTable{};
  frames_.clear();
  reports_.clear();
  command_out_.clear();
  link_counters_ = LinkCounters{};
  counters_.store(link_counters_);
  latest_ = ArmFeedback{};
  feedback_.store(latest_);
  health_.store(LinkHealth{});
  target_.store(StreamTarget{});
  target_read_ = StreamTarget{};
  restart_requested_.store(false);
  feedback_sequence_ = 0;
  last_report_at_ = {};
  codes_ = ErrorWarning{};
  last_status_ = StatusBits{};
  error_poll_in_flight_ = false;
  phase_ = ServoPhase::kPosition;
  servo_fault_.clear();
  generation_ = 0;
  confirm_after_ = 0;
  leave_requested_at_ = {};
  stopped_since_ = {};
  estop_sent_ = false;
  lost_ = false;
  const Clock::time_point now = Clock::now();
  next_error_poll_at_ = now;
  next_servo_at_ = now;
  last_servo_at_ = {};
  return io_.start("xarm-link", settings.io_priority, [this] { run(); });
}

void ControllerLink::close() noexcept {
  io_.stop();
  std::vector<Outgoing> abandoned;
  {
    const std::lock_guard lock(queue_mutex_);
    abandoned.swap(queue_);
  }
  for (Outgoing& outgoing : abandoned) {
    outgoing.on_reply(make_error(ErrorCode::kNotAvailable, "the link to the control box was closed"));
  }
  command_.reset();
  report_.reset();
}

Result<Reply> ControllerLink::request(const Request& request, std::chrono::milliseconds timeout,
                                      const driver::AbortFlag* abort) {
  if (!is_open() || health().lost) return make_error(ErrorCode::kNotAvailable, "not connected to the control box");
  auto replied = std::make_shared<std::promise<Result<Reply>>>();
  auto reply = replied->get_future();
  {
    const std::lock_guard lock(queue_mutex_);
    queue_.push_back(Outgoing{.request = request, .timeout = timeout, .on_reply = [replied](Result<Reply> result) {
                                replied->set_value(std::move(result));
                              }});
  }
  wake();
  if (!driver::wait_ready(reply, timeout + kCallerSlack, abort)) {
    if (abort != nullptr && abort->requested())
      return driver::aborted_error("waiting for " + register_name(request.reg));
    return make_error(ErrorCode::kTimeout, "no reply to " + register_name(request.reg) + " from the control box");
  }
  return reply.get();
}

void ControllerLink::restart() {
  restart_requested_.store(true, std::memory_order_release);
  wake();
}

void ControllerLink::run() noexcept {
  try {
    while (!io_.stopping() && !lost_) {
      serve(Clock::now());
      if (!lost_) wait_for_io(Clock::now());
    }
    transactions_.fail_all(lost_ ? "the link to the control box was lost" : "the link to the control box was closed");
  } catch (const std::exception& error) {
    lose_link(std::string("link thread failed: ") + error.what());
    transactions_.fail_all("the link to the control box failed");
  }
}

void ControllerLink::serve(Clock::time_point now) {
  io_.drain();
  take_requests(now);
  read_command_port();
  read_report_port(now);
  if (lost_) return;
  if (restart_requested_.exchange(false)) {
    ++generation_;
    phase_ = ServoPhase::kPosition;
    servo_fault_.clear();
    next_error_poll_at_ = now;
  }
  poll_errors(now);
  drive_servo(now);
  link_counters_.timeouts += transactions_.expire(now);
  if (last_report_at_ != Clock::time_point{} && now - last_report_at_ > settings_.report_timeout) {
    const auto silent_ms = std::chrono::duration_cast<std::chrono::milliseconds>(now - last_report_at_).count();
    lose_link("no report from the control box for " + std::to_string(silent_ms) + " ms (expected every " +
              std::to_string(
                  std::chrono::duration_cast<std::chrono::milliseconds>(report_period(settings_.report_kind)).count()) +
              " ms on " + settings_.report.to_string() + ")");
    return;
  }
  flush_command_port();
  counters_.store(link_counters_);
}

void ControllerLink::wait_for_io(Clock::time_point now) {
  Clock::time_point until = now + kIdleWake;
  if (phase_ == ServoPhase::kServo) until = std::min(until, next_servo_at_);
  until = std::min(until, next_error_poll_at_);
  if (const auto deadline = transactions_.next_deadline()) until = std::min(until, *deadline);
  std::array<pollfd, 3> fds{{
      {.fd = io_.wake_fd(), .events = POLLIN, .revents = 0},
      {.fd = command_.fd(), .events = static_cast<short>(POLLIN | (command_out_.empty() ? 0 : POLLOUT)), .revents = 0},
      {.fd = report_.fd(), .events = POLLIN, .revents = 0},
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
  for (Outgoing& outgoing : taken) send(outgoing.request, now, outgoing.timeout, std::move(outgoing.on_reply));
}

void ControllerLink::send(const Request& request, Clock::time_point now, std::chrono::milliseconds timeout,
                          TransactionTable::Callback on_reply) {
  const std::uint16_t id = transactions_.next_id();
  const Bytes frame = encode_frame(
      Frame{.transaction_id = id, .protocol = kProtocolPrivate, .reg = request.reg, .body = request.params});
  command_out_.insert(command_out_.end(), frame.begin(), frame.end());
  transactions_.add(id, request.reg, now + timeout, std::move(on_reply));
  ++link_counters_.requests;
}

void ControllerLink::read_command_port() {
  std::array<std::uint8_t, 4096> buffer{};
  for (;;) {
    const ssize_t n = ::recv(command_.fd(), buffer.data(), buffer.size(), 0);
    if (n == 0) {
      lose_link("the control box closed the command connection (" + settings_.controller.to_string() + ")");
      return;
    }
    if (n < 0) {
      if (errno == EINTR) continue;
      if (errno == EAGAIN || errno == EWOULDBLOCK) return;
      if (errno == ECONNRESET) {
        lose_link("the control box closed the command connection (" + settings_.controller.to_string() + ", reset)");
        return;
      }
      lose_link("command connection to " + settings_.controller.to_string() + " failed (" + errno_text(errno) + ")");
      return;
    }
    frames_.append(ByteView(buffer.data(), static_cast<std::size_t>(n)));
    for (;;) {
      auto frame = frames_.next();
      if (!frame) {
        lose_link("the command port's byte stream from " + settings_.controller.to_string() +
                  " lost its framing: " + frame.error().message);
        return;
      }
      if (!frame.value()) break;
      handle_frame(*frame.value());
      if (lost_) return;
    }
  }
}

void ControllerLink::handle_frame(const Frame& frame) {
  if (is_motion_feedback(frame)) {
    ++link_counters_.motion_feedback;  // only sent after set_feedback_type, which robotd does not use
    return;
  }
  auto reply = parse_reply(frame);
  if (!reply) {
    ++link_counters_.unmatched;
    return;
  }
  watch_status(reply.value());
  if (!transactions_.answer(std::move(reply).value())) ++link_counters_.unmatched;
}

void ControllerLink::watch_status(const Reply& reply) {
  const bool changed = reply.status.error != last_status_.error || reply.status.warning != last_status_.warning;
  last_status_ = reply.status;
  const bool unread = (reply.status.error && codes_.error == 0) || (reply.status.warning && codes_.warning == 0) ||
                      (!reply.status.error && codes_.error != 0) || (!reply.status.warning && codes_.warning != 0);
  if (changed || unread) next_error_poll_at_ = std::min(next_error_poll_at_, Clock::now());
}

void ControllerLink::read_report_port(Clock::time_point now) {
  std::array<std::uint8_t, 4096> buffer{};
  for (;;) {
    const ssize_t n = ::recv(report_.fd(), buffer.data(), buffer.size(), 0);
    if (n == 0) {
      lose_link("the control box closed the report connection (" + settings_.report.to_string() + ")");
      return;
    }
    if (n < 0) {
      if (errno == EINTR) continue;
      if (errno == EAGAIN || errno == EWOULDBLOCK) return;
      if (errno == ECONNRESET) {
        lose_link("the control box closed the report connection (" + settings_.report.to_string() + ", reset)");
        return;
      }
      lose_link("report connection to " + settings_.report.to_string() + " failed (" + errno_text(errno) + ")");
      return;
    }
    reports_.append(ByteView(buffer.data(), static_cast<std::size_t>(n)));
    for (;;) {
      auto packet = reports_.next();
      if (!packet) {
        lose_link("the report stream from " + settings_.report.to_string() +
                  " lost its framing: " + packet.error().message);
        return;
      }
      if (!packet.value()) break;
      auto report = parse_report(*packet.value(), settings_.report_kind);
      if (!report) {
        ++link_counters_.bad_reports;
        continue;
      }
      ++link_counters_.reports;
      publish(report.value(), now);
    }
  }
}

void ControllerLink::publish(const Report& report, Clock::time_point now) {
  ArmFeedback out;
  out.position_rad = report.position_rad;
  if (report.has_velocity) {
    out.velocity_rad_s = report.velocity_rad_s;
  } else if (last_report_at_ != Clock::time_point{}) {
    // Packets leave the box every period; arrival jitter is not motion.
    const double period_s = std::chrono::duration<double>(report_period(settings_.report_kind)).count();
    const double elapsed_s = std::chrono::duration<double>(now - last_report_at_).count();
    const double dt_s = std::max(1.0, std::round(elapsed_s / period_s)) * period_s;
    for (std::size_t j = 0; j < settings_.dof; ++j) {
      out.velocity_rad_s[j] = (report.position_rad[j] - latest_.position_rad[j]) / dt_s;
    }
  }
  out.effort = report.effort;
  out.pose = driver::Pose{.position_m = report.tcp_pose.position_m,
                          .orientation_xyzw = kinematics::quaternion_xyzw_from_rpy(report.tcp_pose.rpy_rad)};
  out.state = report.state;
  out.mode = report.mode;
  out.cmd_num = report.cmd_num;
  if (report.has_codes) codes_ = ErrorWarning{.error = report.error_code, .warning = report.warning_code};
  out.error_code = codes_.error;
  out.warning_code = codes_.warning;
  out.phase = phase_;
  // The box stops on any error (state 4); a stop while streaming that no error explains is
  // somebody else's set_state(4) — the session's commands no longer move the arm. The error's
  // code may come a poll after the report that shows the stop, so the stop must last first.
  const bool stopped = report.state == kStateStopped || report.state == kStateReset;
  if (phase_ != ServoPhase::kServo || estop_sent_ || !stopped) {
    stopped_since_ = {};
  } else if (stopped_since_ == Clock::time_point{}) {
    stopped_since_ = now;
  } else if (codes_.error == 0 && !last_status_.error && now - stopped_since_ > kUnexplainedStop) {
    servo_fault_.set(kArmStoppedFault, ("the control box left servo mode: " + motion_state_text(report.state) +
                                        " while a session streams; recover to continue")
                                           .c_str());
  }
  out.fault = arm_fault(codes_.error, servo_fault_);
  out.sequence = ++feedback_sequence_;
  latest_ = out;
  feedback_.store(out);
  last_report_at_ = now;
}

void ControllerLink::poll_errors(Clock::time_point now) {
  if (now < next_error_poll_at_ || error_poll_in_flight_) return;
  next_error_poll_at_ = now + settings_.error_poll_period;
  error_poll_in_flight_ = true;
  ++link_counters_.error_polls;
  send(plain_request(Register::kGetErrCode), now, kErrorPollTimeout, [this](Result<Reply> reply) {
    error_poll_in_flight_ = false;
    if (!reply) return;
    if (auto codes = parse_err_code(reply.value().data)) apply_codes(codes.value());
  });
}

void ControllerLink::apply_codes(const ErrorWarning& codes) {
  codes_ = codes;
  latest_.error_code = codes.error;
  latest_.warning_code = codes.warning;
  latest_.fault = arm_fault(codes.error, servo_fault_);
  feedback_.store(latest_);
}

void ControllerLink::flush_command_port() {
  if (command_out_.empty()) return;
  std::size_t sent = 0;
  const std::string_view bytes(reinterpret_cast<const char*>(command_out_.data()), command_out_.size());
  const transport::SendResult result = transport::send_some(command_.fd(), bytes, sent);
  command_out_.erase(command_out_.begin(), command_out_.begin() + static_cast<std::ptrdiff_t>(sent));
  if (result == transport::SendResult::kClosed) {
    lose_link("the control box closed the command connection (" + settings_.controller.to_string() + ")");
  }
}

void ControllerLink::lose_link(const std::string& why) {
  if (lost_) return;
  lost_ = true;
  LinkHealth health;
  health.lost = true;
  health.reason.set(kLinkLostFault, why.c_str());
  health_.store(health);
  transactions_.fail_all("the link to the control box was lost: " + why);
  counters_.store(link_counters_);
}

}  // namespace robotd::xarm
