"""Callbacks on robotd's state topics, for as long as a Subscription lives."""
import sys
import traceback
from ctypes import byref, c_void_p

from . import _native
from ._native import check, lib

# topic: (C callback type, subscribe function, converter of the C struct)
_TOPICS = {
    "joint_states": (_native.JointStateCallback, "robotd_subscribe_joint_states", _native.joint_state),
    "device_status": (_native.DeviceStatusCallback, "robotd_subscribe_device_status", _native.device_status),
}


class Subscription:
    """Calls `callback` with every sample of a topic, on the client's dispatch thread (one per
    client: a slow callback delays the others), until cancel() or the end of a with block. An
    exception in the callback is printed and the subscription goes on. A callback may command
    sessions and call services, but not subscribe, cancel or read samples of its own client."""

    def __init__(self, client, topic, callback):
        callback_type, subscribe, convert = _TOPICS[topic]

        def trampoline(sample, _user_data):
            try:
                callback(convert(sample.contents))
            except Exception:  # noqa: BLE001 — nothing may unwind into the C library
                print(f"robotd: exception in a {topic} callback:", file=sys.stderr)
                traceback.print_exc()

        # The C function pointer must live as long as the subscription does.
        self._trampoline = callback_type(trampoline)
        handle = c_void_p()
        check(getattr(lib, subscribe)(client.handle, self._trampoline, None, byref(handle)))
        self._handle = handle

    @property
    def active(self):
        return self._handle is not None

    def cancel(self):
        """Stops the callbacks; returns after a running callback has finished."""
        if self._handle is not None:
            check(lib.robotd_unsubscribe(self._handle))
            self._handle = None

    def __enter__(self):
        return self

    def __exit__(self, *exception):
        self.cancel()

    def __del__(self):
        if getattr(self, "_handle", None) is not None:
            lib.robotd_unsubscribe(self._handle)
