#include "device/loop_statistics.hpp"

#include <algorithm>
#include <cmath>

namespace robotd::device {

LoopStatisticsWindow::LoopStatisticsWindow(std::size_t capacity) : samples_(capacity) {}

void LoopStatisticsWindow::add(const TickTiming& timing) {
  samples_[next_] = timing;
  next_ = (next_ + 1) % samples_.size();
  count_ = std::min(count_ + 1, samples_.size());
}

void LoopStatisticsWindow::clear() {
  next_ = 0;
  count_ = 0;
}

std::vector<TickTiming> LoopStatisticsWindow::samples() const {
  std::vector<TickTiming> ordered;
  ordered.reserve(count_);
  const std::size_t oldest = (next_ + samples_.size() - count_) % samples_.size();
  for (std::size_t i = 0; i < count_; ++i) ordered.push_back(samples_[(oldest + i) % samples_.size()]);
  return ordered;
}

Percentiles percentiles(std::vector<std::int64_t>& values) {
  if (values.empty()) return {};
  const auto rank = [&](double q) {
    const auto index = static_cast<std::size_t>(std::ceil(q * static_cast<double>(values.size()))) - 1;
    const auto nth = values.begin() + static_cast<std::ptrdiff_t>(std::min(index, values.size() - 1));
    std::nth_element(values.begin(), nth, values.end());
    return static_cast<float>(static_cast<double>(*nth) / 1000.0);
  };
  Percentiles out;
  out.p50 = rank(0.50);
  out.p99 = rank(0.99);
  out.p999 = rank(0.999);
  out.max = static_cast<float>(static_cast<double>(*std::max_element(values.begin(), values.end())) / 1000.0);
  return out;
}

LoopStatistics LoopStatisticsWindow::summarize() const {
  std::vector<std::int64_t> period;
  std::vector<std::int64_t> latency;
  std::vector<std::int64_t> execution;
  period.reserve(count_);
  latency.reserve(count_);
  execution.reserve(count_);
  for (std::size_t i = 0; i < count_; ++i) {
    period.push_back(samples_[i].period_ns);
    latency.push_back(samples_[i].wake_latency_ns);
    execution.push_back(samples_[i].execution_ns);
  }
  LoopStatistics stats;
  stats.window_ticks = static_cast<std::uint32_t>(count_);
  const Percentiles p = percentiles(period);
  const Percentiles l = percentiles(latency);
  const Percentiles e = percentiles(execution);
  stats.period_p50_us = p.p50;
  stats.period_p99_us = p.p99;
  stats.period_max_us = p.max;
  stats.wake_latency_p50_us = l.p50;
  stats.wake_latency_p99_us = l.p99;
  stats.wake_latency_max_us = l.max;
  stats.execution_p50_us = e.p50;
  stats.execution_p99_us = e.p99;
  stats.execution_max_us = e.max;
  return stats;
}

}  // namespace robotd::device
