// An op's planned move (move_pose, move_cart, jog), handed from the op thread to the RT thread
// one sample per exchange. No lock the RT thread could wait on: the op cancels the running move,
// waits until the RT thread has let go of the samples, refills them and publishes a new
// generation; the RT thread only reads a generation it has acknowledged.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <thread>
#include <vector>

#include "driver/frame_planner.hpp"

namespace robotd::parol6 {

class TrajectoryBuffer {
 public:
  /// Non-RT, before use: room for `capacity` samples (no allocation afterwards).
  void reserve(std::size_t capacity) { samples_.reserve(capacity); }
  std::size_t capacity() const { return samples_.capacity(); }

  // --- op thread -------------------------------------------------------------------------------

  /// Stops the running move; false if the RT thread did not let go within `timeout` (the loop
  /// is not running).
  bool cancel(std::chrono::milliseconds timeout) {
    published_.store(0, std::memory_order_release);
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (acknowledged_.load(std::memory_order_acquire) != 0) {
      if (std::chrono::steady_clock::now() > deadline) return false;
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    return true;
  }

  /// After cancel(): the new move's samples, then publish(). `samples.size()` ≤ capacity().
  void load(const std::vector<StepTarget>& samples) {
    samples_.assign(samples.begin(), samples.end());
    next_.store(0, std::memory_order_relaxed);
  }
  void publish() { published_.store(++generation_, std::memory_order_release); }

  bool running() const { return published_.load(std::memory_order_acquire) != 0; }
  std::size_t progress() const { return next_.load(std::memory_order_relaxed); }
  std::size_t size() const { return samples_.size(); }

  // --- RT thread -------------------------------------------------------------------------------

  /// The next sample of the published move, or nullptr (none, finished, or cancelled). A
  /// finished move repeats its last sample for `settle` more calls, so the board's tracker
  /// reaches the end point, then ends.
  const StepTarget* next(std::size_t settle) noexcept {
    const std::uint64_t generation = published_.load(std::memory_order_acquire);
    acknowledged_.store(generation, std::memory_order_release);
    if (generation == 0 || samples_.empty()) return nullptr;
    const std::size_t index = next_.load(std::memory_order_relaxed);
    if (index >= samples_.size() + settle) {
      std::uint64_t expected = generation;
      published_.compare_exchange_strong(expected, 0, std::memory_order_acq_rel);
      return nullptr;
    }
    next_.store(index + 1, std::memory_order_relaxed);
    return &samples_[std::min(index, samples_.size() - 1)];
  }

  /// The RT thread ends the move (a session took joints, an e-stop).
  void abort() noexcept {
    const std::uint64_t generation = published_.load(std::memory_order_acquire);
    std::uint64_t expected = generation;
    if (generation != 0) published_.compare_exchange_strong(expected, 0, std::memory_order_acq_rel);
    acknowledged_.store(0, std::memory_order_release);
  }

 private:
  std::vector<StepTarget> samples_;
  std::atomic<std::uint64_t> published_{0};     // generation of the move to run, 0 = none
  std::atomic<std::uint64_t> acknowledged_{0};  // what the RT thread last saw
  std::atomic<std::size_t> next_{0};
  std::uint64_t generation_ = 0;  // op thread only
};

}  // namespace robotd::parol6
