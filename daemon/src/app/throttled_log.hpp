// Warnings that can repeat at 1 kHz (a client streaming bad commands) are logged at most once
// per interval per key, with a count of what was suppressed. A caller on a hot path passes the
// message as a function, built only when it is logged, and a key it keeps: a suppressed
// message then allocates nothing.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#include <spdlog/spdlog.h>

namespace robotd::app {

class ThrottledLog {
 public:
  explicit ThrottledLog(std::chrono::milliseconds interval = std::chrono::seconds(1)) : interval_(interval) {}

  /// `message` (text, or a callable that makes it) at warning level; see log().
  template <class Message>
  void warn(std::string_view key, Message&& message) {
    log(spdlog::level::warn, key, std::forward<Message>(message));
  }

  /// `message` at `level`, unless `key` was logged less than an interval ago. Keys must come
  /// from a bounded set (a reason, a service, a place in the code), never from the network.
  /// `message` is the text, or a callable that makes it: called only when it is logged, so a
  /// flood of suppressed messages costs no text at all.
  template <class Message>
  void log(spdlog::level::level_enum level, std::string_view key, Message&& message) {
    const auto now = std::chrono::steady_clock::now();
    std::uint64_t suppressed = 0;
    {
      const std::lock_guard lock(mutex_);
      auto entry = entries_.find(key);
      if (entry == entries_.end()) entry = entries_.emplace(std::string(key), Entry{}).first;
      if (entry->second.last_logged.time_since_epoch().count() != 0 && now - entry->second.last_logged < interval_) {
        ++entry->second.suppressed;
        return;
      }
      suppressed = entry->second.suppressed;
      entry->second.suppressed = 0;
      entry->second.last_logged = now;
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
  std::map<std::string, Entry, std::less<>> entries_;
};

}  // namespace robotd::app
