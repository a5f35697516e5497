// The DDS side of robotd a closed-loop client talks to, played by the test on a private domain
// over the real DDS stack: it grants /request_control and /release_control, writes TickState on
// /arm/tick_state, /session_status and /device_status, and reads the client's /control_command.
// It decides nothing (robotd's behaviour is tested through a real robotd in tests/e2e); it lets
// the client's tick reading, answering and loop ending be tested alone, each case exactly.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "robotd/client.hpp"
#include "robotd/messages.hpp"
#include "test_domain.hpp"
#include "wire/participant.hpp"
#include "wire/service.hpp"
#include "wire/topic_io.hpp"

namespace robotd::testing {

inline constexpr std::string_view kPeerDevice = "arm";
inline constexpr std::string_view kPeerSessionId = "s-test-1";
inline constexpr std::int64_t kPeerPeriodNs = 1'000'000;

class TickPeer {
 public:
  TickPeer();
  TickPeer(const TickPeer&) = delete;
  TickPeer& operator=(const TickPeer&) = delete;
  ~TickPeer();

  /// Options of a client on the peer's domain.
  ClientOptions client_options() const;

  /// A TickState of the arm (6 joints, position[j] = tick / 1000 + j).
  static TickState tick_state(std::uint64_t tick);
  void write_tick(std::uint64_t tick) const;
  /// /session_status listing the granted session (with `ticks_in_time` answered in time), or none.
  void write_session_status(bool listed, std::uint64_t ticks_in_time = 0) const;
  void write_device_status(std::int64_t tick_deadline_steady_ns, std::int64_t period_ns) const;

  /// The next ControlCommand the client published, or none within `timeout`.
  std::optional<ControlCommand> next_command(std::chrono::milliseconds timeout);
  /// Until the client's readers of these topics have matched the peer's writers.
  bool await_tick_reader(std::chrono::milliseconds timeout) const;

 private:
  TestDomain domain_;
  wire::Participant participant_;
  std::unique_ptr<wire::ServiceServer<RequestControlRequest, RequestControlResponse>> request_control_;
  std::unique_ptr<wire::ServiceServer<ReleaseControlRequest, ReleaseControlResponse>> release_control_;
  std::unique_ptr<wire::TopicWriter<TickState>> ticks_;
  std::unique_ptr<wire::TopicWriter<SessionStatus>> statuses_;
  std::unique_ptr<wire::TopicWriter<DeviceStatus>> device_statuses_;
  std::unique_ptr<wire::TopicReader<ControlCommand>> commands_;
  std::vector<ControlCommand> received_;
  std::jthread server_;
};

}  // namespace robotd::testing
