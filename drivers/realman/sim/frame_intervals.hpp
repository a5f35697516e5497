// The arrival intervals of a stream of frames (movej_canfd): a 1 µs histogram for the
// percentiles tests and the lead's jitter measurement read, and the stream's period: the mean
// interval over the last second, which batching cannot shrink. A client without TCP_NODELAY
// (the vendor SDK) has its frames coalesced by Nagle and delayed ACKs, so several arrive at once
// after a gap of tens of ms; any one interval says nothing about the rate it streams at.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

namespace robotd::realman::sim {

class FrameIntervals {
 public:
  FrameIntervals() : histogram_(kBins, 0) {}

  /// A frame arrived at `now_ns` (CLOCK_MONOTONIC); `first_of_stream` forgets the period of the
  /// stream before (the arm held meanwhile).
  void arrived(std::int64_t now_ns, bool first_of_stream);
  /// The mean interval of the frames that arrived in the last kPeriodWindowNs; nullopt until
  /// they span kMinPeriodSpanNs (a batch of frames has no period of its own).
  std::optional<double> stream_period_s() const;
  /// {"count", "p50", "p99", "max"} in µs (count = intervals, not frames).
  nlohmann::json summary_us() const;

 private:
  static constexpr std::size_t kBins = 100'000;  // 1 µs each; longer intervals land in the last
  static constexpr std::int64_t kPeriodWindowNs = 1'000'000'000;
  // Linux delays an ACK up to 40 ms: over 250 ms that shortens the span by at most a sixth.
  static constexpr std::int64_t kMinPeriodSpanNs = 250'000'000;

  std::int64_t percentile_us(double fraction) const;

  std::vector<std::uint32_t> histogram_;
  std::uint64_t count_ = 0;
  std::int64_t max_us_ = 0;
  std::optional<std::int64_t> last_arrival_ns_;
  std::deque<std::int64_t> stream_arrivals_ns_;  // this stream's, within the last kPeriodWindowNs
};

}  // namespace robotd::realman::sim
