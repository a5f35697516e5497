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


class LowRateAction(_ParsedEnum):
    """What robotd does when a closed-loop session's command success rate falls below its minimum."""
    WARN = 0  # log it and flag it in /session_status (success_rate_low)
    FALLBACK = 1  # end the session with its on_timeout behavior, as on timeout


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
    kinematic_model: str  # the arm model clients plan motion with, e.g. "parol6"; "" when none
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


@dataclass(frozen=True)
class TickState:
    """What one tick of a device's loop measured (/<device>/tick_state). A closed-loop session
    answers it (Session.answer); robotd counts the answer in time when it arrives before the
    device's next state is measured."""
    device: str
    tick: int  # 1, 2, ...
    stamp_ns: int  # the tick's deadline, CLOCK_REALTIME
    deadline_steady_ns: int  # the tick's deadline, CLOCK_MONOTONIC (time.monotonic_ns())
    period_ns: int  # the next tick is due at deadline_steady_ns + period_ns
    state_ready_steady_ns: int  # robotd's loop handed the state over
    published_steady_ns: int  # robotd wrote the sample
    state: DeviceState
    position: tuple  # rad, in motor id order
    velocity: tuple  # rad/s
    effort: tuple  # N·m
    imu: tuple  # None, or (orientation (x, y, z, w), angular velocity rad/s, linear acceleration m/s²)


@dataclass(frozen=True)
class SessionInfo:
    """A session's entry in /session_status, with its closed-loop counters: each tick it was to
    answer (since its first answer) was answered in time, late, or never."""
    session_id: str
    node_name: str
    device: str
    commands_accepted: int
    closed_loop: bool  # the session has answered a tick
    ticks_to_answer: int
    ticks_answered_in_time: int
    ticks_answered_late: int
    ticks_unanswered: int
    command_success_rate: float  # in time / to answer over the last 100 ticks to answer, 0..1
    min_command_success_rate: float  # 0 = none
    on_low_success_rate: LowRateAction
    success_rate_low: bool  # below the minimum now


class Shape(_ParsedEnum):
    """A planned move's velocity profile (RBTscript's func)."""
    DEFAULT = 0  # RBTscript's: the polynomial with t, else the trapezoid
    POLY = 1  # a quintic: zero speed and acceleration at both ends
    TRAP = 2  # a trapezoid; with t in thirds (accelerate, cruise, decelerate)


class RunEnd(_ParsedEnum):
    """How an RBTscript run ended."""
    NOT_RUN = 0  # a dry run, or there were problems: nothing was sent to the device
    END_OF_PROGRAM = 1  # ran past the last statement
    END = 2  # reached End()
    LOOP_LIMIT = 3  # reached Loop() after `loops` passes
    STOPPED = 4  # stopped (Ctrl-C, the stop event): the arm holds where it was
    FAILED = 5  # a statement failed (an e-stop, a refused op): see RbtscriptReport.failure


@dataclass(frozen=True)
class MoveReport:
    """How a planned move (Session.move_joints, move_cartesian) ended."""
    stopped: bool  # the stop event or Ctrl-C ended it: the arm holds where it was measured then
    commands_sent: int
    fraction_done: float  # of the planned trajectory, 0..1
    last_measured: tuple  # rad, where the joints were measured at the end
    summary: str


@dataclass(frozen=True)
class RbtscriptProblem:
    """A syntax error, what a dry run found, or why a statement failed."""
    line: int  # 1-based
    column: int  # 1-based, in bytes
    statement: str  # as written ("" for a syntax error)
    message: str
    description: str  # all of it: "line 3, column 1: MoveJoint(0,0,170,0,0,0): ..."

    def __str__(self):
        return self.description


@dataclass(frozen=True)
class RbtscriptReport:
    """What robotd.run_rbtscript did. `problems` (syntax errors, or the dry run's findings) mean
    nothing was sent to the device."""
    device: str  # "" when there were syntax errors
    syntax_errors: bool
    problems: tuple  # of RbtscriptProblem, in line order
    moves_planned: int  # by the dry run, on one pass
    pass_seconds: float  # one pass's moves and delays, as planned
    end: RunEnd
    statements_run: int
    passes: int
    failure: object  # an RbtscriptProblem when end is FAILED, else None
