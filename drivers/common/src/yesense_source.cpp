#include "yesense_source.hpp"

#include <algorithm>
#include <array>
#include <poll.h>
#include <span>
#include <utility>

#include "imu_source_internal.hpp"
#include "robotd/driver/monotonic_clock.hpp"

namespace robotd::imu {
namespace {

using driver::monotonic_now_ns;

constexpr std::int64_t kReopenPeriodNs = 1'000'000'000;  // unplugged: try again every second
constexpr std::int64_t kRateWindowNs = 1'000'000'000;
constexpr int kMaxPollMs = 50;  // the longest the thread sleeps before checking for staleness
constexpr int kMaxReadsPerWake = 16;
constexpr int kReaderPriority = 0;  // normal scheduling: the RT loop only copies the newest sample

}  // namespace

YesenseSource::YesenseSource(ImuSourceConfig config) : config_(std::move(config)), port_(config_.serial) {}

std::string YesenseSource::describe() const { return "yesense on " + config_.serial.device; }

Result<void> YesenseSource::start() {
  stop();
  have_sample_.store(false);
  have_sequence_ = false;
  splitter_.reset();
  next_open_ns_ = 0;
  rate_window_start_ns_ = monotonic_now_ns();
  rate_window_samples_ = samples_.load();
  rate_hz_.store(0);
  link_.store(LinkState::kDown);
  try_open(monotonic_now_ns());  // here, so that status() says at once whether the device is there
  return thread_.start("imu-yesense", kReaderPriority, [this] { run(); });
}

void YesenseSource::stop() noexcept {
  thread_.stop();
  port_.close();
  have_sample_.store(false);
  link_.store(LinkState::kStopped);
  rate_hz_.store(0);
}

bool YesenseSource::latest_reading(ImuReading& out, std::int64_t& stamp_ns) const noexcept {
  if (!have_sample_.load(std::memory_order_acquire)) return false;
  if (link_.load(std::memory_order_relaxed) == LinkState::kDown) return false;  // unplugged: stale at once
  StampedReading stamped;
  // The reader stores ~150 bytes once per frame (every few ms): a couple of attempts find a
  // quiet moment; the RT thread never waits for one.
  constexpr int kAttempts = 4;
  bool loaded = false;
  for (int i = 0; i < kAttempts && !loaded; ++i) loaded = latest_.try_load(stamped);
  if (!loaded) return false;
  if (monotonic_now_ns() - stamped.stamp_ns > config_.timeout_ms * 1'000'000) return false;
  out = stamped.reading;
  stamp_ns = stamped.stamp_ns;
  return true;
}

ImuStatus YesenseSource::status() const {
  ImuStatus status;
  status.link = link_.load();
  status.samples = samples_.load();
  status.checksum_errors = checksum_errors_.load();
  status.malformed = malformed_.load();
  status.bytes_discarded = bytes_discarded_.load();
  status.sequence_gaps = sequence_gaps_.load();
  status.opens = opens_.load();
  status.rate_hz = rate_hz_.load();
  if (have_sample_.load()) {
    const StampedReading stamped = latest_.load_non_rt();
    status.age_ms = static_cast<double>(monotonic_now_ns() - stamped.stamp_ns) / 1e6;
    status.content = content_of(stamped.reading);
  }
  if (status.link != LinkState::kUp) {
    const std::lock_guard lock(error_mutex_);
    status.error = error_;
  }
  return status;
}

void YesenseSource::set_error(std::string text) {
  const std::lock_guard lock(error_mutex_);
  error_ = std::move(text);
}

// --- the reader thread ----------------------------------------------------------------------------

void YesenseSource::run() {
  while (!thread_.stopping()) {
    const std::int64_t now = monotonic_now_ns();
    if (!port_.is_open()) {
      if (now >= next_open_ns_) try_open(now);
      if (!port_.is_open()) {
        const std::int64_t left_ms = (next_open_ns_ - now) / 1'000'000;
        wait(static_cast<int>(std::clamp<std::int64_t>(left_ms, 1, kMaxPollMs)));
        update_state(monotonic_now_ns());
        continue;
      }
    }
    wait(static_cast<int>(std::min<std::int64_t>(config_.timeout_ms, kMaxPollMs)));
    read_line();
    update_state(monotonic_now_ns());
  }
  port_.close();
}

void YesenseSource::wait(int timeout_ms) const {
  std::array<pollfd, 2> fds{
      {{.fd = thread_.wake_fd(), .events = POLLIN, .revents = 0}, {.fd = port_.fd(), .events = POLLIN, .revents = 0}}};
  const nfds_t count = port_.is_open() ? 2 : 1;
  poll(fds.data(), count, timeout_ms);
  thread_.drain();
}

void YesenseSource::try_open(std::int64_t now_ns) {
  next_open_ns_ = now_ns + kReopenPeriodNs;
  if (auto opened = port_.open(); !opened) {
    link_.store(LinkState::kDown);
    set_error(opened.error().message);
    return;
  }
  port_.flush();  // what waited in the kernel is old
  splitter_.reset();
  have_sequence_ = false;
  opens_.fetch_add(1);
  link_.store(LinkState::kSilent);
  set_error("no valid frame yet from " + config_.serial.device + " at " + std::to_string(config_.serial.baud) +
            " baud");
}

void YesenseSource::lose_line(const std::string& why, std::int64_t now_ns) {
  port_.close();
  splitter_.reset();
  link_.store(LinkState::kDown);
  set_error(why);
  next_open_ns_ = now_ns + kReopenPeriodNs;
}

void YesenseSource::read_line() {
  std::array<std::uint8_t, 1024> bytes{};
  for (int i = 0; i < kMaxReadsPerWake; ++i) {
    std::size_t count = 0;
    const transport::SerialIo result = port_.read(bytes, count);
    const std::int64_t now = monotonic_now_ns();
    if (result == transport::SerialIo::kClosed) {
      lose_line(config_.serial.device + " closed (unplugged?); reopening every second", now);
      return;
    }
    if (result != transport::SerialIo::kDone) break;
    std::span<const std::uint8_t> input(bytes.data(), count);
    yesense::Frame frame;
    while (splitter_.next(input, frame)) on_frame(frame, now);
  }
  const auto& counters = splitter_.counters();
  checksum_errors_.store(counters.checksum_errors);
  malformed_.store(counters.oversize + undecodable_);
  bytes_discarded_.store(counters.bytes_discarded);
}

void YesenseSource::on_frame(const yesense::Frame& frame, std::int64_t now_ns) {
  StampedReading stamped;
  stamped.stamp_ns = now_ns;
  if (yesense::decode(frame.sequence, frame.payload, stamped.reading) != yesense::DecodeStatus::kOk) {
    ++undecodable_;
    return;
  }
  if (have_sequence_) {
    const std::uint16_t expected = last_sequence_ >= yesense::kMaxSequence ? 1 : last_sequence_ + 1;
    if (frame.sequence != expected) sequence_gaps_.fetch_add(1);
  }
  have_sequence_ = true;
  last_sequence_ = frame.sequence;
  latest_.store(stamped);
  last_sample_ns_ = now_ns;
  have_sample_.store(true, std::memory_order_release);
  samples_.fetch_add(1);
}

void YesenseSource::update_state(std::int64_t now_ns) {
  if (now_ns - rate_window_start_ns_ >= kRateWindowNs) {
    const std::uint64_t samples = samples_.load();
    rate_hz_.store(static_cast<double>(samples - rate_window_samples_) * 1e9 /
                   static_cast<double>(now_ns - rate_window_start_ns_));
    rate_window_start_ns_ = now_ns;
    rate_window_samples_ = samples;
  }
  if (!port_.is_open()) return;
  const bool fresh = have_sample_.load() && now_ns - last_sample_ns_ <= config_.timeout_ms * 1'000'000;
  if (fresh) {
    link_.store(LinkState::kUp);
    return;
  }
  if (link_.exchange(LinkState::kSilent) == LinkState::kUp) {
    set_error("no valid frame from " + config_.serial.device + " for more than " + std::to_string(config_.timeout_ms) +
              " ms");
  }
}

}  // namespace robotd::imu
