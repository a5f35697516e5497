// Commands of a session: values for its motors, and keepalives.
#include <string>

#include "arguments.hpp"
#include "errors.hpp"
#include "handles.hpp"

using robotd::c::array_argument;
using robotd::c::check;
using robotd::c::fail;
using robotd::c::guarded;
using robotd::c::require;
using robotd::c::session_handle;
using robotd::c::to_command;

extern "C" {

robotd_status robotd_send_command(robotd_session* session, const robotd_command* command) {
  return guarded("robotd_send_command", [&] {
    auto& handle = session_handle(session);
    const auto& values = require(command, "command", "a robotd_command");
    check(handle.session.command(to_command(values, handle.session.motor_ids().size())));
  });
}

robotd_status robotd_send_positions(robotd_session* session, const float* positions_rad, size_t count) {
  return guarded("robotd_send_positions", [&] {
    auto& handle = session_handle(session);
    const std::size_t motors = handle.session.motor_ids().size();
    if (count != motors) {
      fail(ROBOTD_INVALID_ARGUMENT, "count is " + std::to_string(count) + ": expected " + std::to_string(motors) +
                                        ", one position per motor of the session");
    }
    require(positions_rad, "positions_rad", "count positions in rad");
    check(handle.session.send_positions(array_argument(positions_rad, count)));
  });
}

robotd_status robotd_keepalive(robotd_session* session) {
  return guarded("robotd_keepalive", [&] { check(session_handle(session).session.keepalive()); });
}

}  // extern "C"
