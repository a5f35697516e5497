// Loop timing over the most recent ticks, as nearest-rank percentiles in microseconds.
#include "device/loop_statistics.hpp"

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace robotd::device {
namespace {

TickTiming timing(std::int64_t period_ns, std::int64_t wake_latency_ns, std::int64_t execution_ns) {
  TickTiming t;
  t.period_ns = period_ns;
  t.wake_latency_ns = wake_latency_ns;
  t.execution_ns = execution_ns;
  return t;
}

TEST(Percentiles, NearestRankOnOneToHundredMicroseconds) {
  std::vector<std::int64_t> values(100);
  std::iota(values.begin(), values.end(), 1);
  for (auto& v : values) v *= 1000;  // 1..100 µs, in ns
  std::shuffle(values.begin(), values.end(), std::mt19937(7));
  const Percentiles p = percentiles(values);
  EXPECT_FLOAT_EQ(p.p50, 50.0F);
  EXPECT_FLOAT_EQ(p.p99, 99.0F);
  EXPECT_FLOAT_EQ(p.max, 100.0F);
}

TEST(Percentiles, NearestRankRoundsTheRankUp) {
  std::vector<std::int64_t> values{4000, 1000, 3000, 2000, 5000};  // p50: rank ⌈2.5⌉ = 3
  const Percentiles p = percentiles(values);
  EXPECT_FLOAT_EQ(p.p50, 3.0F);
  EXPECT_FLOAT_EQ(p.p99, 5.0F);
  EXPECT_FLOAT_EQ(p.max, 5.0F);
}

TEST(Percentiles, SingleValueIsEveryPercentile) {
  std::vector<std::int64_t> values{1500};
  const Percentiles p = percentiles(values);
  EXPECT_FLOAT_EQ(p.p50, 1.5F);
  EXPECT_FLOAT_EQ(p.p99, 1.5F);
  EXPECT_FLOAT_EQ(p.max, 1.5F);
}

TEST(Percentiles, NoValuesGiveZeros) {
  std::vector<std::int64_t> values;
  const Percentiles p = percentiles(values);
  EXPECT_EQ(p.p50, 0.0F);
  EXPECT_EQ(p.p99, 0.0F);
  EXPECT_EQ(p.max, 0.0F);
}

TEST(LoopStatisticsWindow, WindowFillsUpToItsCapacity) {
  LoopStatisticsWindow window(4);
  EXPECT_EQ(window.size(), 0u);
  EXPECT_EQ(window.summarize().window_ticks, 0u);
  for (int i = 0; i < 3; ++i) window.add(timing(1'000'000, 0, 0));
  EXPECT_EQ(window.size(), 3u);
  for (int i = 0; i < 3; ++i) window.add(timing(1'000'000, 0, 0));
  EXPECT_EQ(window.size(), 4u);
  EXPECT_EQ(window.summarize().window_ticks, 4u);
}

TEST(LoopStatisticsWindow, WrappedWindowKeepsOnlyTheNewestTicks) {
  LoopStatisticsWindow window(3);
  window.add(timing(900'000, 0, 0));  // these two old, slow ticks fall out
  window.add(timing(800'000, 0, 0));
  window.add(timing(1'000, 0, 0));
  window.add(timing(2'000, 0, 0));
  window.add(timing(3'000, 0, 0));
  const LoopStatistics stats = window.summarize();
  EXPECT_EQ(stats.window_ticks, 3u);
  EXPECT_FLOAT_EQ(stats.period_p50_us, 2.0F);
  EXPECT_FLOAT_EQ(stats.period_max_us, 3.0F);
}

TEST(LoopStatisticsWindow, SummaryReportsEachInputInItsOwnFields) {
  LoopStatisticsWindow window(100);
  for (std::int64_t i = 1; i <= 100; ++i) {
    // period 1001..1100 µs, wake latency 1..100 µs, execution 0.5..50 µs
    window.add(timing((1000 + i) * 1000, i * 1000, i * 500));
  }
  const LoopStatistics stats = window.summarize();
  EXPECT_EQ(stats.window_ticks, 100u);
  EXPECT_FLOAT_EQ(stats.period_p50_us, 1050.0F);
  EXPECT_FLOAT_EQ(stats.period_p99_us, 1099.0F);
  EXPECT_FLOAT_EQ(stats.period_max_us, 1100.0F);
  EXPECT_FLOAT_EQ(stats.wake_latency_p50_us, 50.0F);
  EXPECT_FLOAT_EQ(stats.wake_latency_p99_us, 99.0F);
  EXPECT_FLOAT_EQ(stats.wake_latency_max_us, 100.0F);
  EXPECT_FLOAT_EQ(stats.execution_p50_us, 25.0F);
  EXPECT_FLOAT_EQ(stats.execution_p99_us, 49.5F);
  EXPECT_FLOAT_EQ(stats.execution_max_us, 50.0F);
}

TEST(LoopStatisticsWindow, AStallOfSecondsIsReportedAsItWasNotWrappedAround) {
  // 2.1 s is beyond a 32-bit count of nanoseconds; a stall that long must still read as one.
  LoopStatisticsWindow window(10);
  window.add(timing(1'000'000, 1'000, 500));
  window.add(timing(5'001'000'000, 5'000'000'000, 500));
  const LoopStatistics stats = window.summarize();
  EXPECT_FLOAT_EQ(stats.wake_latency_max_us, 5'000'000.0F);
  EXPECT_FLOAT_EQ(stats.period_max_us, 5'001'000.0F);
}

}  // namespace
}  // namespace robotd::device
