// A sequence lock: one writer at a time publishes a trivially copyable value, any number of
// readers copy it without blocking the writer. The value is stored as relaxed atomic words
// (Boehm, "Can seqlocks get along with programming language memory models?"), so a read that
// races a write is well defined and simply retried.
//
// A reader that may preempt the writer must never wait for it: if robotd's SCHED_FIFO loop
// interrupts a link thread mid-store on the same CPU, the store cannot finish until the loop
// yields the CPU, so a reader that waits for it waits forever. A driver's read() and write(),
// and a SCHED_FIFO link thread reading what the RT thread stores, use try_load() and make do
// with their previous copy when it fails; only threads that never preempt the writer may use
// load_non_rt().
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <thread>
#include <type_traits>

namespace robotd::driver {

template <class T>
class SeqLock {
  static_assert(std::is_trivially_copyable_v<T>);
  static_assert(std::is_default_constructible_v<T>);

 public:
  SeqLock() { store(T{}); }

  /// Writers must not overlap: callers serialise them (one thread, or a writers-only mutex).
  void store(const T& value) noexcept {
    const std::uint64_t sequence = sequence_.load(std::memory_order_relaxed);
    sequence_.store(sequence + 1, std::memory_order_relaxed);
    std::atomic_thread_fence(std::memory_order_release);
    const auto* bytes = reinterpret_cast<const unsigned char*>(&value);
    for (std::size_t i = 0; i < kWords; ++i) {
      std::uint64_t word = 0;
      std::memcpy(&word, bytes + i * kWordSize, bytes_in_word(i));
      words_[i].store(word, std::memory_order_relaxed);
    }
    sequence_.store(sequence + 2, std::memory_order_release);
  }

  /// One attempt, never waits: false when a write was in progress (`out` is then unchanged).
  /// The only read for the RT thread, and for any thread that may preempt the writer.
  bool try_load(T& out) const noexcept {
    const std::uint64_t before = sequence_.load(std::memory_order_acquire);
    if (before % 2 != 0) return false;
    std::array<std::uint64_t, kWords> copy;
    for (std::size_t i = 0; i < kWords; ++i) copy[i] = words_[i].load(std::memory_order_relaxed);
    std::atomic_thread_fence(std::memory_order_acquire);
    if (sequence_.load(std::memory_order_relaxed) != before) return false;
    auto* bytes = reinterpret_cast<unsigned char*>(&out);
    for (std::size_t i = 0; i < kWords; ++i) std::memcpy(bytes + i * kWordSize, &copy[i], bytes_in_word(i));
    return true;
  }

  /// Retries until a consistent copy is read: waits for a writer that is mid-store. Never on the
  /// RT thread (a driver's read()/write()), nor on any thread that may preempt the writer.
  T load_non_rt() const noexcept {
    T out{};
    while (!try_load(out)) std::this_thread::yield();
    return out;
  }

 private:
  static constexpr std::size_t kWordSize = sizeof(std::uint64_t);
  static constexpr std::size_t kWords = (sizeof(T) + kWordSize - 1) / kWordSize;
  static constexpr std::size_t bytes_in_word(std::size_t index) noexcept {
    return index + 1 < kWords ? kWordSize : sizeof(T) - index * kWordSize;
  }

  std::atomic<std::uint64_t> sequence_{0};
  std::array<std::atomic<std::uint64_t>, kWords> words_{};
};

}  // namespace robotd::driver
