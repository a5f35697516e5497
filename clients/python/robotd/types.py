"""The values robotd's API passes around: modes, behaviours, device states, and the samples and
descriptions it returns. Vectors are tuples of floats, in robotd's units (rad, rad/s, N·m)."""
import enum
from dataclasses import dataclass


class _ParsedEnum(enum.IntEnum):
    @classmethod
    def parse(cls, value):
        """An instance from an instance, its number, or its name in any case ("zero_torque")."""
        if isinstance(value, cls):
            return value
        if isinstance(value, str):
            try:
                return cls[value.strip().upper()]
            except KeyError:
                names = ", ".join(member.name.lower() for member in cls)
                raise ValueError(f"{value!r} is not a {cls.__name__} (expected one of: {names})") from None
        if isinstance(value, int) and not isinstance(value, bool):
            try:
                return cls(value)
            except ValueError:
                raise ValueError(f"{value} is not a {cls.__name__} (expected 0..{len(cls) - 1})") from None
        raise TypeError(f"a {cls.__name__} is given by name or number, not {type(value).__name__}")


class Mode(_ParsedEnum):
    """How a session commands its motors."""
    POSITION = 0  # positions (optional velocities, kp, kd)
    TORQUE = 1  # torques
    MIXED = 2  # positions, kp, kd and torques: the MIT law with feed-forward


class Behavior(_ParsedEnum):
    """What robotd does with a session's motors on its timeout or release."""
    KEEP = 0  # hold where commanded now
    DAMPING = 1  # kp = 0, kd = the session's default kd
    ZERO_TORQUE = 2  # let go


class DeviceState(_ParsedEnum):
    CONNECTING = 0
    RUNNING = 1
    FAULT = 2
    ESTOP = 3
    MAINTENANCE = 4  # recover or reset_zero in progress
    STOPPED = 5


@dataclass(frozen=True)
class DeviceInfo:
    """A device robotd drives, with its joints' limits."""
    name: str
    driver: str
    model: str
    state: DeviceState
    rate_hz: float
    joint_names: tuple
    position_min: tuple  # rad
    position_max: tuple  # rad
    velocity_max: tuple  # rad/s
    effort_max: tuple  # N·m


@dataclass(frozen=True)
class JointState:
    """One /joint_states sample of a device."""
    device: str
    stamp_ns: int  # CLOCK_REALTIME
    names: tuple
    position: tuple  # rad
    velocity: tuple  # rad/s
    effort: tuple  # N·m


@dataclass(frozen=True)
class DeviceStatus:
    """One /device_status sample: the device's state, loop timing and command counters."""
    device: str
    stamp_ns: int  # CLOCK_REALTIME
    state: DeviceState
    state_text: str
    fault_code: int
    fault_text: str
    estop_engaged: bool
    loop_period_p50_us: float
    loop_period_p99_us: float
    loop_period_max_us: float
    loop_overruns: int  # ticks missed since robotd started
    commands_accepted: int
    commands_rejected: int  # every reason
