// One request at a time from an op's thread to the RT thread, decided by the RT thread at the
// tick it acts on it, with the outcome handed back: the decision sees that tick's CommandFrame,
// so nothing that changes between an op's look and the RT thread's action can slip through.
// Lock-free and allocation-free; a request the RT thread has not taken yet can be withdrawn, so
// an op that gave up waiting never acts later.
//
//   op thread:  if (!handoff.offer(request)) …;  std::optional<Outcome> outcome = handoff.await(timeout);
//   RT thread:  if (const Request* request = handoff.take()) handoff.answer(decide(*request));
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <optional>
#include <thread>
#include <type_traits>

namespace robotd::driver {

template <class Request, class Outcome>
class RtHandoff {
  static_assert(std::is_trivially_copyable_v<Request> && std::is_trivially_copyable_v<Outcome>);

 public:
  // --- the op's thread (one at a time) ---------------------------------------------------------

  /// False when a request is still pending (offer only after the last await returned).
  bool offer(const Request& request) noexcept {
    if (state_.load(std::memory_order_acquire) != State::kEmpty) return false;
    request_ = request;
    state_.store(State::kPending, std::memory_order_release);
    return true;
  }

  /// The RT thread's outcome, or nullopt when it did not take the request within `timeout`: the
  /// request is then withdrawn and never acted on. Once taken, the answer comes in the same tick.
  std::optional<Outcome> await(std::chrono::nanoseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    for (;;) {
      State state = state_.load(std::memory_order_acquire);
      if (state == State::kAnswered) {
        const Outcome outcome = outcome_;
        state_.store(State::kEmpty, std::memory_order_release);
        return outcome;
      }
      if (state == State::kPending && std::chrono::steady_clock::now() >= deadline &&
          state_.compare_exchange_strong(state, State::kEmpty, std::memory_order_acq_rel)) {
        return std::nullopt;
      }
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  }

  // --- the RT thread ---------------------------------------------------------------------------

  /// The pending request, now the RT thread's to decide (answer() in the same tick), or nullptr.
  const Request* take() noexcept {
    State pending = State::kPending;
    if (state_.load(std::memory_order_relaxed) != pending) return nullptr;
    if (!state_.compare_exchange_strong(pending, State::kTaken, std::memory_order_acq_rel)) return nullptr;
    return &request_;
  }

  void answer(const Outcome& outcome) noexcept {
    outcome_ = outcome;
    state_.store(State::kAnswered, std::memory_order_release);
  }

 private:
  enum class State : std::uint8_t { kEmpty, kPending, kTaken, kAnswered };
  std::atomic<State> state_{State::kEmpty};
  Request request_{};
  Outcome outcome_{};
};

}  // namespace robotd::driver
