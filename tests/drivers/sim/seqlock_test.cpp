#include "robotd/driver/seqlock.hpp"

#include <array>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <ctime>
#include <memory>
#include <pthread.h>
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
  const Sample loaded = lock.load_non_rt();
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
    const Sample sample = lock.load_non_rt();
    for (const std::uint64_t word : sample.words) torn_words += word != sample.tail ? 1 : 0;
    newest_generation = sample.tail;
  }
  reading.store(false);
  writer.join();
  EXPECT_EQ(torn_words, 0);
  EXPECT_GT(newest_generation, 0u);
}

// A value whose store takes long enough (8192 words) that a signal sent to a thread that does
// nothing but store it lands in the middle of a store.
struct LargeSample {
  std::array<std::uint64_t, 8192> words{};
};

// The writer thread parks in this SIGUSR1 handler until released: a writer stopped mid-store, as
// one preempted by robotd's SCHED_FIFO loop on its CPU is.
std::atomic<bool> writer_parked{false};
std::atomic<bool> writer_released{false};

void park_writer(int /*signal*/) {
  writer_parked.store(true);
  while (!writer_released.load()) {
    const timespec pause{0, 100'000};
    nanosleep(&pause, nullptr);
  }
  writer_parked.store(false);
}

TEST(SeqLock, TryLoadDoesNotWaitForAWriterStoppedMidStoreWhileLoadNonRtDoes) {
  struct sigaction parking {};
  parking.sa_handler = park_writer;
  sigemptyset(&parking.sa_mask);
  struct sigaction previous {};
  ASSERT_EQ(sigaction(SIGUSR1, &parking, &previous), 0);

  auto lock = std::make_unique<SeqLock<LargeSample>>();
  std::atomic<bool> writing{true};
  std::thread writer([&] {
    LargeSample sample;
    sample.words.fill(1);
    while (writing.load(std::memory_order_relaxed)) lock->store(sample);
  });
  auto out = std::make_unique<LargeSample>();
  bool caught_mid_store = false;
  // Nearly every signal lands mid-store; one that lands between two stores parks a writer whose
  // value reads fine, and the next attempt tries again.
  for (int attempt = 0; attempt < 200 && !caught_mid_store; ++attempt) {
    writer_released.store(false);
    ASSERT_EQ(pthread_kill(writer.native_handle(), SIGUSR1), 0);
    while (!writer_parked.load()) std::this_thread::yield();
    out->words.fill(7);
    caught_mid_store = !lock->try_load(*out);
    if (caught_mid_store) {
      int successes = 0;
      for (int i = 0; i < 1000; ++i) successes += lock->try_load(*out) ? 1 : 0;
      EXPECT_EQ(successes, 0) << "the writer is stopped with its store half done";
      EXPECT_EQ(out->words.front(), 7u) << "a failed try_load leaves its output as it was";
      EXPECT_EQ(out->words.back(), 7u);
      // What the RT thread would do with load_non_rt(): wait as long as the writer is stopped.
      std::atomic<bool> loaded{false};
      std::thread reader([&] {
        (void)lock->load_non_rt();
        loaded.store(true);
      });
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      EXPECT_FALSE(loaded.load()) << "load_non_rt() returned while the writer was stopped mid-store";
      writing.store(false);  // the writer finishes this store and stops (a busy one would starve the reader)
      writer_released.store(true);
      reader.join();
      EXPECT_TRUE(loaded.load());
    }
    writer_released.store(true);
    while (writer_parked.load()) std::this_thread::yield();
  }
  writing.store(false);
  writer.join();
  ASSERT_EQ(sigaction(SIGUSR1, &previous, nullptr), 0);
  EXPECT_TRUE(caught_mid_store) << "no signal in 200 landed inside a store";
  EXPECT_TRUE(lock->try_load(*out)) << "the finished store reads";
  EXPECT_EQ(out->words[4096], 1u);
}

}  // namespace
}  // namespace robotd::driver
