// The Yesense IMU as an ImuSource: a reader thread on its USB serial line splits and decodes
// frames (yesense_codec.hpp) and publishes the newest sample through a seqlock. It reopens the
// line every second while it is gone.
#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>

#include "robotd/driver/seqlock.hpp"
#include "robotd/imu/imu_source.hpp"
#include "robotd/imu/yesense_codec.hpp"
#include "robotd/transport/io_thread.hpp"
#include "robotd/transport/serial_port.hpp"

namespace robotd::imu {

/// A sample and when the reader read it (CLOCK_MONOTONIC ns).
struct StampedReading {
  ImuReading reading;
  std::int64_t stamp_ns = 0;
};

class YesenseSource final : public ImuSource {
 public:
  explicit YesenseSource(ImuSourceConfig config);
  ~YesenseSource() override { stop(); }

  Result<void> start() override;
  void stop() noexcept override;
  bool latest_reading(ImuReading& out, std::int64_t& stamp_ns) const noexcept override;
  ImuStatus status() const override;
  std::string describe() const override;

 private:
  // The reader thread's.
  void run();
  void try_open(std::int64_t now_ns);
  void read_line();
  void on_frame(const yesense::Frame& frame, std::int64_t now_ns);
  void lose_line(const std::string& why, std::int64_t now_ns);
  void update_state(std::int64_t now_ns);
  void wait(int timeout_ms) const;
  void set_error(std::string text);

  ImuSourceConfig config_;
  transport::SerialPort port_;
  transport::IoThread thread_;
  yesense::FrameSplitter splitter_;
  std::int64_t next_open_ns_ = 0;
  std::int64_t rate_window_start_ns_ = 0;
  std::uint64_t rate_window_samples_ = 0;
  std::uint64_t undecodable_ = 0;  // checked frames whose items did not decode
  std::int64_t last_sample_ns_ = 0;
  bool have_sequence_ = false;
  std::uint16_t last_sequence_ = 0;

  // Shared with the driver's threads.
  driver::SeqLock<StampedReading> latest_;
  std::atomic<bool> have_sample_{false};
  std::atomic<LinkState> link_{LinkState::kStopped};
  std::atomic<std::uint64_t> samples_{0};
  std::atomic<std::uint64_t> checksum_errors_{0};
  std::atomic<std::uint64_t> malformed_{0};
  std::atomic<std::uint64_t> bytes_discarded_{0};
  std::atomic<std::uint64_t> sequence_gaps_{0};
  std::atomic<std::uint64_t> opens_{0};
  std::atomic<double> rate_hz_{0};
  mutable std::mutex error_mutex_;
  std::string error_;
};

}  // namespace robotd::imu
