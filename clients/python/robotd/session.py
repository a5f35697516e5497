"""An exclusive control session on some motors of one device."""
import time
from ctypes import byref, c_char_p, c_double, c_float, c_int, c_int32, c_size_t, c_void_p

from . import _native
from ._native import check, doubles, floats, int32s, lib, milliseconds, optional_text, pointer
from .client import Client
from .errors import Refused
from .types import Behavior, LowRateAction, Mode


class Session:
    """Exclusive control of `motors` (None: every motor) of `device` (None: robotd's only device).
    While it lives, only its commands move those motors. If it sends nothing for `timeout` seconds,
    robotd applies `on_timeout` and ends it. Leaving the with block (or close()) releases the
    motors with `on_release`.

        with robotd.Session(device="arm", motors=[0, 1, 2]) as session:
            session.command(positions=[0.5, 0.0, 0.3])

    `policy` and `policy_file` name who commands (e.g. "walk", "walk_v3.onnx"); /session_status
    shows them to everyone.

    Closed loop (ticks(), answer()): `closed_loop` makes the session read its device's tick states
    from the grant on (else from the first ticks() / next_tick(), whose first wait then includes
    DDS discovery); `min_command_success_rate` (0..1, 0 = none) is the least fraction of ticks it
    must answer in time, and `on_low_success_rate` ("warn" or "fallback") what robotd does below it.

    Without `client`, the session connects a Client of its own (from the environment) and closes
    it with the session. Raises Refused, naming the holder, when another session has a motor."""

    def __init__(self, device=None, motors=None, *, mode=Mode.POSITION, on_timeout=Behavior.DAMPING, timeout=1.0,
                 kp=None, kd=None, on_release=Behavior.KEEP, policy=None, policy_file=None, closed_loop=False,
                 min_command_success_rate=0.0, on_low_success_rate=LowRateAction.WARN, client=None):
        self._handle = None
        self._own_client = client is None
        self._client = Client() if client is None else client
        try:
            self._request(device, motors, Mode.parse(mode), Behavior.parse(on_timeout), timeout, kp, kd,
                          Behavior.parse(on_release), (policy, policy_file),
                          (closed_loop, min_command_success_rate, LowRateAction.parse(on_low_success_rate)))
        except BaseException:
            self._close_own_client()
            raise

    def _request(self, device, motors, mode, on_timeout, timeout, kp, kd, on_release, policy, closed_loop):
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
        request.closed_loop, request.min_command_success_rate, request.on_low_success_rate = closed_loop
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
        command, _arrays = self._command(positions, velocities, kp, kd, torques, motors)
        check(lib.robotd_send_command(self._live_handle(), byref(command)))

    def _command(self, positions, velocities, kp, kd, torques, motors):
        """The C command for these values (see command()), and the arrays its pointers point into:
        keep them until the call it is passed to returns."""
        motor_ids = int32s(motors, "motors")
        count = len(motor_ids) if motor_ids is not None else len(self.motors)
        arrays = {name: floats(values, name, count) for name, values in
                  (("positions", positions), ("velocities", velocities), ("kp", kp), ("kd", kd),
                   ("torques", torques))}
        command = _native.Command(motor_ids=pointer(motor_ids, c_int32),
                                  count=len(motor_ids) if motor_ids is not None else 0,
                                  **{name: pointer(array, c_float) for name, array in arrays.items()})
        return command, (motor_ids, arrays)

    def next_tick(self, timeout=1.0):
        """The newest TickState of the session's device newer than the last one returned, waited
        for up to `timeout` seconds (Timeout). Raises Refused once robotd no longer lists the
        session (it timed out, fell back or was released)."""
        raw = _native.TickStateStruct()
        check(lib.robotd_session_next_tick(self._live_handle(), milliseconds(timeout, "timeout"), byref(raw)))
        return _native.tick_state(raw)

    def ticks(self, duration=None, state_timeout=0.2):
        """Each new TickState of the session's device, for a control loop:

            for state in session.ticks():
                session.answer(state, torques=[kp * (r - q) - kd * v for r, q, v in
                                               zip(reference, state.position, state.velocity)])

        Ends after `duration` seconds (None: no limit), or when robotd ends the session; break out
        of the loop to stop. Raises Timeout when no new tick comes within `state_timeout` seconds
        (the device stopped ticking or faulted, or robotd stopped). A tick the loop was too slow for
        is skipped: each state is the newest."""
        start = time.monotonic()
        while self._handle is not None and (duration is None or time.monotonic() - start < duration):
            try:
                yield self.next_tick(state_timeout)
            except Refused:
                return  # robotd no longer lists the session: its loop is over

    def answer(self, state, positions=None, velocities=None, kp=None, kd=None, torques=None, *, motors=None):
        """Sends a command (as command() does) as the answer to `state`, a TickState of ticks()
        or next_tick(). robotd counts it in time when it arrives before the device's next state."""
        command, _arrays = self._command(positions, velocities, kp, kd, torques, motors)
        tick = _native.tick_reference(state)
        check(lib.robotd_session_answer(self._live_handle(), byref(tick), byref(command)))

    def send_aligned(self, positions=None, velocities=None, kp=None, kd=None, torques=None, *, motors=None,
                     lead=None):
        """Sends a command `lead` seconds (None: the library's default, 120 µs) before the device's
        next tick is due, sleeping until then: open-loop streaming whose commands wait in robotd
        for about `lead` instead of up to a period."""
        if lead is not None and lead < 0:
            raise ValueError(f"lead is a duration in seconds, >= 0 (got {lead!r})")
        lead_us = -1 if lead is None else int(round(lead * 1e6))
        command, _arrays = self._command(positions, velocities, kp, kd, torques, motors)
        check(lib.robotd_session_send_aligned(self._live_handle(), byref(command), lead_us))

    def info(self, timeout=2.0):
        """The session's SessionInfo as robotd last published it in /session_status (its command
        success rate and answer counts), waiting up to `timeout` seconds for the first one."""
        raw = _native.SessionInfoStruct()
        check(lib.robotd_session_get_info(self._live_handle(), milliseconds(timeout, "timeout"), byref(raw)))
        return _native.session_info(raw)

    def move_joints(self, target, t=None, v=None, a=None, func=None, *, stop=None):
        """Moves every joint of the device to `target` (rad, one per joint), planned here on the
        device's limits and streamed through the session until every joint is within 0.1° of it;
        returns a MoveReport. RBTscript's timing: `t` seconds overrides `v` and `a` (percent of the
        leading joint's maximum speed and acceleration); `func` "poly" or "trap" (default: the
        polynomial with t, else the trapezoid); none: a conservative trapezoid. The session must be
        a POSITION session on every motor of its device. Ctrl-C or `stop` (a threading.Event) end
        the move with the arm held (MoveReport.stopped). Raises InvalidArgument before anything
        moves for a target out of the limits or a move too fast, Refused on an e-stop or a fault."""
        from . import motion
        values = doubles(target, "target")
        handle = self._live_handle()

        def call(options, report):
            check(lib.robotd_session_move_joints(self._client.handle, handle, values, len(values), byref(options),
                                                 byref(report)))

        return motion.move(call, (t, v, a, func), stop)

    def move_cartesian(self, pose, t=None, v=None, a=None, func=None, *, line=False, stop=None):
        """Moves the tool of the device's arm model to `pose`: (x, y, z) in m and the arm's three
        angles in rad (its vendor's Euler convention), in the base frame. `line=False`: IK, then a
        joint move (RBTscript MovePose); `line=True`: a straight line, IK along it, refused before
        a singularity or a limit (MoveCart; takes only t and func). Otherwise as move_joints."""
        from . import motion
        values = doubles(pose, "pose (x, y, z in m, three angles in rad)", 6)
        goal = _native.Pose((c_double * 3)(*values[:3]), (c_double * 3)(*values[3:]))
        handle = self._live_handle()
        if line and (v is not None or a is not None):
            raise ValueError("a straight line takes t and func only, not v or a")

        def call(options, report):
            check(lib.robotd_session_move_cartesian(self._client.handle, handle, byref(goal), 1 if line else 0,
                                                    byref(options), byref(report)))

        return motion.move(call, (t, v, a, func), stop)

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

