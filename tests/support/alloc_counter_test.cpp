// The allocation counter must count, or the zero-allocation proof means nothing. Runs with
// LD_PRELOAD=librobotd_alloc_counter.so (set by CTest).
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "rt/allocation_probe.hpp"

namespace {

TEST(AllocationCounter, IsLoaded) { EXPECT_GE(robotd::rt::thread_allocation_count(), 0); }

TEST(AllocationCounter, CountsNewOnThisThread) {
  const auto before = robotd::rt::thread_allocation_count();
  auto value = std::make_unique<int>(42);
  EXPECT_EQ(*value, 42);
  EXPECT_GE(robotd::rt::thread_allocation_count() - before, 1);
}

TEST(AllocationCounter, CountsVectorGrowthAndStrings) {
  const auto before = robotd::rt::thread_allocation_count();
  std::vector<int> values;
  // Growing without reserve() on purpose: each reallocation must be counted.
  for (int i = 0; i < 100; ++i) values.push_back(i);  // NOLINT(performance-inefficient-vector-operation)
  std::string text(200, 'x');
  EXPECT_GE(robotd::rt::thread_allocation_count() - before, 2);
  EXPECT_EQ(text.size(), 200U);
}

TEST(AllocationCounter, CountsOnlyTheCallingThread) {
  std::int64_t quiet_thread_count = -1;
  std::thread quiet([&] {
    const auto before = robotd::rt::thread_allocation_count();
    volatile double sum = 0;
    for (int i = 0; i < 1000; ++i) sum = sum + i * 0.5;
    quiet_thread_count = robotd::rt::thread_allocation_count() - before;
  });
  std::thread noisy([] {
    for (int i = 0; i < 100; ++i) auto value = std::make_unique<double>(i);
  });
  quiet.join();
  noisy.join();
  EXPECT_EQ(quiet_thread_count, 0);
}

}  // namespace
