// The session a running program holds on its device, and its streamer. A device op that robotd
// refuses while a session holds a motor (a PiPER's gripper) runs between releasing the session
// (KEEP: the arm holds) and taking it again.
#pragma once

#include <optional>
#include <string>
#include <utility>

#include "robotd/client/client.hpp"
#include "robotd/motion/device_io.hpp"
#include "robotd/motion/trajectory_streamer.hpp"

namespace robotd::rbtscript::detail {

class ArmSession {
 public:
  ArmSession(Client& client, SessionRequest request) : client_(client), request_(std::move(request)) {}

  /// Takes the device's motors (again).
  Result<void> open();
  /// Only while open.
  motion::TrajectoryStreamer& streamer() { return *streamer_; }
  /// Runs `call` on the device, releasing the motors around it when the op needs them free.
  Result<std::string> run(const motion::DeviceIo& io, const motion::DeviceCall& call);

 private:
  Client& client_;
  SessionRequest request_;
  std::optional<Session> session_;
  std::optional<motion::TrajectoryStreamer> streamer_;  // after session_: it refers to it
};

}  // namespace robotd::rbtscript::detail
