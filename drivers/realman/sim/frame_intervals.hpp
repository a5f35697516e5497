// The arrival intervals of a stream of frames (movej_canfd): a 1 µs histogram for the
// percentiles tests and the lead's jitter measurement read, and the median of the last few,
// which is the stream's period despite one late or early frame.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

namespace robotd::realman::sim {

class FrameIntervals {
 public:
  FrameIntervals() : histogram_(kBins, 0) {}

  /// A frame arrived at `now_ns` (CLOCK_MONOTONIC).
  void arrived(std::int64_t now_ns);
  /// The median of the last kRecent intervals; nullopt until kMinRecent are known.
  std::optional<double> recent_period_s() const;
  /// The interval before the last frame; nullopt for the first frame.
  std::optional<double> last_interval_s() const { return last_interval_s_; }
  /// {"count", "p50", "p99", "max"} in µs (count = intervals, not frames).
  nlohmann::json summary_us() const;

 private:
  static constexpr std::size_t kBins = 100'000;  // 1 µs each; longer intervals land in the last
  static constexpr std::size_t kRecent = 16;
  static constexpr std::size_t kMinRecent = 4;

  std::int64_t percentile_us(double fraction) const;

  std::vector<std::uint32_t> histogram_;
  std::uint64_t count_ = 0;
  std::int64_t max_us_ = 0;
  std::optional<std::int64_t> last_arrival_ns_;
  std::optional<double> last_interval_s_;
  std::array<double, kRecent> recent_s_{};
  std::size_t recent_count_ = 0;  // valid entries, up to kRecent
  std::size_t recent_next_ = 0;
};

}  // namespace robotd::realman::sim
