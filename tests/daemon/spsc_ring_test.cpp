// The event ring between one producer and one consumer: first in, first out; a full ring
// refuses the newest item instead of overwriting the oldest.
#include "robotd/driver/spsc_ring.hpp"

#include <atomic>
#include <cstdint>
#include <thread>

#include <gtest/gtest.h>

namespace robotd::driver {
namespace {

TEST(SpscRing, PopsItemsInTheOrderTheyWerePushed) {
  SpscRing<int, 8> ring;
  for (int i = 1; i <= 5; ++i) ASSERT_TRUE(ring.push(i));
  for (int i = 1; i <= 5; ++i) EXPECT_EQ(ring.pop(), i);
}

TEST(SpscRing, EmptyRingPopsNothing) {
  SpscRing<int, 4> ring;
  EXPECT_TRUE(ring.empty());
  EXPECT_FALSE(ring.pop().has_value());
  ASSERT_TRUE(ring.push(7));
  EXPECT_FALSE(ring.empty());
  EXPECT_EQ(ring.pop(), 7);
  EXPECT_TRUE(ring.empty());
  EXPECT_FALSE(ring.pop().has_value());
}

TEST(SpscRing, FullRingRefusesThePushAndKeepsItsItems) {
  SpscRing<int, 4> ring;
  for (int i = 1; i <= 4; ++i) ASSERT_TRUE(ring.push(i));
  EXPECT_FALSE(ring.push(99));
  for (int i = 1; i <= 4; ++i) EXPECT_EQ(ring.pop(), i);
  EXPECT_FALSE(ring.pop().has_value());
}

TEST(SpscRing, SlotsAreReusedAcrossManyWraps) {
  SpscRing<std::uint32_t, 4> ring;
  for (std::uint32_t i = 0; i < 1000; ++i) {
    ASSERT_TRUE(ring.push(i));
    ASSERT_TRUE(ring.push(i + 1'000'000));
    ASSERT_EQ(ring.pop(), i);
    ASSERT_EQ(ring.pop(), i + 1'000'000);
  }
  EXPECT_TRUE(ring.empty());
}

constexpr std::uint64_t kStressItems = 1'000'000;

TEST(SpscRing, ConcurrentProducerThatRetriesLosesNothingAndKeepsOrder) {
  SpscRing<std::uint64_t, 1024> ring;
  std::thread producer([&ring] {
    for (std::uint64_t i = 0; i < kStressItems; ++i) {
      while (!ring.push(i)) std::this_thread::yield();
    }
  });
  std::uint64_t expected = 0;
  bool in_order = true;
  while (expected < kStressItems) {
    if (const auto item = ring.pop()) {
      in_order = in_order && *item == expected;
      ++expected;
    } else {
      std::this_thread::yield();
    }
  }
  producer.join();
  EXPECT_TRUE(in_order);
  EXPECT_EQ(expected, kStressItems);
  EXPECT_TRUE(ring.empty());
}

TEST(SpscRing, ConcurrentProducerThatDoesNotWaitLosesOnlyWhatPushReportedAsRefused) {
  SpscRing<std::uint64_t, 64> ring;
  std::atomic<std::uint64_t> refused{0};
  std::atomic<bool> done{false};
  std::thread producer([&] {
    std::uint64_t failed = 0;
    for (std::uint64_t i = 0; i < kStressItems; ++i) {
      if (!ring.push(i)) ++failed;
    }
    refused.store(failed, std::memory_order_relaxed);
    done.store(true, std::memory_order_release);
  });
  std::uint64_t received = 0;
  std::uint64_t previous = 0;
  bool increasing = true;
  const auto take = [&](std::uint64_t item) {
    increasing = increasing && (received == 0 || item > previous);
    previous = item;
    ++received;
  };
  for (;;) {
    if (const auto item = ring.pop()) {
      take(*item);
    } else if (done.load(std::memory_order_acquire)) {
      while (const auto rest = ring.pop()) take(*rest);  // everything pushed before `done`
      break;
    }
  }
  producer.join();
  EXPECT_TRUE(increasing);
  EXPECT_EQ(received + refused.load(), kStressItems);
  EXPECT_GT(received, 0u);
}

}  // namespace
}  // namespace robotd::driver
