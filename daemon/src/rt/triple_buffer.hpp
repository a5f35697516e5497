// Latest-value mailbox between one writer and one reader (a "triple buffer"). The writer
// never waits for the reader and the reader always gets the newest complete value; values
// published in between are skipped. Lock-free, allocation-free, for large trivially copyable
// values (a whole tick's state or a device's command snapshot).
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <type_traits>

namespace robotd::rt {

template <class T>
class TripleBuffer {
  static_assert(std::is_trivially_copyable_v<T>);

 public:
  /// The writer's private buffer: fill it, then publish().
  T& write_buffer() noexcept { return buffers_[write_index_]; }

  void publish() noexcept {
    // Swap our buffer into the middle, marking it fresh, and take the old middle one.
    const std::uint8_t previous =
        middle_.exchange(static_cast<std::uint8_t>(write_index_ | kFresh), std::memory_order_acq_rel);
    write_index_ = previous & kIndexMask;
  }

  /// Takes the newest published value if there is one the reader has not seen; returns
  /// nullptr otherwise. The pointer stays valid until the next call to take().
  const T* take() noexcept {
    if ((middle_.load(std::memory_order_relaxed) & kFresh) == 0) return nullptr;
    const std::uint8_t previous = middle_.exchange(read_index_, std::memory_order_acq_rel);
    read_index_ = previous & kIndexMask;
    return &buffers_[read_index_];
  }

  /// The value take() last returned (valid once take() returned non-null at least once).
  const T& last_taken() const noexcept { return buffers_[read_index_]; }

 private:
  static constexpr std::uint8_t kFresh = 0x4;
  static constexpr std::uint8_t kIndexMask = 0x3;

  std::array<T, 3> buffers_{};
  std::uint8_t write_index_ = 0;
  std::uint8_t read_index_ = 1;
  std::atomic<std::uint8_t> middle_{2};
};

}  // namespace robotd::rt
