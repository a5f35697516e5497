// Warnings that can repeat at 1 kHz (a client streaming bad commands) are logged at most once
// per interval per key, with a count of what was suppressed. The text of a suppressed message
// need not even be made.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <type_traits>
#include <utility>

#include <spdlog/spdlog.h>

namespace robotd::app {

class ThrottledLog {
 public:
  explicit ThrottledLog(std::chrono::milliseconds interval = std::chrono::seconds(1)) : interval_(interval) {}

  /// `message` (text, or a callable that makes it) at warning level; see log().
  template <class Message>
  void warn(const std::string& key, Message&& message) {
    log(spdlog::level::warn, key, std::forward<Message>(message));
  }

  /// `message` at `level`, unless `key` was logged less than an interval ago. Keys must come
  /// from a bounded set (a reason, a service, a place in the code), never from the network.
  /// `message` is the text, or a callable that makes it: called only when it is logged, so a
  /// flood of suppressed messages costs no text at all.
  template <class Message>
  void log(spdlog::level::level_enum level, const std::string& key, Message&& message) {
    const auto now = std::chrono::steady_clock::now();
    std::uint64_t suppressed = 0;
    {
      const std::lock_guard lock(mutex_);
      Entry& entry = entries_[key];
      if (entry.last_logged.time_since_epoch().count() != 0 && now - entry.last_logged < interval_) {
        ++entry.suppressed;
        return;
      }
      suppressed = entry.suppressed;
      entry.suppressed = 0;
      entry.last_logged = now;
    }
    const std::string text = make_text(std::forward<Message>(message));
    if (suppressed > 0) {
      spdlog::log(level, "{} ({} similar messages suppressed)", text, suppressed);
    } else {
      spdlog::log(level, "{}", text);
    }
  }

 private:
  template <class Message>
  static std::string make_text(Message&& message) {
    if constexpr (std::is_invocable_v<Message>) {
      return message();
    } else {
      return std::string(std::forward<Message>(message));
    }
  }

  struct Entry {
    std::chrono::steady_clock::time_point last_logged{};
    std::uint64_t suppressed = 0;
  };
  std::chrono::milliseconds interval_;
  std::mutex mutex_;
  std::map<std::string, Entry> entries_;
};

}  // namespace robotd::app
