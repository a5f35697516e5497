// What the session service tells a device's RT loop when a session is granted or released:
// the ControlEvents built from a session record. One home, used by SessionService and by the
// tests that play the service side of a loop.
#pragma once

#include "device/device_channel.hpp"
#include "session/session_table.hpp"

namespace robotd::service {

/// The loop event that starts `record`'s session: its slot, generation, mode, applied timeout
/// fallback, timeout, grant time, motors and per-joint default gains (kNoGain where not given).
device::ControlEvent session_start_event(const session::SessionRecord& record);

/// The loop event that ends `record`'s session with the (already mapped) release behaviour.
device::ControlEvent session_release_event(const session::SessionRecord& record, Behavior applied);

}  // namespace robotd::service
