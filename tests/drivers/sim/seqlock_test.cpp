#include "robotd/driver/seqlock.hpp"

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <thread>

#include <gtest/gtest.h>

namespace robotd::driver {
namespace {

// Not a multiple of 8 bytes: exercises the partial last word.
struct Sample {
  std::array<std::uint64_t, 127> words{};
  std::uint32_t tail = 0;
};

TEST(SeqLock, LoadReturnsTheLastStoredValue) {
  SeqLock<Sample> lock;
  Sample sample;
  sample.words.fill(7);
  sample.tail = 9;
  lock.store(sample);
  const Sample loaded = lock.load();
  EXPECT_EQ(loaded.words, sample.words);
  EXPECT_EQ(loaded.tail, 9u);
}

TEST(SeqLock, ReadersNeverSeeATornValue) {
  SeqLock<Sample> lock;
  std::atomic<bool> reading{true};
  std::thread writer([&] {
    Sample sample;
    for (std::uint32_t generation = 1; reading.load(std::memory_order_relaxed); ++generation) {
      sample.words.fill(generation);
      sample.tail = generation;
      lock.store(sample);
    }
  });
  // Read until the writer has published many generations (it may start late on a busy machine).
  int torn_words = 0;
  std::uint32_t newest_generation = 0;
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  for (int read = 0; (read < 20'000 || newest_generation < 1000) && std::chrono::steady_clock::now() < give_up;
       ++read) {
    const Sample sample = lock.load();
    for (const std::uint64_t word : sample.words) torn_words += word != sample.tail ? 1 : 0;
    newest_generation = sample.tail;
  }
  reading.store(false);
  writer.join();
  EXPECT_EQ(torn_words, 0);
  EXPECT_GT(newest_generation, 0u);
}

}  // namespace
}  // namespace robotd::driver
