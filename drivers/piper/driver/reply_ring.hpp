// Frames the arm sends in answer to a query or setting (0x473, 0x476, 0x478, 0x47B, 0x47C,
// 0x47E, 0x4AF), handed from the RT thread that reads the bus to the op waiting for them.
// Single producer (RT thread), single consumer (ops, serialised by the driver); lock-free,
// fixed size: when full the newest frames are dropped, and the op times out and says so.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>

#include "robotd/transport/can_message.hpp"

namespace robotd::piper {

class ReplyRing {
 public:
  static constexpr std::size_t kCapacity = 256;

  bool push(const transport::CanMessage& message) noexcept {
    const std::size_t head = head_.load(std::memory_order_relaxed);
    if (head - tail_.load(std::memory_order_acquire) >= kCapacity) return false;
    slots_[head % kCapacity] = message;
    head_.store(head + 1, std::memory_order_release);
    return true;
  }

  bool pop(transport::CanMessage& out) noexcept {
    const std::size_t tail = tail_.load(std::memory_order_relaxed);
    if (tail == head_.load(std::memory_order_acquire)) return false;
    out = slots_[tail % kCapacity];
    tail_.store(tail + 1, std::memory_order_release);
    return true;
  }

  void clear() noexcept {
    transport::CanMessage discard;
    while (pop(discard)) {
    }
  }

 private:
  std::array<transport::CanMessage, kCapacity> slots_{};
  alignas(64) std::atomic<std::size_t> head_{0};
  alignas(64) std::atomic<std::size_t> tail_{0};
};

}  // namespace robotd::piper
