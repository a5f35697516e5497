#include "dds/session_status_publisher.hpp"

#include "rt/monotonic_clock.hpp"
#include "wire/qos.hpp"
#include "wire/topics.hpp"

namespace robotd::dds {

Result<std::unique_ptr<SessionStatusPublisher>> SessionStatusPublisher::create(const wire::Participant& participant,
                                                                               std::chrono::milliseconds period) {
  auto qos = wire::transient_local_qos(1);
  auto writer = wire::TopicWriter<SessionStatus>::create(participant, wire::kSessionStatusTopic, qos.get());
  if (!writer) return writer.error();
  return std::unique_ptr<SessionStatusPublisher>(new SessionStatusPublisher(std::move(writer.value()), period));
}

SessionStatusPublisher::SessionStatusPublisher(wire::TopicWriter<SessionStatus> writer,
                                               std::chrono::milliseconds period)
    : writer_(std::move(writer)), period_(period) {}

SessionStatusPublisher::~SessionStatusPublisher() { stop(); }

void SessionStatusPublisher::start(const service::SessionService& sessions, const SurfaceCounterSet& surface) {
  sessions_ = &sessions;
  surface_ = &surface;
  thread_ = driver::NamedThread("session-status", [this] { run(); });
}

void SessionStatusPublisher::changed() {
  {
    const std::lock_guard lock(mutex_);
    changed_ = true;
  }
  wake_.notify_one();
}

void SessionStatusPublisher::stop() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  if (thread_.joinable()) thread_.join();
  if (sessions_ != nullptr) {  // the final word: usually "idle" after the devices stopped
    (void)writer_.write(current());
    writer_.wait_for_acks(DDS_MSECS(500));
    sessions_ = nullptr;
  }
}

SessionStatus SessionStatusPublisher::current() const {
  SessionStatus status = sessions_->status(rt::monotonic_now_ns());
  status.surface = surface_->snapshot();
  return status;
}

void SessionStatusPublisher::run() {
  std::unique_lock lock(mutex_);
  while (!stopping_) {
    lock.unlock();
    (void)writer_.write(current());
    lock.lock();
    wake_.wait_for(lock, period_, [this] { return changed_ || stopping_; });
    changed_ = false;
  }
}

}  // namespace robotd::dds
