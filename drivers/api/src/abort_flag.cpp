#include "robotd/driver/abort_flag.hpp"

#include <algorithm>
#include <string>
#include <thread>

namespace robotd::driver {

bool AbortFlag::sleep_for(std::chrono::nanoseconds duration) const {
  constexpr std::chrono::nanoseconds kLookEvery = std::chrono::milliseconds(1);
  const auto until = std::chrono::steady_clock::now() + duration;
  while (!requested()) {
    const auto left = until - std::chrono::steady_clock::now();
    if (left <= std::chrono::nanoseconds::zero()) return true;
    std::this_thread::sleep_for(std::min<std::chrono::nanoseconds>(left, kLookEvery));
  }
  return false;
}

namespace {

constexpr std::string_view kAborted = "aborted: an e-stop or shutdown pre-empted ";

}  // namespace

Result<void> AbortFlag::verdict(Result<void> result, std::string_view what) const {
  if (result || !requested()) return result;
  // The step that was pre-empted, or what failed as the abort came.
  std::string_view step = result.error().message;
  if (step.starts_with(kAborted)) step.remove_prefix(kAborted.size());
  return make_error(ErrorCode::kRefused, std::string(kAborted) + std::string(what) + " (" + std::string(step) + ")");
}

Error aborted_error(std::string_view what) {
  return make_error(ErrorCode::kRefused, std::string(kAborted) + std::string(what));
}

}  // namespace robotd::driver
