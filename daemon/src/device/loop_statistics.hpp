// Loop timing over a sliding window of the most recent ticks, summarised as percentiles.
// Fed off the RT thread (from the timing ring), so the loop itself only pushes three numbers.
#pragma once

#include <cstdint>
#include <vector>

#include "device/device_channel.hpp"
#include "robotd/messages.hpp"

namespace robotd::device {

class LoopStatisticsWindow {
 public:
  explicit LoopStatisticsWindow(std::size_t capacity);

  void add(const TickTiming& timing);
  void clear();
  std::size_t size() const { return count_; }
  /// The samples in the window, oldest first.
  std::vector<TickTiming> samples() const;
  /// p50 / p99 / max of period, wake latency and execution time over the window, in µs.
  LoopStatistics summarize() const;

 private:
  std::vector<TickTiming> samples_;
  std::size_t next_ = 0;
  std::size_t count_ = 0;
};

struct Percentiles {
  float p50 = 0;
  float p99 = 0;
  float p999 = 0;
  float max = 0;
};

/// Percentiles of `values` (reordered in place), nearest-rank.
Percentiles percentiles(std::vector<std::int64_t>& values);

}  // namespace robotd::device
