#include "frame_intervals.hpp"

#include <algorithm>

namespace robotd::realman::sim {

void FrameIntervals::arrived(std::int64_t now_ns, bool first_of_stream) {
  if (last_arrival_ns_) {
    const std::int64_t interval_us = std::max<std::int64_t>(0, now_ns - *last_arrival_ns_) / 1000;
    ++histogram_[std::min(static_cast<std::size_t>(interval_us), kBins - 1)];
    ++count_;
    max_us_ = std::max(max_us_, interval_us);
  }
  last_arrival_ns_ = now_ns;
  if (first_of_stream) stream_arrivals_ns_.clear();
  stream_arrivals_ns_.push_back(now_ns);
  while (now_ns - stream_arrivals_ns_.front() > kPeriodWindowNs) stream_arrivals_ns_.pop_front();
}

std::optional<double> FrameIntervals::stream_period_s() const {
  if (stream_arrivals_ns_.size() < 2) return std::nullopt;
  const std::int64_t span_ns = stream_arrivals_ns_.back() - stream_arrivals_ns_.front();
  if (span_ns < kMinPeriodSpanNs) return std::nullopt;
  return static_cast<double>(span_ns) * 1e-9 / static_cast<double>(stream_arrivals_ns_.size() - 1);
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
