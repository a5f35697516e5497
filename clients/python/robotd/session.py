"""An exclusive control session on some motors of one device."""
from ctypes import byref, c_char_p, c_float, c_int, c_int32, c_size_t, c_void_p

from . import _native
from ._native import check, floats, int32s, lib, milliseconds, optional_text, pointer
from .client import Client
from .types import Behavior, Mode


class Session:
    """Exclusive control of `motors` (None: every motor) of `device` (None: robotd's only device).
    While it lives, only its commands move those motors. If it sends nothing for `timeout` seconds,
    robotd applies `on_timeout` and ends it. Leaving the with block (or close()) releases the
    motors with `on_release`.

        with robotd.Session(device="arm", motors=[0, 1, 2]) as session:
            session.command(positions=[0.5, 0.0, 0.3])

    `policy` and `policy_file` name who commands (e.g. "walk", "walk_v3.onnx"); /session_status
    shows them to everyone.

    Without `client`, the session connects a Client of its own (from the environment) and closes
    it with the session. Raises Refused, naming the holder, when another session has a motor."""

    def __init__(self, device=None, motors=None, *, mode=Mode.POSITION, on_timeout=Behavior.DAMPING, timeout=1.0,
                 kp=None, kd=None, on_release=Behavior.KEEP, policy=None, policy_file=None, client=None):
        self._handle = None
        self._own_client = client is None
        self._client = Client() if client is None else client
        try:
            self._request(device, motors, Mode.parse(mode), Behavior.parse(on_timeout), timeout, kp, kd,
                          Behavior.parse(on_release), (policy, policy_file))
        except BaseException:
            self._close_own_client()
            raise

    def _request(self, device, motors, mode, on_timeout, timeout, kp, kd, on_release, policy):
        request = _native.SessionRequest()
        check(lib.robotd_session_request_init(byref(request)))
        device_text = optional_text(device)
        motor_ids = int32s(motors, "motors")
        count = len(motor_ids) if motor_ids is not None else 0
        gains = (floats(kp, "kp", count or None), floats(kd, "kd", count or None))
        request.device = device_text
        request.motor_ids = pointer(motor_ids, c_int32)
        request.motor_count = count
        request.mode = mode
        request.on_timeout = on_timeout
        request.timeout_ms = milliseconds(timeout, "timeout")
        request.default_kp, request.default_kd = (pointer(gain, c_float) for gain in gains)
        request.on_release = on_release
        request.policy_name, request.policy_file_name = (optional_text(text) for text in policy)
        handle = c_void_p()
        check(lib.robotd_request_control(self._client.handle, byref(request), byref(handle)))
        self._handle = handle
        self.uuid = self._text(lib.robotd_session_uuid)  # the capability: keep it to this program
        self.session_id = self._text(lib.robotd_session_id)  # the public id others see
        self.device = self._text(lib.robotd_session_device)
        self.motors = self._motor_ids()
        self.mode = Mode(self._enum(lib.robotd_session_mode))
        self.timeout_behavior = Behavior(self._enum(lib.robotd_session_timeout_behavior))  # what robotd applies

    def _text(self, accessor):
        value = c_char_p()
        check(accessor(self._handle, byref(value)))
        return _native.text(value.value)

    def _enum(self, accessor):
        value = c_int()
        check(accessor(self._handle, byref(value)))
        return value.value

    def _motor_ids(self):
        ids, count = (c_int32 * _native.MAX_JOINTS)(), c_size_t()
        check(lib.robotd_session_motor_ids(self._handle, ids, _native.MAX_JOINTS, byref(count)))
        return tuple(ids[:count.value])

    @property
    def client(self):
        return self._client

    def command(self, positions=None, velocities=None, kp=None, kd=None, torques=None, *, motors=None):
        """Sends one command. Each array has a value per motor: per session motor in `motors`
        order, or per entry of `motors`. What a mode needs: POSITION positions; TORQUE torques;
        MIXED positions, kp, kd and torques. Raises only on malformed input or a released session;
        robotd's verdict shows in Client.device_status()'s counters."""
        motor_ids = int32s(motors, "motors")
        count = len(motor_ids) if motor_ids is not None else len(self.motors)
        arrays = {name: floats(values, name, count) for name, values in
                  (("positions", positions), ("velocities", velocities), ("kp", kp), ("kd", kd),
                   ("torques", torques))}
        command = _native.Command(motor_ids=pointer(motor_ids, c_int32),
                                  count=len(motor_ids) if motor_ids is not None else 0,
                                  **{name: pointer(array, c_float) for name, array in arrays.items()})
        check(lib.robotd_send_command(self._live_handle(), byref(command)))

    def keepalive(self):
        """Renews the session without moving anything."""
        check(lib.robotd_keepalive(self._live_handle()))

    def release(self, behavior=Behavior.KEEP):
        """Releases the motors now, robotd applying `behavior`; the session is over."""
        check(lib.robotd_release(self._live_handle(), Behavior.parse(behavior)))

    def close(self):
        """Releases the motors with the session's on_release if it is still active, then frees it
        (and the session's own client)."""
        if self._handle is not None:
            lib.robotd_session_free(self._handle)
            self._handle = None
        self._close_own_client()

    def _live_handle(self):
        if self._handle is None:
            raise ValueError(f"session {getattr(self, 'session_id', '')} is closed")
        return self._handle

    def _close_own_client(self):
        if self._own_client:
            self._client.close()

    def __enter__(self):
        return self

    def __exit__(self, *exception):
        self.close()

    def __del__(self):
        if getattr(self, "_handle", None) is not None:
            self.close()

    def __repr__(self):
        return (f"Session({self.device!r}, motors={list(self.motors)}, mode={self.mode.name}, "
                f"session_id={self.session_id!r})")
