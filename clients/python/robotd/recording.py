"""Reading robotd recordings, the files `robotctl record` writes (docs/recording.md), with the
standard library only: no robotd, no librobotd_c, no numpy.

    from robotd import recording

    run = recording.read("run.rdrec")
    arm = run.device("arm")
    for state in run.joint_states:
        if state.device == "arm":
            print(state.time_ns * 1e-9, dict(zip(arm.joint_names, state.position)))
    print(run.problems)  # [] for a file that robotctl record closed

A file cut short (robotctl killed while recording) reads up to its last complete record, and
`problems` says what was lost. A file that is not a recording, or of another major format
version, raises RecordingError."""
import json
import struct
from dataclasses import dataclass, field

MAGIC = b"\x89RBDREC\n"
MAJOR_VERSION = 1  # the format version this module reads: 1.x, any minor version

KIND_JOINT_STATE = 1
KIND_CONTROL_COMMAND = 2
KIND_SESSION_STATUS = 3
KIND_DEVICE_STATUS = 4
KIND_END = 255

UNKNOWN_DEVICE = 0xFFFF  # a command whose device robotctl could not tell

_FILE_HEADER = struct.Struct("<8sHHI")  # magic, major, minor, description length
_RECORD_HEADER = struct.Struct("<BIq")  # kind, payload length, receive time (ns since the start)
_JOINT_STATE_START = struct.Struct("<Hq")  # device index, stamp_ns
_COMMAND_START = struct.Struct("<HqI")  # device index, stamp_ns, session tag
_COUNT = struct.Struct("<H")


class RecordingError(ValueError):
    """The file is not a robotd recording this module can read; the message says why."""


@dataclass(frozen=True)
class Device:
    """A device as /list_devices described it when the recording began."""
    name: str
    driver: str
    model: str
    rate_hz: float
    joint_names: tuple
    position_min: tuple  # rad
    position_max: tuple  # rad
    velocity_max: tuple  # rad/s
    acceleration_max: tuple  # rad/s²
    effort_max: tuple  # N·m


@dataclass(frozen=True)
class JointState:
    """A /joint_states sample; values in the order of the device's joint_names."""
    time_ns: int  # receive time, ns since the recording began
    device: str
    stamp_ns: int  # robotd's stamp, CLOCK_REALTIME
    position: tuple  # rad
    velocity: tuple  # rad/s
    effort: tuple  # N·m


@dataclass(frozen=True)
class Command:
    """A /control_command sample; arrays parallel to motor_ids (empty arrays were not sent)."""
    time_ns: int  # receive time, ns since the recording began
    device: str  # None when robotctl could not tell
    stamp_ns: int  # the sender's stamp, CLOCK_REALTIME
    session: str  # the first 8 hex digits of the session's uuid (not its public id)
    motor_ids: tuple
    positions: tuple  # rad
    velocities: tuple  # rad/s
    kp: tuple
    kd: tuple
    torques: tuple  # N·m


@dataclass(frozen=True)
class Status:
    """A /session_status or /device_status sample, as robotctl echo --json prints it (sessions
    named by their public ids)."""
    time_ns: int  # receive time, ns since the recording began
    message: dict


@dataclass
class Recording:
    path: str
    version: tuple  # (major, minor)
    description: dict  # the header's JSON description
    devices: tuple  # Device, in the order records refer to them
    joint_states: list = field(default_factory=list)
    commands: list = field(default_factory=list)
    session_status: list = field(default_factory=list)
    device_status: list = field(default_factory=list)
    closed: bool = False  # the end record was read
    duration_ns: int = 0  # receive time of the last record
    problems: list = field(default_factory=list)  # what was wrong with the file; [] when whole

    @property
    def start_time_ns(self):
        """CLOCK_REALTIME when recording began."""
        return self.description["start_time_ns"]

    def device(self, name):
        """The recorded device called `name`; KeyError (naming those recorded) if there is none."""
        for device in self.devices:
            if device.name == name:
                return device
        raise KeyError(f"{self.path} recorded no device {name!r} (it recorded "
                       f"{', '.join(repr(d.name) for d in self.devices) or 'none'})")


class _Payload:
    """Reads little-endian values in order; raises ValueError past the end."""

    def __init__(self, data):
        self._data = data
        self._offset = 0

    def unpack(self, layout):
        values = layout.unpack_from(self._data, self._offset)
        self._offset += layout.size
        return values

    def array(self, code):
        (count,) = self.unpack(_COUNT)
        return self.unpack(struct.Struct(f"<{count}{code}"))

    def check_consumed(self):
        if self._offset != len(self._data):
            raise ValueError(f"{len(self._data) - self._offset} bytes left over")


def _device_name(devices, index):
    return devices[index].name if index < len(devices) else None


def _joint_state(time_ns, payload, devices):
    data = _Payload(payload)
    device, stamp_ns = data.unpack(_JOINT_STATE_START)
    position, velocity, effort = data.array("d"), data.array("d"), data.array("d")
    data.check_consumed()
    return JointState(time_ns, _device_name(devices, device), stamp_ns, position, velocity, effort)


def _command(time_ns, payload, devices):
    data = _Payload(payload)
    device, stamp_ns, session = data.unpack(_COMMAND_START)
    motor_ids = data.array("i")
    positions, velocities, kp, kd, torques = (data.array("f") for _ in range(5))
    data.check_consumed()
    return Command(time_ns, _device_name(devices, device), stamp_ns, f"{session:08x}", motor_ids, positions,
                   velocities, kp, kd, torques)


def _status(time_ns, payload, _devices):
    return Status(time_ns, json.loads(payload.decode("utf-8")))


# kind: (how to decode its payload, the Recording list it goes to)
_DECODERS = {
    KIND_JOINT_STATE: (_joint_state, "joint_states"),
    KIND_CONTROL_COMMAND: (_command, "commands"),
    KIND_SESSION_STATUS: (_status, "session_status"),
    KIND_DEVICE_STATUS: (_status, "device_status"),
}


def _device(description):
    def values(key):
        return tuple(description.get(key, ()))
    return Device(description["name"], description.get("driver", ""), description.get("model", ""),
                  description.get("rate_hz", 0.0), values("joint_names"), values("position_min"),
                  values("position_max"), values("velocity_max"), values("acceleration_max"), values("effort_max"))


def _read_header(path, file):
    expected = "expected a file written by robotctl record (docs/recording.md)"
    header = file.read(_FILE_HEADER.size)
    if header[:len(MAGIC)] != MAGIC:
        raise RecordingError(f"{path} is not a robotd recording: it does not start with the recording signature; "
                             f"{expected}")
    if len(header) < _FILE_HEADER.size:
        raise RecordingError(f"{path} ends inside its file header; {expected}")
    _, major, minor, description_bytes = _FILE_HEADER.unpack(header)
    if major != MAJOR_VERSION:
        raise RecordingError(f"{path} is a robotd recording of format version {major}.{minor}; this module reads "
                             f"version {MAJOR_VERSION}.x (use a robotd package of that version)")
    text = file.read(description_bytes)
    if len(text) < description_bytes:
        raise RecordingError(f"{path} ends inside its description ({len(text)} of {description_bytes} bytes): "
                             "the file is damaged")
    try:
        description = json.loads(text.decode("utf-8"))
        devices = tuple(_device(device) for device in description["devices"])
        int(description["start_time_ns"])
    except (ValueError, KeyError, TypeError) as error:
        raise RecordingError(f"{path}: its description is not what docs/recording.md specifies: {error!r}") from None
    return (major, minor), description, devices


def read(path):
    """The whole recording at `path` (a str or os.PathLike) as a Recording."""
    path = str(path)
    with open(path, "rb") as file:
        version, description, devices = _read_header(path, file)
        recording = Recording(path, version, description, devices)
        count = 0
        while True:
            offset = file.tell()
            header = file.read(_RECORD_HEADER.size)
            if not header:
                recording.problems.append(f"{path} has no end record after its {count} records: robotctl record did "
                                          "not finish (it was killed, or the disk filled); every record is complete")
                break
            payload = b""
            if len(header) == _RECORD_HEADER.size:
                kind, payload_bytes, time_ns = _RECORD_HEADER.unpack(header)
                payload = file.read(payload_bytes)
            if len(header) < _RECORD_HEADER.size or len(payload) < payload_bytes:
                recording.problems.append(f"{path} is cut short: the record at byte {offset} has only "
                                          f"{len(header) + len(payload)} bytes (robotctl record was killed while "
                                          f"writing it); the {count} records before it are complete")
                break
            count += 1
            recording.duration_ns = time_ns
            if kind == KIND_END:
                recording.closed = True
                break
            if kind not in _DECODERS:
                continue  # a kind of a newer minor version
            decode, destination = _DECODERS[kind]
            try:
                getattr(recording, destination).append(decode(time_ns, payload, devices))
            except (ValueError, struct.error) as error:
                recording.problems.append(f"{path}: the record at byte {offset} (kind {kind}) is damaged and was "
                                          f"skipped: {error}")
        return recording
