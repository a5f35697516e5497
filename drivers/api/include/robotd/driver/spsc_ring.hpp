// Bounded single-producer / single-consumer ring, shared by robotd (its event rings) and drivers
// (replies handed from the RT thread to ops). Lock-free and allocation-free after
// construction: the RT thread may be either end. push() fails (returns false) when full rather
// than overwrite, so a slow consumer costs the newest items, never corrupts old ones.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <new>
#include <optional>
#include <type_traits>

namespace robotd::driver {

template <class T, std::size_t Capacity>
class SpscRing {
  static_assert(Capacity >= 2 && (Capacity & (Capacity - 1)) == 0, "capacity must be a power of two");
  static_assert(std::is_trivially_copyable_v<T>, "ring items are copied byte-wise across threads");

 public:
  bool push(const T& item) noexcept {
    const std::size_t head = head_.load(std::memory_order_relaxed);
    if (head - tail_.load(std::memory_order_acquire) == Capacity) return false;
    slots_[head & (Capacity - 1)] = item;
    head_.store(head + 1, std::memory_order_release);
    return true;
  }

  std::optional<T> pop() noexcept {
    const std::size_t tail = tail_.load(std::memory_order_relaxed);
    if (tail == head_.load(std::memory_order_acquire)) return std::nullopt;
    T item = slots_[tail & (Capacity - 1)];
    tail_.store(tail + 1, std::memory_order_release);
    return item;
  }

  /// Consumer side: drops everything waiting.
  void clear() noexcept {
    while (pop()) {
    }
  }

  bool empty() const noexcept { return tail_.load(std::memory_order_acquire) == head_.load(std::memory_order_acquire); }

 private:
  static constexpr std::size_t kCacheLine = 64;
  alignas(kCacheLine) std::atomic<std::size_t> head_{0};
  alignas(kCacheLine) std::atomic<std::size_t> tail_{0};
  alignas(kCacheLine) std::array<T, Capacity> slots_{};
};

}  // namespace robotd::driver
