#include "simulator.hpp"

#include <algorithm>
#include <cerrno>
#include <ctime>
#include <poll.h>
#include <unistd.h>
#include <utility>

#include <spdlog/spdlog.h>
namespace robotd::parol6::sim {
namespace {

constexpr std::int64_t kLoopPeriodNs = 1'000'000;
constexpr std::int64_t kReopenRetryNs = 100'000'000;
constexpr int kMaxReadsPerPass = 64;
constexpr std::size_t kFieldBytes = 50;  // host body offsets 0 … 49 carry fields

}  // namespace

Simulator::Simulator(SimOptions options) : options_(std::move(options)), board_(options_, monotonic_ns()) {
  logged_ = summary();
}

Result<void> Simulator::open() {
  if (auto opened = pty_.open(options_.pty_path); !opened) return opened;
  line_open_ = true;
  if (!options_.control_path.empty()) {
    control_server_.emplace(options_.control_path);
    if (auto opened = control_server_->open(); !opened) {
      close_line();
      return opened;
    }
  }
  return {};
}

void Simulator::run(const volatile std::sig_atomic_t& stop) {
  std::int64_t next_pass_ns = monotonic_ns();
  const sim_control::ControlServer::Handler handler = [this](const nlohmann::json& request) {
    return control(request);
  };
  while (stop == 0) {
    const std::int64_t now = monotonic_ns();
    if (control_server_) control_server_->poll(handler);
    reopen_line_if_due(now);
    board_.run_until(now);
    read_line(now);
    send_garbage();
    if (!options_.quiet) log_changes();
    if (now >= next_pass_ns) {
      next_pass_ns += kLoopPeriodNs;
      if (next_pass_ns < now) next_pass_ns = now + kLoopPeriodNs;  // overran: start afresh, do not race
    }
    wait_until(next_pass_ns);
  }
  if (control_server_) control_server_->close();
  close_line();
}

void Simulator::wait_until(std::int64_t wake_ns) {
  if (line_open_ && host_connected_) {
    // Wakes as soon as the host writes (or hangs up), so frames are timed and answered at once.
    const std::int64_t left_ns = wake_ns - monotonic_ns();
    if (left_ns <= 0) return;
    const timespec timeout = to_timespec(left_ns);
    pollfd line{.fd = pty_.fd(), .events = POLLIN, .revents = 0};
    ppoll(&line, 1, &timeout, nullptr);
    return;
  }
  // No host: reading the master fails with EIO and polling it reports a hang-up at once, so
  // just sleep; a signal (EINTR) ends the sleep and the loop checks `stop`.
  const timespec wake = to_timespec(wake_ns);
  clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &wake, nullptr);
}

void Simulator::read_line(std::int64_t now_ns) {
  if (!line_open_) return;
  std::array<std::uint8_t, 4096> bytes{};
  for (int i = 0; i < kMaxReadsPerPass; ++i) {
    const ssize_t n = ::read(pty_.fd(), bytes.data(), bytes.size());
    if (n > 0) {
      host_connected_ = true;
      bytes_received_ += static_cast<std::uint64_t>(n);
      const std::size_t kept = faults_.filter(std::span<std::uint8_t>(bytes.data(), static_cast<std::size_t>(n)));
      parser_.feed(std::span<const std::uint8_t>(bytes.data(), kept),
                   [&](std::span<const std::uint8_t> body) { on_frame(body, now_ns); });
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    // EAGAIN: a host holds the device open and sent nothing more. EIO (or 0): no process has
    // the device end open — no host connected, not an error.
    host_connected_ = n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK);
    return;
  }
}

void Simulator::on_frame(std::span<const std::uint8_t> body, std::int64_t now_ns) {
  ++frames_received_;
  if (now_ns < silent_until_ns_) {  // hung: read and dropped, no effect, no reply
    ++frames_unanswered_;
    return;
  }
  std::copy_n(body.begin(), std::min(body.size(), data_buffer_.size()), data_buffer_.begin());
  std::array<std::uint8_t, kHostLength> image{};
  std::copy_n(data_buffer_.begin(), kFieldBytes, image.begin());
  image[kFieldBytes] = 0x01;
  image[kFieldBytes + 1] = 0x02;
  const auto frame = decode_host_body(image);
  if (!frame) return;  // cannot happen: the image always holds every field
  const std::uint8_t command_before = board_.arm().command();
  send_reply(board_.answer(*frame, now_ns));
  if (board_.arm().command() != command_before) command_since_ns_ = now_ns;
}

void Simulator::send_reply(const RobotFrame& reply) {
  const auto bytes = encode(reply);
  ssize_t n = -1;
  do {
    n = ::write(pty_.fd(), bytes.data(), bytes.size());
  } while (n < 0 && errno == EINTR);
  if (n == static_cast<ssize_t>(bytes.size())) {
    ++replies_sent_;
  } else {
    ++replies_dropped_;  // the host does not read and its buffer is full (or it just left)
  }
}

void Simulator::send_garbage() {
  if (!line_open_ || !host_connected_ || faults_.garbage_pending() == 0) return;
  std::array<std::uint8_t, 1024> bytes{};
  const std::size_t count = faults_.take_garbage(bytes);
  const ssize_t n = ::write(pty_.fd(), bytes.data(), count);
  const std::size_t written = n > 0 ? static_cast<std::size_t>(n) : 0;
  if (written < count) faults_.return_garbage(count - written);  // the rest on a later pass
}

void Simulator::close_line() {
  pty_.close();  // the host's end hangs up; the symlink goes
  line_open_ = false;
  host_connected_ = false;
  parser_.reset();
}

void Simulator::reopen_line_if_due(std::int64_t now_ns) {
  if (!reopen_line_at_ns_ || now_ns < *reopen_line_at_ns_) return;
  if (auto opened = pty_.open(options_.pty_path); !opened) {
    spdlog::warn("cannot recreate the pty: {}; retrying", opened.error().message);
    reopen_line_at_ns_ = now_ns + kReopenRetryNs;
    return;
  }
  reopen_line_at_ns_.reset();
  line_open_ = true;
}

Simulator::Summary Simulator::summary() const {
  return Summary{.command = board_.arm().command(),
                 .disabled = board_.arm().disabled(),
                 .homed_mask = board_.arm().homed_mask(),
                 .homing = board_.arm().homing().phase(),
                 .host_connected = host_connected_,
                 .line_open = line_open_,
                 .estop_pressed = board_.estop_pressed()};
}

void Simulator::log_changes() {
  const Summary now = summary();
  if (now == logged_) return;
  if (now.line_open != logged_.line_open) {
    if (now.line_open) {
      spdlog::info("serial line {} -> {}", options_.pty_path, pty_.device_path());
    } else {
      spdlog::info("serial line closed (disconnect)");
    }
  }
  if (now.host_connected != logged_.host_connected) {
    spdlog::info(now.host_connected ? "host connected" : "host disconnected");
  }
  if (now.command != logged_.command || now.disabled != logged_.disabled || now.homed_mask != logged_.homed_mask ||
      now.homing != logged_.homing || now.estop_pressed != logged_.estop_pressed) {
    spdlog::info("board: command {}{}, homed 0x{:02X}, homing {}{}", now.command, now.disabled ? ", DISABLED" : "",
                 homed_byte(now.homed_mask), phase_text(now.homing), now.estop_pressed ? ", E-STOP PRESSED" : "");
  }
  logged_ = now;
}

}  // namespace robotd::parol6::sim
