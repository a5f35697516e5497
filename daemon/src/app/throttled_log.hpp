// Warnings that can repeat at 1 kHz (a client streaming bad commands) are logged at most once
// per interval per key, with a count of what was suppressed. A caller on a hot path passes the
// message as a function, built only when it is logged, and a key it keeps: a suppressed warning
// then allocates nothing.
#pragma once

#include <chrono>
#include <concepts>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <string_view>

#include <spdlog/spdlog.h>

namespace robotd::app {

class ThrottledLog {
 public:
  explicit ThrottledLog(std::chrono::milliseconds interval = std::chrono::seconds(1)) : interval_(interval) {}

  void warn(std::string_view key, const std::string& message) {
    warn(key, [&message] { return message; });
  }

  template <std::invocable MakeMessage>
  void warn(std::string_view key, MakeMessage&& make_message) {
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
    if (suppressed > 0) {
      spdlog::warn("{} ({} similar messages suppressed)", make_message(), suppressed);
    } else {
      spdlog::warn("{}", make_message());
    }
  }

 private:
  struct Entry {
    std::chrono::steady_clock::time_point last_logged{};
    std::uint64_t suppressed = 0;
  };
  std::chrono::milliseconds interval_;
  std::mutex mutex_;
  std::map<std::string, Entry, std::less<>> entries_;
};

}  // namespace robotd::app
