"""A connection to robotd over DDS: devices, state, sessions, safety and device operations."""
import json
from ctypes import byref, c_char_p, c_size_t, c_void_p, cast

from . import _native
from ._native import check, lib, milliseconds, optional_text
from .subscription import Subscription
from .types import Behavior


class Client:
    """Joins robotd's DDS domain. The defaults are robotd's (domain 0 on loopback), overridden by
    ROBOTD_DOMAIN_ID, ROBOTD_DDS_INTERFACE, ROBOTD_DDS_PEERS and ROBOTD_DDS_MULTICAST=1, and then
    by the arguments. Connecting succeeds without robotd running; calls then raise NotAvailable.

        with robotd.Client() as client:
            print([device.name for device in client.devices()])

    A client may be shared by threads. close() (or the end of a with block) leaves the domain;
    sessions and subscriptions made from it keep its connection open until they end too."""

    def __init__(self, domain_id=None, *, interface=None, peers=None, multicast=None, node_name="robotd_python",
                 service_timeout=None):
        self._handle = None
        options = _native.ClientOptions()
        check(lib.robotd_client_options_init(byref(options)))
        if domain_id is not None:
            options.domain_id = domain_id
        # The option strings must outlive robotd_connect: keep the bytes referenced until then.
        keep = []
        for field, value in (("network_interface", interface), ("node_name", node_name)):
            if value is not None:
                keep.append(optional_text(value))
                setattr(options, field, keep[-1])
        if peers is not None:
            keep.append(optional_text(",".join(peers) if not isinstance(peers, str) else peers))
            options.peers = keep[-1]
        if multicast is not None:
            options.multicast = bool(multicast)
        if service_timeout is not None:
            options.service_timeout_ms = milliseconds(service_timeout, "service_timeout")
        handle = c_void_p()
        check(lib.robotd_connect(byref(options), byref(handle)))
        self._handle = handle

    @property
    def handle(self):
        """The C API's robotd_client*; raises once closed."""
        if self._handle is None:
            raise ValueError("this robotd.Client is closed")
        return self._handle

    def close(self):
        if self._handle is not None:
            lib.robotd_disconnect(self._handle)
            self._handle = None

    def __enter__(self):
        return self

    def __exit__(self, *exception):
        self.close()

    def __del__(self):
        self.close()

    # ---- devices and state --------------------------------------------------------------------

    def devices(self):
        """The devices robotd drives: a list of DeviceInfo."""
        capacity, count = 8, c_size_t()
        while True:
            infos = (_native.DeviceInfoStruct * capacity)()
            status = lib.robotd_list_devices(self.handle, infos, capacity, byref(count))
            if status != _native.BUFFER_TOO_SMALL:
                check(status)
                return [_native.device_info(infos[i]) for i in range(count.value)]
            capacity = count.value  # more devices than room: ask again with room for all

    def joint_state(self, device=None, timeout=1.0):
        """The next /joint_states sample of `device` (None: robotd's any device) within `timeout` s."""
        state = _native.JointStateStruct()
        check(lib.robotd_next_joint_state(self.handle, optional_text(device), milliseconds(timeout, "timeout"),
                                          byref(state)))
        return _native.joint_state(state)

    def joint_states(self, device=None, timeout=1.0):
        """Every /joint_states sample of `device` as it comes, forever; raises Timeout when none came
        within `timeout` s. For samples at robotd's full rate without polling, see on_joint_states."""
        while True:
            yield self.joint_state(device, timeout)

    def device_status(self, device=None, timeout=1.0):
        """The next /device_status sample of `device`: state, fault, loop timing, command counters."""
        status = _native.DeviceStatusStruct()
        check(lib.robotd_next_device_status(self.handle, optional_text(device), milliseconds(timeout, "timeout"),
                                            byref(status)))
        return _native.device_status(status)

    def on_joint_states(self, callback):
        """Calls callback(JointState) with every sample of every device, on the client's dispatch
        thread, until the returned Subscription is cancelled (or its with block ends)."""
        return Subscription(self, "joint_states", callback)

    def on_device_status(self, callback):
        """Calls callback(DeviceStatus) with every /device_status sample, like on_joint_states."""
        return Subscription(self, "device_status", callback)

    # ---- sessions ------------------------------------------------------------------------------

    def session(self, device=None, motors=None, **options):
        """A Session on this client; the arguments are Session's."""
        from .session import Session  # session.py imports this module
        return Session(device, motors, client=self, **options)

    def release(self, uuid, behavior=Behavior.KEEP):
        """Releases the session with this uuid (like robotctl release), e.g. one an earlier run of this
        program was granted and whose uuid it kept. A public session id releases nothing."""
        check(lib.robotd_release_by_uuid(self.handle, optional_text(uuid), Behavior.parse(behavior)))

    # ---- safety and device operations ------------------------------------------------------------

    def estop(self, device=None, reason=None):
        """Engages (latches) the e-stop of `device`, or of every device. Returns robotd's answer: per
        device whether its loop wrote the e-stop frame and how soon ("reached 'arm' in 0.42 ms"), or
        that it could not ("NOT confirmed on 'arm' (FAULT: …)"; robotd keeps sending it every tick)."""
        report = c_void_p()
        check(lib.robotd_estop_report(self.handle, optional_text(device), optional_text(reason), byref(report)))
        try:
            return _native.text(cast(report, c_char_p).value)
        finally:
            lib.robotd_free_string(report)

    def reset_estop(self, device=None):
        check(lib.robotd_reset_estop(self.handle, optional_text(device)))

    def call(self, device, op, args=None, *, timeout=10.0, **kwargs):
        """A device operation (a driver op, or robotd's recover / blackbox / loop_timing) with its
        arguments as a dict or keywords; returns its JSON result as Python values.

            client.call("arm", "state")
            client.call("piper", "set_crash_protection", levels=[1, 1, 1, 1, 1, 1])"""
        arguments = dict(args or {}, **kwargs)
        result = c_void_p()
        check(lib.robotd_device_call(self.handle, optional_text(device), optional_text(op),
                                     json.dumps(arguments).encode("utf-8"), milliseconds(timeout, "timeout"),
                                     byref(result)))
        try:
            return json.loads(_native.text(cast(result, c_char_p).value))
        finally:
            lib.robotd_free_string(result)
