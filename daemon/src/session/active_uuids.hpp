// The uuids of the active sessions, for a reader that must not wait on the session service's
// lock: the command intake asks on Cyclone's receive thread, for every command that arrives
// (docs/reliability.md, "Command flood"). Written only when a session starts or ends, read
// for every command, so readers share the lock.
#pragma once

#include <algorithm>
#include <mutex>
#include <shared_mutex>
#include <string>
#include <string_view>
#include <vector>

namespace robotd::session {

class ActiveUuids {
 public:
  bool contains(std::string_view uuid) const {
    const std::shared_lock lock(mutex_);
    return std::find(uuids_.begin(), uuids_.end(), uuid) != uuids_.end();
  }

  void add(std::string uuid) {
    const std::unique_lock lock(mutex_);
    uuids_.push_back(std::move(uuid));
  }

  void remove(std::string_view uuid) {
    const std::unique_lock lock(mutex_);
    std::erase(uuids_, uuid);
  }

 private:
  mutable std::shared_mutex mutex_;
  std::vector<std::string> uuids_;
};

}  // namespace robotd::session
