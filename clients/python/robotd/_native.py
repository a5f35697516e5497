"""librobotd_c through ctypes: the library, its structs and functions (robotd/robotd.h), and the
conversion of its results into this package's types. Nothing here is public."""
import ctypes
import os
import threading
from ctypes import POINTER, Structure, c_bool, c_char, c_char_p, c_double, c_float, c_int, c_int32, c_int64
from ctypes import c_size_t, c_uint64, c_void_p

from . import errors
from .types import DeviceInfo, DeviceState, DeviceStatus, JointState, LowRateAction, SessionInfo, TickState

C_API_VERSION = 5  # the robotd/robotd.h this module mirrors
MAX_JOINTS = 64
NAME_CAPACITY = 64
UUID_CAPACITY = 40
TEXT_CAPACITY = 256
BUFFER_TOO_SMALL = 7

_Name = c_char * NAME_CAPACITY
_Text = c_char * TEXT_CAPACITY
_Doubles = c_double * MAX_JOINTS
_Enum = c_int  # a C enum whose values fit an int


class ClientOptions(Structure):
    _fields_ = [("domain_id", c_int32), ("network_interface", c_char_p), ("peers", c_char_p),
                ("multicast", c_bool), ("node_name", c_char_p), ("service_timeout_ms", c_int32)]


class DeviceInfoStruct(Structure):
    _fields_ = [("name", _Name), ("driver", _Name), ("model", _Name), ("kinematic_model", _Name), ("state", _Enum), ("rate_hz", c_double),
                ("joint_count", c_size_t), ("joint_names", _Name * MAX_JOINTS), ("position_min", _Doubles),
                ("position_max", _Doubles), ("velocity_max", _Doubles), ("effort_max", _Doubles)]


class SessionRequest(Structure):
    _fields_ = [("device", c_char_p), ("motor_ids", POINTER(c_int32)), ("motor_count", c_size_t), ("mode", _Enum),
                ("on_timeout", _Enum), ("timeout_ms", c_int32), ("default_kp", POINTER(c_float)),
                ("default_kd", POINTER(c_float)), ("on_release", _Enum), ("policy_name", c_char_p),
                ("policy_file_name", c_char_p), ("closed_loop", c_bool), ("min_command_success_rate", c_float),
                ("on_low_success_rate", _Enum)]


class Command(Structure):
    _fields_ = [("motor_ids", POINTER(c_int32)), ("count", c_size_t), ("positions", POINTER(c_float)),
                ("velocities", POINTER(c_float)), ("kp", POINTER(c_float)), ("kd", POINTER(c_float)),
                ("torques", POINTER(c_float))]


class JointStateStruct(Structure):
    _fields_ = [("device", _Name), ("stamp_ns", c_int64), ("joint_count", c_size_t), ("names", _Name * MAX_JOINTS),
                ("position", _Doubles), ("velocity", _Doubles), ("effort", _Doubles)]


class DeviceStatusStruct(Structure):
    _fields_ = [("device", _Name), ("stamp_ns", c_int64), ("state", _Enum), ("state_text", _Text),
                ("fault_code", c_int32), ("fault_text", _Text), ("estop_engaged", c_bool),
                ("loop_period_p50_us", c_float), ("loop_period_p99_us", c_float), ("loop_period_max_us", c_float),
                ("loop_overruns", c_uint64), ("commands_accepted", c_uint64), ("commands_rejected", c_uint64)]


class TickStateStruct(Structure):
    _fields_ = [("device", _Name), ("tick", c_uint64), ("stamp_ns", c_int64), ("deadline_steady_ns", c_int64),
                ("period_ns", c_int64), ("state_ready_steady_ns", c_int64), ("published_steady_ns", c_int64),
                ("state", _Enum), ("joint_count", c_size_t), ("position", _Doubles), ("velocity", _Doubles),
                ("effort", _Doubles), ("has_imu", c_bool), ("imu_orientation", c_double * 4),
                ("imu_angular_velocity", c_double * 3), ("imu_linear_acceleration", c_double * 3)]


class SessionInfoStruct(Structure):
    _fields_ = [("session_id", c_char * UUID_CAPACITY), ("node_name", _Name), ("device", _Name),
                ("commands_accepted", c_uint64), ("closed_loop", c_bool), ("ticks_to_answer", c_uint64),
                ("ticks_answered_in_time", c_uint64), ("ticks_answered_late", c_uint64),
                ("ticks_unanswered", c_uint64), ("command_success_rate", c_float),
                ("min_command_success_rate", c_float), ("on_low_success_rate", _Enum),
                ("success_rate_low", c_bool)]


class MoveOptions(Structure):
    _fields_ = [("duration_s", c_double), ("speed_percent", c_double), ("acceleration_percent", c_double),
                ("shape", _Enum), ("stop", POINTER(c_int))]


class MoveReportStruct(Structure):
    _fields_ = [("stopped", c_bool), ("commands_sent", c_uint64), ("fraction_done", c_double),
                ("joint_count", c_size_t), ("last_measured", _Doubles), ("summary", _Text)]


class Pose(Structure):
    _fields_ = [("position_m", c_double * 3), ("angles_rad", c_double * 3)]


RbtscriptProgress = ctypes.CFUNCTYPE(None, c_size_t, c_char_p, c_uint64, c_void_p)


class RbtscriptOptions(Structure):
    _fields_ = [("device", c_char_p), ("dry_run", c_bool), ("loops", c_uint64), ("stop", POINTER(c_int)),
                ("on_statement", RbtscriptProgress), ("user_data", c_void_p), ("session_timeout_ms", c_int32)]


class RbtscriptProblemStruct(Structure):
    _fields_ = [("line", c_size_t), ("column", c_size_t), ("statement", c_char_p), ("message", c_char_p),
                ("description", c_char_p)]


class RbtscriptOutcomeStruct(Structure):
    _fields_ = [("device", _Name), ("syntax_errors", c_bool), ("problem_count", c_size_t),
                ("moves_planned", c_size_t), ("pass_seconds", c_double), ("end", _Enum),
                ("statements_run", c_uint64), ("passes", c_uint64), ("failure", RbtscriptProblemStruct)]


JointStateCallback = ctypes.CFUNCTYPE(None, POINTER(JointStateStruct), c_void_p)
DeviceStatusCallback = ctypes.CFUNCTYPE(None, POINTER(DeviceStatusStruct), c_void_p)

_Status = c_int
_Handle = c_void_p
# name: (result type, argument types)
_PROTOTYPES = {
    "robotd_last_error": (c_char_p, []),
    "robotd_status_name": (c_char_p, [_Status]),
    "robotd_c_api_version": (c_int, []),
    "robotd_version": (c_char_p, []),
    "robotd_client_options_init": (_Status, [POINTER(ClientOptions)]),
    "robotd_connect": (_Status, [POINTER(ClientOptions), POINTER(_Handle)]),
    "robotd_disconnect": (None, [_Handle]),
    "robotd_list_devices": (_Status, [_Handle, POINTER(DeviceInfoStruct), c_size_t, POINTER(c_size_t)]),
    "robotd_session_request_init": (_Status, [POINTER(SessionRequest)]),
    "robotd_request_control": (_Status, [_Handle, POINTER(SessionRequest), POINTER(_Handle)]),
    "robotd_session_uuid": (_Status, [_Handle, POINTER(c_char_p)]),
    "robotd_session_id": (_Status, [_Handle, POINTER(c_char_p)]),
    "robotd_session_device": (_Status, [_Handle, POINTER(c_char_p)]),
    "robotd_session_motor_ids": (_Status, [_Handle, POINTER(c_int32), c_size_t, POINTER(c_size_t)]),
    "robotd_session_mode": (_Status, [_Handle, POINTER(_Enum)]),
    "robotd_session_timeout_behavior": (_Status, [_Handle, POINTER(_Enum)]),
    "robotd_release": (_Status, [_Handle, _Enum]),
    "robotd_release_by_uuid": (_Status, [_Handle, c_char_p, _Enum]),
    "robotd_session_free": (None, [_Handle]),
    "robotd_send_command": (_Status, [_Handle, POINTER(Command)]),
    "robotd_keepalive": (_Status, [_Handle]),
    "robotd_session_next_tick": (_Status, [_Handle, c_int32, POINTER(TickStateStruct)]),
    "robotd_session_answer": (_Status, [_Handle, POINTER(TickStateStruct), POINTER(Command)]),
    "robotd_session_send_aligned": (_Status, [_Handle, POINTER(Command), c_int32]),
    "robotd_session_get_info": (_Status, [_Handle, c_int32, POINTER(SessionInfoStruct)]),
    "robotd_next_joint_state": (_Status, [_Handle, c_char_p, c_int32, POINTER(JointStateStruct)]),
    "robotd_next_device_status": (_Status, [_Handle, c_char_p, c_int32, POINTER(DeviceStatusStruct)]),
    "robotd_subscribe_joint_states": (_Status, [_Handle, JointStateCallback, c_void_p, POINTER(_Handle)]),
    "robotd_subscribe_device_status": (_Status, [_Handle, DeviceStatusCallback, c_void_p, POINTER(_Handle)]),
    "robotd_unsubscribe": (_Status, [_Handle]),
    "robotd_estop": (_Status, [_Handle, c_char_p, c_char_p]),
    "robotd_estop_report": (_Status, [_Handle, c_char_p, c_char_p, POINTER(c_void_p)]),
    "robotd_reset_estop": (_Status, [_Handle, c_char_p]),
    # The result is a char* the library allocated: kept as a void pointer, so that it can be freed.
    "robotd_device_call": (_Status, [_Handle, c_char_p, c_char_p, c_char_p, c_int32, POINTER(c_void_p)]),
    "robotd_free_string": (None, [c_void_p]),
    "robotd_move_options_init": (_Status, [POINTER(MoveOptions)]),
    "robotd_session_move_joints": (_Status, [_Handle, _Handle, POINTER(c_double), c_size_t, POINTER(MoveOptions),
                                             POINTER(MoveReportStruct)]),
    "robotd_session_move_cartesian": (_Status, [_Handle, _Handle, POINTER(Pose), _Enum, POINTER(MoveOptions),
                                                POINTER(MoveReportStruct)]),
    "robotd_rbtscript_options_init": (_Status, [POINTER(RbtscriptOptions)]),
    "robotd_run_rbtscript": (_Status, [_Handle, c_char_p, POINTER(RbtscriptOptions), POINTER(_Handle)]),
    "robotd_rbtscript_report_outcome": (_Status, [_Handle, POINTER(RbtscriptOutcomeStruct)]),
    "robotd_rbtscript_report_problem": (_Status, [_Handle, c_size_t, POINTER(RbtscriptProblemStruct)]),
    "robotd_rbtscript_report_free": (None, [_Handle]),
}


def _library_paths():
    """Where to look for librobotd_c, most specific first: $ROBOTD_C_LIBRARY, the path the
    install rules wrote into _installed.py, then the dynamic loader's own search."""
    if os.environ.get("ROBOTD_C_LIBRARY"):
        return [os.environ["ROBOTD_C_LIBRARY"]]
    paths = []
    try:
        from ._installed import LIBRARY  # written by the install rules only
        paths.append(LIBRARY)
    except ImportError:
        pass
    paths.append(f"librobotd_c.so.{C_API_VERSION}")
    return paths


def _load():
    failures = []
    for path in _library_paths():
        try:
            library = ctypes.CDLL(path)
            break
        except OSError as error:
            failures.append(str(error))
    else:
        raise ImportError("robotd: cannot load the robotd C library (" + "; ".join(failures) + "). Install "
                          "robotd, or set ROBOTD_C_LIBRARY to the path of librobotd_c.so")
    for name, (result, arguments) in _PROTOTYPES.items():
        function = getattr(library, name)
        function.restype = result
        function.argtypes = arguments
    version = library.robotd_c_api_version()
    if version != C_API_VERSION:
        raise ImportError(f"robotd: the C library at {library._name} has C API version {version}; this "
                          f"package needs version {C_API_VERSION}")
    return library


lib = _load()


def text(raw):
    """A C string as str: bytes (a char* result, or a char[] field, which ctypes hands out as
    bytes) or a char[] element of a 2-D field. robotd's texts are UTF-8."""
    if raw is None:
        return ""
    if isinstance(raw, ctypes.Array):
        raw = raw.value
    return raw.decode("utf-8", errors="replace")


def check(status):
    """Raises the exception for a failed call, with the library's message for this thread."""
    if status == 0:
        return
    message = text(lib.robotd_last_error())
    exception = errors.BY_STATUS.get(status, errors.RobotdError)
    raise exception(text(lib.robotd_status_name(status)), message)


def stoppable(call, stop_flag, stop=None):
    """Runs call() (a library call and its check()) on a thread of its own and waits for it here,
    so that Ctrl-C (KeyboardInterrupt) or `stop` (a threading.Event) can set `stop_flag` (the C
    int the library watches): the library then ends what it is doing with the arm held. Returns
    call()'s result or raises its exception; KeyboardInterrupt is raised again after the stop."""
    outcome = {}

    def work():
        try:
            outcome["value"] = call()
        except BaseException as error:  # handed to the waiting thread
            outcome["error"] = error

    worker = threading.Thread(target=work, name="robotd-planned-motion", daemon=True)
    worker.start()
    try:
        while worker.is_alive():
            worker.join(0.05)
            if stop is not None and stop.is_set():
                stop_flag.value = 1
    except KeyboardInterrupt:
        stop_flag.value = 1
        worker.join()
        raise
    if "error" in outcome:
        raise outcome["error"]
    return outcome["value"]


def optional_text(value):
    """str (or None) as the const char* the C API takes (NULL for None)."""
    return None if value is None else str(value).encode("utf-8")


def milliseconds(seconds, what):
    if seconds is None or seconds < 0:
        raise ValueError(f"{what} is a duration in seconds, >= 0 (got {seconds!r})")
    return int(round(seconds * 1000))


def c_array(c_type, values, what, count=None, count_text=", expected {count}"):
    """A sequence of numbers as a C array of c_type, or None for None; count_text says what a
    wrong length should have been."""
    if values is None:
        return None
    try:
        array = (c_type * len(values))(*values)
    except TypeError:
        raise TypeError(f"{what}: a sequence of numbers, not {type(values).__name__}") from None
    if count is not None and len(values) != count:
        raise ValueError(f"{what}: {len(values)} values" + count_text.format(count=count))
    return array


def floats(values, what, count=None):
    """A sequence of numbers as a C float array, or None for None."""
    return c_array(c_float, values, what, count, " for {count} motors")


def doubles(values, what, count=None):
    """A sequence of numbers as a C double array, or None for None."""
    return c_array(c_double, values, what, count)


def int32s(values, what):
    if values is None:
        return None
    try:
        return (c_int32 * len(values))(*values)
    except TypeError:
        raise TypeError(f"{what}: a sequence of integers, not {type(values).__name__}") from None


def pointer(array, element):
    """A ctypes array as the `element*` a struct field holds (None stays NULL). The array must
    outlive the call the struct is passed to."""
    return None if array is None else ctypes.cast(array, POINTER(element))


def _vector(array, count):
    return tuple(array[:count])


def device_info(raw):
    count = raw.joint_count
    return DeviceInfo(name=text(raw.name), driver=text(raw.driver), model=text(raw.model),
                      kinematic_model=text(raw.kinematic_model),
                      state=DeviceState(raw.state), rate_hz=raw.rate_hz,
                      joint_names=tuple(text(raw.joint_names[j]) for j in range(count)),
                      position_min=_vector(raw.position_min, count), position_max=_vector(raw.position_max, count),
                      velocity_max=_vector(raw.velocity_max, count), effort_max=_vector(raw.effort_max, count))


def joint_state(raw):
    count = raw.joint_count
    return JointState(device=text(raw.device), stamp_ns=raw.stamp_ns,
                      names=tuple(text(raw.names[j]) for j in range(count)),
                      position=_vector(raw.position, count), velocity=_vector(raw.velocity, count),
                      effort=_vector(raw.effort, count))


def device_status(raw):
    return DeviceStatus(device=text(raw.device), stamp_ns=raw.stamp_ns, state=DeviceState(raw.state),
                        state_text=text(raw.state_text), fault_code=raw.fault_code,
                        fault_text=text(raw.fault_text), estop_engaged=bool(raw.estop_engaged),
                        loop_period_p50_us=raw.loop_period_p50_us, loop_period_p99_us=raw.loop_period_p99_us,
                        loop_period_max_us=raw.loop_period_max_us, loop_overruns=raw.loop_overruns,
                        commands_accepted=raw.commands_accepted, commands_rejected=raw.commands_rejected)



def tick_state(raw):
    count = raw.joint_count
    imu = (tuple(raw.imu_orientation), tuple(raw.imu_angular_velocity),
           tuple(raw.imu_linear_acceleration)) if raw.has_imu else None
    return TickState(device=text(raw.device), tick=raw.tick, stamp_ns=raw.stamp_ns,
                     deadline_steady_ns=raw.deadline_steady_ns, period_ns=raw.period_ns,
                     state_ready_steady_ns=raw.state_ready_steady_ns, published_steady_ns=raw.published_steady_ns,
                     state=DeviceState(raw.state), position=_vector(raw.position, count),
                     velocity=_vector(raw.velocity, count), effort=_vector(raw.effort, count), imu=imu)


def tick_reference(state):
    """What robotd_session_answer reads of a TickState: its device and tick."""
    raw = TickStateStruct()
    raw.device = state.device.encode("utf-8")[:NAME_CAPACITY - 1]
    raw.tick = state.tick
    return raw


def session_info(raw):
    return SessionInfo(session_id=text(raw.session_id), node_name=text(raw.node_name), device=text(raw.device),
                       commands_accepted=raw.commands_accepted, closed_loop=bool(raw.closed_loop),
                       ticks_to_answer=raw.ticks_to_answer, ticks_answered_in_time=raw.ticks_answered_in_time,
                       ticks_answered_late=raw.ticks_answered_late, ticks_unanswered=raw.ticks_unanswered,
                       command_success_rate=raw.command_success_rate,
                       min_command_success_rate=raw.min_command_success_rate,
                       on_low_success_rate=LowRateAction(raw.on_low_success_rate),
                       success_rate_low=bool(raw.success_rate_low))
