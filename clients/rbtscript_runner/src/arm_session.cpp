#include "arm_session.hpp"

namespace robotd::rbtscript::detail {

Result<void> ArmSession::open() {
  streamer_.reset();
  session_.reset();
  auto session = client_.request_control(request_);
  if (!session) return session.error();
  session_.emplace(std::move(session).value());
  auto streamer = motion::TrajectoryStreamer::create(client_, *session_);
  if (!streamer) return streamer.error();
  streamer_.emplace(std::move(streamer).value());
  return {};
}

Result<std::string> ArmSession::run(const motion::DeviceIo& io, const motion::DeviceCall& call) {
  if (!call.needs_free_motors) return io.run(client_, call);
  streamer_.reset();
  if (auto released = session_->release(Behavior::kKeep); !released) return released.error();
  session_.reset();
  auto done = io.run(client_, call);
  if (auto reopened = open(); !reopened) return reopened.error();
  return done;
}

}  // namespace robotd::rbtscript::detail
