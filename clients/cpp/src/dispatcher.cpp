#include "dispatcher.hpp"

#include <array>

namespace robotd::detail {

Dispatcher::Dispatcher(const wire::Participant& participant)
    : waitset_(dds_create_waitset(participant.handle())), wakeup_(dds_create_guardcondition(participant.handle())) {
  dds_waitset_attach(waitset_.get(), wakeup_, 0);
  thread_ = std::thread([this] { run(); });
}

Dispatcher::~Dispatcher() {
  stopping_.store(true);
  dds_set_guardcondition(wakeup_, true);
  thread_.join();
  const std::lock_guard lock(mutex_);
  for (auto& [id, entry] : entries_) dds_waitset_detach(waitset_.get(), entry.condition);
  entries_.clear();
}

std::uint64_t Dispatcher::add(dds_entity_t reader, std::function<void()> drain, std::shared_ptr<void> keep_alive) {
  const std::lock_guard lock(mutex_);
  const std::uint64_t id = next_id_++;
  const dds_entity_t condition = dds_create_readcondition(reader, DDS_ANY_STATE);
  entries_[id] = Entry{condition, std::move(drain), std::move(keep_alive)};
  dds_waitset_attach(waitset_.get(), condition, static_cast<dds_attach_t>(id));
  return id;
}

void Dispatcher::remove(std::uint64_t id) {
  const std::lock_guard lock(mutex_);
  const auto it = entries_.find(id);
  if (it == entries_.end()) return;
  dds_waitset_detach(waitset_.get(), it->second.condition);
  dds_delete(it->second.condition);
  entries_.erase(it);
}

void Dispatcher::run() {
  pthread_setname_np(pthread_self(), "robotd-client");
  constexpr std::size_t kMaxTriggered = 32;
  std::array<dds_attach_t, kMaxTriggered> triggered{};
  while (!stopping_.load()) {
    const dds_return_t count = dds_waitset_wait(waitset_.get(), triggered.data(), triggered.size(), DDS_MSECS(200));
    if (count <= 0) continue;
    const std::lock_guard lock(mutex_);
    for (dds_return_t i = 0; i < count && static_cast<std::size_t>(i) < triggered.size(); ++i) {
      const auto id = static_cast<std::uint64_t>(triggered[static_cast<std::size_t>(i)]);
      if (id == 0) continue;  // the wakeup guard
      const auto it = entries_.find(id);
      if (it != entries_.end()) it->second.drain();
    }
  }
}

}  // namespace robotd::detail
