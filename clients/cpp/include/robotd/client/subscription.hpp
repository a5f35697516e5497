// A live subscription: callbacks run on the client's dispatch thread until the Subscription
// is destroyed (or reset). Do not destroy a Subscription from inside its own callback.
#pragma once

#include <functional>
#include <memory>

namespace robotd {

class Subscription {
 public:
  Subscription() = default;
  explicit Subscription(std::function<void()> cancel) : cancel_(std::move(cancel)) {}
  Subscription(Subscription&& other) noexcept : cancel_(std::move(other.cancel_)) { other.cancel_ = nullptr; }
  Subscription& operator=(Subscription&& other) noexcept {
    if (this != &other) {
      reset();
      cancel_ = std::move(other.cancel_);
      other.cancel_ = nullptr;
    }
    return *this;
  }
  Subscription(const Subscription&) = delete;
  Subscription& operator=(const Subscription&) = delete;
  ~Subscription() { reset(); }

  /// Stops the callbacks; returns after any running callback has finished.
  void reset() {
    if (cancel_) cancel_();
    cancel_ = nullptr;
  }
  bool active() const { return static_cast<bool>(cancel_); }

 private:
  std::function<void()> cancel_;
};

}  // namespace robotd
