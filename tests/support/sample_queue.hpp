// Samples a subscription delivered, for a test to wait on in the order they came.
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

namespace robotd::testing {

/// Every sample offered; wait_for() hands out the next one, in order, that satisfies a predicate.
template <class T>
class SampleQueue {
 public:
  void offer(const T& value) {
    const std::lock_guard lock(mutex_);
    values_.push_back(value);
  }
  std::optional<T> wait_for(const std::function<bool(const T&)>& predicate, std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
      {
        const std::lock_guard lock(mutex_);
        for (; checked_ < values_.size(); ++checked_) {
          if (predicate(values_[checked_])) return values_[checked_++];
        }
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return std::nullopt;
  }

 private:
  std::mutex mutex_;
  std::vector<T> values_;
  std::size_t checked_ = 0;
};

}  // namespace robotd::testing
