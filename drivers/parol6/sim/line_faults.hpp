// Faults on the serial line, as the control channel asks for them: received bytes dropped (a
// lost byte) or garbled (bits flipped), and random bytes sent to the host between replies.
#pragma once

#include <cstddef>
#include <cstdint>
#include <random>
#include <span>

namespace robotd::parol6::sim {

class LineFaults {
 public:
  static constexpr std::uint8_t kGarbleMask = 0x5A;  // the bits flipped in a garbled byte

  void drop_next(std::int64_t count) { drop_pending_ += count; }
  void garble_next(std::int64_t count) { garble_pending_ += count; }
  void queue_garbage(std::int64_t count) { garbage_pending_ += count; }

  /// Applies the pending drops (first) and garbling to bytes just received; the bytes that
  /// remain are moved to the front and their number returned.
  std::size_t filter(std::span<std::uint8_t> bytes);
  /// Fills `out` with up to its size of the pending garbage; how many bytes.
  std::size_t take_garbage(std::span<std::uint8_t> out);
  /// `count` bytes taken by take_garbage were not sent after all.
  void return_garbage(std::size_t count) {
    garbage_pending_ += static_cast<std::int64_t>(count);
    garbage_sent_ -= count;
  }

  std::int64_t drop_pending() const { return drop_pending_; }
  std::int64_t garble_pending() const { return garble_pending_; }
  std::int64_t garbage_pending() const { return garbage_pending_; }
  std::uint64_t dropped() const { return dropped_; }
  std::uint64_t garbled() const { return garbled_; }
  std::uint64_t garbage_sent() const { return garbage_sent_; }
  void reset_counters() { dropped_ = garbled_ = garbage_sent_ = 0; }

 private:
  std::int64_t drop_pending_ = 0;
  std::int64_t garble_pending_ = 0;
  std::int64_t garbage_pending_ = 0;
  std::uint64_t dropped_ = 0;
  std::uint64_t garbled_ = 0;
  std::uint64_t garbage_sent_ = 0;
  std::mt19937 random_{0x9A7016};
};

}  // namespace robotd::parol6::sim
