// The client's dispatch thread: waits on every subscription's reader and runs its callback.
// Adding and removing subscriptions is safe from any thread but the dispatch thread itself.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <thread>

#include "wire/entity.hpp"
#include "wire/participant.hpp"

namespace robotd::detail {

class Dispatcher {
 public:
  explicit Dispatcher(const wire::Participant& participant);
  Dispatcher(const Dispatcher&) = delete;
  Dispatcher& operator=(const Dispatcher&) = delete;
  ~Dispatcher();

  /// Calls `drain` whenever `reader` has data. `keep_alive` owns the reader.
  std::uint64_t add(dds_entity_t reader, std::function<void()> drain, std::shared_ptr<void> keep_alive);
  /// Stops calling it; returns after a running callback has finished.
  void remove(std::uint64_t id);

 private:
  struct Entry {
    dds_entity_t condition = 0;
    std::function<void()> drain;
    std::shared_ptr<void> keep_alive;
  };
  void run();

  wire::Entity waitset_;
  dds_entity_t wakeup_ = 0;
  std::mutex mutex_;
  std::map<std::uint64_t, Entry> entries_;
  std::uint64_t next_id_ = 1;
  std::atomic<bool> stopping_{false};
  std::thread thread_;
};

}  // namespace robotd::detail
