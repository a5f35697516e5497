#include "stop_flag.hpp"

#include <chrono>

namespace robotd::c {
namespace {

// How often the C flag is read: well under a human's reaction, a small cost for a move.
constexpr std::chrono::milliseconds kPollPeriod{5};

}  // namespace

StopFlagWatch::StopFlagWatch(const volatile int* flag) : watching_(flag != nullptr) {
  if (!watching_) return;
  stop_ = *flag != 0;
  watcher_ = std::jthread([this, flag](const std::stop_token& done) {
    while (!done.stop_requested() && !stop_.load()) {
      if (*flag != 0) stop_ = true;
      std::this_thread::sleep_for(kPollPeriod);
    }
  });
}

StopFlagWatch::~StopFlagWatch() = default;  // the jthread asks its loop to end and joins it

}  // namespace robotd::c
