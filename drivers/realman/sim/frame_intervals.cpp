#include "frame_intervals.hpp"

#include <algorithm>

namespace robotd::realman::sim {

void FrameIntervals::arrived(std::int64_t now_ns) {
  if (last_arrival_ns_) {
    const std::int64_t interval_ns = std::max<std::int64_t>(0, now_ns - *last_arrival_ns_);
    const std::int64_t interval_us = interval_ns / 1000;
    ++histogram_[std::min(static_cast<std::size_t>(interval_us), kBins - 1)];
    ++count_;
    max_us_ = std::max(max_us_, interval_us);
    last_interval_s_ = static_cast<double>(interval_ns) * 1e-9;
    recent_s_[recent_next_] = *last_interval_s_;
    recent_next_ = (recent_next_ + 1) % kRecent;
    recent_count_ = std::min(recent_count_ + 1, kRecent);
  }
  last_arrival_ns_ = now_ns;
}

std::optional<double> FrameIntervals::recent_period_s() const {
  if (recent_count_ < kMinRecent) return std::nullopt;
  std::array<double, kRecent> sorted = recent_s_;
  const auto end = sorted.begin() + static_cast<std::ptrdiff_t>(recent_count_);
  const auto middle = sorted.begin() + static_cast<std::ptrdiff_t>(recent_count_ / 2);
  std::nth_element(sorted.begin(), middle, end);
  return *middle;
}

std::int64_t FrameIntervals::percentile_us(double fraction) const {
  if (count_ == 0) return 0;
  const auto wanted = static_cast<std::uint64_t>(fraction * static_cast<double>(count_ - 1)) + 1;
  std::uint64_t seen = 0;
  for (std::size_t bin = 0; bin + 1 < kBins; ++bin) {
    seen += histogram_[bin];
    if (seen >= wanted) return static_cast<std::int64_t>(bin);
  }
  return max_us_;  // in the overflow bin: the longest is the best bound known
}

nlohmann::json FrameIntervals::summary_us() const {
  return {{"count", count_}, {"p50", percentile_us(0.5)}, {"p99", percentile_us(0.99)}, {"max", max_us_}};
}

}  // namespace robotd::realman::sim
