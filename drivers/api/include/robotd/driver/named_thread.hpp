// A thread with a name and a stack of a chosen size: robotd's and its drivers' long-lived
// threads. std::thread cannot set a stack size, so each of its threads reserves the process
// default (RLIMIT_STACK, 8 MiB on common distributions) — address space that robotd's mlockall
// counts as locked, and made resident before it let pages be locked as they are touched.
#pragma once

#include <cstddef>
#include <functional>
#include <pthread.h>
#include <string>

namespace robotd::driver {

// How the size was chosen: the deepest stack a robotd thread used, measured as the resident part
// of each thread's stack mapping (with mlockall's MCL_ONFAULT a page is resident once touched)
// while robotd ran the 7-device demo and served moves, status and loop-timing calls, was 28 KiB
// (a driver's link thread; the others 8–24 KiB). 256 KiB is nine times that: room for a sanitizer
// build's larger frames (2–3×) and for paths the measurement did not take. Untouched stack pages
// are neither resident nor locked, so the margin costs address space only.
inline constexpr std::size_t kThreadStackBytes = std::size_t{256} * 1024;

class NamedThread {
 public:
  NamedThread() = default;
  /// Starts `body` on a new thread named `name` (top and ps show the first 15 characters) with a
  /// stack of `stack_bytes` (rounded up to whole pages). Throws std::system_error when the thread
  /// cannot be created, as std::thread does.
  NamedThread(const std::string& name, std::function<void()> body, std::size_t stack_bytes = kThreadStackBytes);
  NamedThread(NamedThread&& other) noexcept;
  /// Like std::thread's: terminates the program if this thread is still joinable.
  NamedThread& operator=(NamedThread&& other) noexcept;
  NamedThread(const NamedThread&) = delete;
  NamedThread& operator=(const NamedThread&) = delete;
  /// Like std::thread's: terminates the program if the thread was neither joined nor moved.
  ~NamedThread();

  bool joinable() const { return joinable_; }
  void join();

 private:
  pthread_t handle_{};
  bool joinable_ = false;
};

}  // namespace robotd::driver
