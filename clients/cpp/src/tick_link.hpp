// A session's own readers of what robotd publishes about its device and itself, read on the
// session's thread through one DDS waitset (no hop through the client's dispatch thread: that
// would add a thread wake-up per tick): /<device>/tick_state for next_tick, /session_status for
// whether robotd still lists the session (and its SessionInfo), and /device_status for the loop's
// tick phase when there are no tick states to take it from.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "client_core.hpp"
#include "robotd/messages.hpp"
#include "robotd/result.hpp"
#include "tick_phase.hpp"
#include "wire/entity.hpp"
#include "wire/topic_io.hpp"

namespace robotd::detail {

class TickLink {
 public:
  /// Reads /session_status for `session_id` from now on; `device` is the session's device.
  static Result<std::unique_ptr<TickLink>> create(std::shared_ptr<ClientCore> core, std::string device,
                                                  std::string session_id);
  TickLink(const TickLink&) = delete;
  TickLink& operator=(const TickLink&) = delete;
  ~TickLink();

  /// Creates the tick state reader unless it exists, then waits until it has matched robotd's
  /// writer, at most `match_timeout`.
  Result<void> open_ticks(std::chrono::milliseconds match_timeout);
  bool reads_ticks() const { return ticks_ != nullptr; }
  /// The newest tick state newer than the last one returned (see Session::next_tick).
  Result<TickState> next_tick(std::chrono::milliseconds timeout);
  /// The session's newest SessionInfo (see Session::info).
  Result<SessionInfo> info(std::chrono::milliseconds timeout);
  /// The device loop's tick phase: from the newest tick state when this reads them, else from
  /// /device_status (waiting up to `timeout` for the device's first status).
  Result<TickPhase> phase(std::chrono::milliseconds timeout);

 private:
  TickLink(std::shared_ptr<ClientCore> core, std::string device, std::string session_id,
           wire::TopicReader<SessionStatus> statuses);
  /// Takes what every reader holds, so that no condition stays triggered.
  void drain();
  /// Waits for any reader's data until `deadline`; false once it has passed.
  bool wait_until(std::chrono::steady_clock::time_point deadline);
  Error ended_error() const;
  void attach(dds_entity_t reader);

  std::shared_ptr<ClientCore> core_;  // first: the readers go before the participant
  std::string device_;
  std::string session_id_;
  wire::TopicReader<SessionStatus> statuses_;
  std::unique_ptr<wire::TopicReader<TickState>> ticks_;
  std::unique_ptr<wire::TopicReader<DeviceStatus>> device_statuses_;
  wire::Entity waitset_;

  std::optional<TickState> newest_tick_;
  std::uint64_t last_returned_tick_ = 0;
  std::optional<SessionInfo> info_;
  // Whether robotd still lists the session. The first status this reader takes may be the one
  // robotd kept (transient local) from before the grant; every later one was written after the
  // reader matched, so after the grant: a status without the session ends it then.
  std::uint64_t statuses_taken_ = 0;
  bool listed_ = false;  // robotd has listed the session in a /session_status taken here
  bool ended_ = false;   // a status taken later no longer does
  TickPhase device_phase_;
};

}  // namespace robotd::detail
