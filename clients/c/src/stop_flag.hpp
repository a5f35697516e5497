// A C stop flag (a volatile int a signal handler or another thread sets) as the std::atomic<bool>
// the C++ planned moves and RBTscript runs watch: a thread of its own reads the C flag every few
// milliseconds while the call runs, since those calls cannot call back on every tick.
#pragma once

#include <atomic>
#include <thread>

namespace robotd::c {

class StopFlagWatch {
 public:
  /// `flag` may be NULL: then nothing is watched and flag() is NULL too.
  explicit StopFlagWatch(const volatile int* flag);
  StopFlagWatch(const StopFlagWatch&) = delete;
  StopFlagWatch& operator=(const StopFlagWatch&) = delete;
  ~StopFlagWatch();

  const std::atomic<bool>* flag() const { return watching_ ? &stop_ : nullptr; }

 private:
  bool watching_;
  std::atomic<bool> stop_{false};
  std::jthread watcher_;  // last: it reads the members above
};

}  // namespace robotd::c
