// The latest-value mailbox: the reader gets the newest complete value, never a half-written
// one, and never the same one twice.
#include "rt/triple_buffer.hpp"

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <thread>

#include <gtest/gtest.h>

namespace robotd::rt {
namespace {

struct Value {
  int number = 0;
};

// Big enough that a torn copy would show: every field holds the same counter.
struct Stamped {
  std::array<std::uint64_t, 64> fields{};
};

void publish(TripleBuffer<Value>& buffer, int number) {
  buffer.write_buffer().number = number;
  buffer.publish();
}

TEST(TripleBuffer, TakeReturnsNothingBeforeTheFirstPublish) {
  TripleBuffer<Value> buffer;
  EXPECT_EQ(buffer.take(), nullptr);
}

TEST(TripleBuffer, TakeReturnsThePublishedValue) {
  TripleBuffer<Value> buffer;
  publish(buffer, 42);
  const Value* value = buffer.take();
  ASSERT_NE(value, nullptr);
  EXPECT_EQ(value->number, 42);
  EXPECT_EQ(buffer.last_taken().number, 42);
}

TEST(TripleBuffer, NewestPublishedValueWins) {
  TripleBuffer<Value> buffer;
  publish(buffer, 1);
  publish(buffer, 2);
  publish(buffer, 3);
  const Value* value = buffer.take();
  ASSERT_NE(value, nullptr);
  EXPECT_EQ(value->number, 3);
}

TEST(TripleBuffer, EachPublishedValueIsTakenAtMostOnce) {
  TripleBuffer<Value> buffer;
  publish(buffer, 1);
  ASSERT_NE(buffer.take(), nullptr);
  EXPECT_EQ(buffer.take(), nullptr);
  EXPECT_EQ(buffer.last_taken().number, 1);
  publish(buffer, 2);
  const Value* second = buffer.take();
  ASSERT_NE(second, nullptr);
  EXPECT_EQ(second->number, 2);
  EXPECT_EQ(buffer.take(), nullptr);
}

TEST(TripleBuffer, WriterKeepsWritingWhileTheReaderHoldsAValue) {
  TripleBuffer<Value> buffer;
  publish(buffer, 1);
  const Value* held = buffer.take();
  ASSERT_NE(held, nullptr);
  for (int i = 2; i <= 10; ++i) publish(buffer, i);
  EXPECT_EQ(held->number, 1);  // the reader's buffer is never written
  const Value* newest = buffer.take();
  ASSERT_NE(newest, nullptr);
  EXPECT_EQ(newest->number, 10);
}

TEST(TripleBuffer, ConcurrentWriterNeverTearsAValueAndTheReaderSeesEachAtMostOnce) {
  constexpr std::uint64_t kTakes = 5'000;
  TripleBuffer<Stamped> buffer;
  std::atomic<bool> stop{false};
  std::uint64_t published = 0;
  // The writer publishes until the reader has seen enough distinct values.
  std::thread writer([&] {
    std::uint64_t counter = 0;
    while (!stop.load(std::memory_order_acquire)) {
      ++counter;
      buffer.write_buffer().fields.fill(counter);
      buffer.publish();
      std::this_thread::yield();  // on a busy machine the reader may share this CPU
    }
    published = counter;
  });

  std::uint64_t last = 0;
  std::uint64_t taken = 0;
  bool whole = true;
  bool increasing = true;
  const auto check = [&](const Stamped& value) {
    const std::uint64_t counter = value.fields[0];
    for (const auto field : value.fields) whole = whole && field == counter;
    increasing = increasing && counter > last;
    last = counter;
    ++taken;
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (taken < kTakes && std::chrono::steady_clock::now() < deadline) {
    if (const Stamped* value = buffer.take()) {
      check(*value);
    } else {
      std::this_thread::yield();
    }
  }
  stop.store(true, std::memory_order_release);
  writer.join();
  if (const Stamped* value = buffer.take()) check(*value);

  EXPECT_TRUE(whole);
  EXPECT_TRUE(increasing);
  EXPECT_GE(taken, kTakes);    // distinct values, all taken while the writer was writing
  EXPECT_EQ(last, published);  // the final value is always delivered
}

}  // namespace
}  // namespace robotd::rt
