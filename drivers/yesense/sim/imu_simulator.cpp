#include "imu_simulator.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <ctime>
#include <unistd.h>
#include <utility>

#include <spdlog/spdlog.h>

#include "robotd/imu/yesense_codec.hpp"
#include "robotd/sim_control/sim_clock.hpp"

namespace robotd::imu::sim {
namespace {

using sim_control::monotonic_ns;
using sim_control::to_timespec;

constexpr std::int64_t kMaxSleepNs = 10'000'000;  // the control channel is served at least every 10 ms
constexpr std::int64_t kReopenRetryNs = 100'000'000;
constexpr double kTemperatureC = 36.5;
constexpr std::size_t kGarbageChunk = 256;

}  // namespace

ImuSimulator::ImuSimulator(SimOptions options)
    : options_(std::move(options)),
      start_ns_(monotonic_ns()),
      period_ns_(static_cast<std::int64_t>(1e9 / options_.rate_hz)),
      body_(start_ns_) {}

Result<void> ImuSimulator::open() {
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

void ImuSimulator::run(const volatile std::sig_atomic_t& stop) {
  const sim_control::ControlServer::Handler handler = [this](const nlohmann::json& request) {
    return control(request);
  };
  std::int64_t next_frame_ns = monotonic_ns();
  while (stop == 0) {
    const std::int64_t now = monotonic_ns();
    if (control_server_) control_server_->poll(handler);
    reopen_line_if_due(now);
    check_host();
    if (now >= next_frame_ns) {
      if (line_open_ && host_connected_ && now >= paused_until_ns_) {
        send_garbage();
        send_frame(now);
      }
      next_frame_ns += period_ns_;
      if (next_frame_ns < now) next_frame_ns = now + period_ns_;  // overran: start afresh, do not race
    }
    if (!options_.quiet) log_changes();
    const timespec wake = to_timespec(std::min(next_frame_ns, now + kMaxSleepNs));
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &wake, nullptr);  // a signal ends it early
  }
  if (control_server_) control_server_->close();
  close_line();
}

void ImuSimulator::check_host() {
  if (!line_open_) return;
  std::array<std::uint8_t, 256> bytes{};
  for (;;) {
    const ssize_t n = ::read(pty_.fd(), bytes.data(), bytes.size());
    if (n > 0) {
      bytes_received_ += static_cast<std::uint64_t>(n);
      host_connected_ = true;
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    // EAGAIN: a host holds the device end open. EIO (or 0): no process has it open.
    host_connected_ = n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK);
    return;
  }
}

void ImuSimulator::send_frame(std::int64_t now_ns) {
  sequence_ = sequence_ >= yesense::kMaxSequence ? 1 : static_cast<std::uint16_t>(sequence_ + 1);
  ImuReading reading = body_.sample(now_ns);
  reading.sequence = sequence_;
  reading.has_temperature = true;
  reading.temperature_c = kTemperatureC;
  reading.has_sample_time = true;
  reading.sample_time_us = static_cast<std::uint32_t>((now_ns - start_ns_) / 1000);
  std::array<std::uint8_t, yesense::kMaxFrame> frame{};
  const std::size_t length = yesense::encode(reading, frame);
  if (corrupt_pending_ > 0) {
    --corrupt_pending_;
    ++frames_corrupted_;
    frame[length - 1] ^= 0xFFU;  // CK2
  }
  if (write_all(frame.data(), length)) {
    ++frames_sent_;
  } else {
    ++frames_dropped_;
  }
}

void ImuSimulator::send_garbage() {
  std::array<std::uint8_t, kGarbageChunk> bytes{};
  std::uniform_int_distribution<int> byte(0, 255);
  while (garbage_pending_ > 0) {
    const std::size_t count = std::min<std::uint64_t>(garbage_pending_, bytes.size());
    for (std::size_t i = 0; i < count; ++i) bytes[i] = static_cast<std::uint8_t>(byte(random_));
    // False headers among the noise, some claiming long messages, so the host must resync.
    if (count >= 5) {
      bytes[0] = yesense::kHeader1;
      bytes[1] = yesense::kHeader2;
    }
    if (!write_all(bytes.data(), count)) return;  // the host does not read: try again next frame
    garbage_pending_ -= count;
    garbage_sent_ += count;
  }
}

bool ImuSimulator::write_all(const std::uint8_t* bytes, std::size_t count) {
  ssize_t n = -1;
  do {
    n = ::write(pty_.fd(), bytes, count);
  } while (n < 0 && errno == EINTR);
  return n == static_cast<ssize_t>(count);
}

void ImuSimulator::close_line() {
  pty_.close();  // the host's end hangs up; the symlink goes
  line_open_ = false;
  host_connected_ = false;
}

void ImuSimulator::reopen_line_if_due(std::int64_t now_ns) {
  if (!reopen_line_at_ns_ || now_ns < *reopen_line_at_ns_) return;
  if (auto opened = pty_.open(options_.pty_path); !opened) {
    spdlog::warn("cannot recreate the pty: {}; retrying", opened.error().message);
    reopen_line_at_ns_ = now_ns + kReopenRetryNs;
    return;
  }
  reopen_line_at_ns_.reset();
  line_open_ = true;
}

void ImuSimulator::log_changes() {
  if (line_open_ != logged_line_open_) {
    if (line_open_) {
      spdlog::info("serial line {} -> {}", options_.pty_path, pty_.device_path());
    } else {
      spdlog::info("serial line closed (unplugged)");
    }
  }
  if (host_connected_ != logged_host_connected_) {
    spdlog::info(host_connected_ ? "host connected: streaming" : "host disconnected");
  }
  logged_line_open_ = line_open_;
  logged_host_connected_ = host_connected_;
}

}  // namespace robotd::imu::sim
