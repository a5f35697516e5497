// /session_status: who holds which motors of which device, until when, and what the DDS
// surface counted. Transient-local so a client that joins late sees the current sessions at
// once; published on every change and every session_status_period_ms (time_left moves).
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>

#include "dds/surface_counters.hpp"
#include "robotd/driver/named_thread.hpp"
#include "service/session_service.hpp"
#include "wire/topic_io.hpp"

namespace robotd::dds {

class SessionStatusPublisher {
 public:
  static Result<std::unique_ptr<SessionStatusPublisher>> create(const wire::Participant& participant,
                                                                std::chrono::milliseconds period);
  SessionStatusPublisher(const SessionStatusPublisher&) = delete;
  SessionStatusPublisher& operator=(const SessionStatusPublisher&) = delete;
  ~SessionStatusPublisher();

  /// Starts periodic publishing of `sessions`' status, with `surface`'s counters.
  void start(const service::SessionService& sessions, const SurfaceCounterSet& surface);
  /// Publishes at once (from any thread; the periodic thread does the writing).
  void changed();
  void stop();

 private:
  SessionStatusPublisher(wire::TopicWriter<SessionStatus> writer, std::chrono::milliseconds period);
  void run();
  SessionStatus current() const;

  wire::TopicWriter<SessionStatus> writer_;
  std::chrono::milliseconds period_;
  const service::SessionService* sessions_ = nullptr;
  const SurfaceCounterSet* surface_ = nullptr;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool changed_ = false;
  bool stopping_ = false;
  driver::NamedThread thread_;
};

}  // namespace robotd::dds
