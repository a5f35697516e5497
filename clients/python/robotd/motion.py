"""Motion planned in this process, over the C API: RBTscript programs (run_rbtscript) and the moves
behind Session.move_joints and Session.move_cartesian. The planning runs here, on the device's
limits and the arm model its driver names; robotd follows the stream. Ctrl-C, or a
threading.Event passed as `stop`, ends a program or a move with the arm held."""
import math
import traceback
from ctypes import byref, c_double, c_int, c_void_p, pointer

from . import _native
from ._native import check, lib, optional_text, stoppable, text
from .types import MoveReport, RbtscriptProblem, RbtscriptReport, RunEnd, Shape


def _move_options(t, v, a, func, stop_flag):
    """The C options for RBTscript's t, v, a and func (None: not given)."""
    options = _native.MoveOptions()
    check(lib.robotd_move_options_init(byref(options)))
    for field, value, name, what in (("duration_s", t, "t", "seconds"),
                                     ("speed_percent", v, "v", "percent of the maximum speed"),
                                     ("acceleration_percent", a, "a", "percent of the maximum acceleration")):
        if value is None:
            continue
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value <= 0:
            raise ValueError(f"{name} is {value!r}: expected {what}, more than 0, or None")
        setattr(options, field, float(value))
    options.shape = Shape.DEFAULT if func is None else Shape.parse(func)
    options.stop = pointer(stop_flag)
    return options


def move_report(raw):
    return MoveReport(stopped=bool(raw.stopped), commands_sent=raw.commands_sent, fraction_done=raw.fraction_done,
                      last_measured=tuple(raw.last_measured[:raw.joint_count]), summary=text(raw.summary))


def _problem(raw):
    return RbtscriptProblem(line=raw.line, column=raw.column, statement=text(raw.statement),
                            message=text(raw.message), description=text(raw.description))


def run_rbtscript(client, program, *, device=None, dry_run=False, loops=None, on_statement=None, stop=None,
                  session_timeout=2.0):
    """Runs the RBTscript `program` (its text) on `device` (None: robotd's only device) through
    `client`, as `robotctl run` does, and returns an RbtscriptReport once it has ended: the whole
    text is parsed, then checked against the device (every move planned on its limits and arm
    model, every Output and Gripper mapped to its ops), and only a program without problems runs
    (unless `dry_run`). `loops`: passes through Loop() at most (None: until stopped).
    `on_statement(line, statement, pass_number)` is called before each statement of the run, on a
    thread of the library. Raises for what stops the run before it starts (robotd not answering,
    an unknown device, a refused session); a statement that fails while running is the report's
    `failure`."""
    if loops is not None and (isinstance(loops, bool) or not isinstance(loops, int) or loops < 1):
        raise ValueError(f"loops is {loops!r}: expected a number of passes, 1 or more, or None (until stopped)")
    options = _native.RbtscriptOptions()
    check(lib.robotd_rbtscript_options_init(byref(options)))
    device_text = optional_text(device)
    options.device = device_text
    options.dry_run = bool(dry_run)
    options.loops = 0 if loops is None else loops
    stop_flag = c_int(0)
    options.stop = pointer(stop_flag)
    options.session_timeout_ms = _native.milliseconds(session_timeout, "session_timeout")
    if on_statement is not None:
        def progress(line, statement, pass_number, _user_data):
            try:
                on_statement(line, text(statement), pass_number)
            except Exception as error:  # an exception cannot cross the C library
                traceback.print_exception(type(error), error, error.__traceback__)

        callback = _native.RbtscriptProgress(progress)
        options.on_statement = callback
    program_text = str(program).encode("utf-8")

    def call():
        handle = c_void_p()
        check(lib.robotd_run_rbtscript(client.handle, program_text, byref(options), byref(handle)))
        return handle

    handle = stoppable(call, stop_flag, stop)
    try:
        outcome = _native.RbtscriptOutcomeStruct()
        check(lib.robotd_rbtscript_report_outcome(handle, byref(outcome)))
        problems = []
        for index in range(outcome.problem_count):
            raw = _native.RbtscriptProblemStruct()
            check(lib.robotd_rbtscript_report_problem(handle, index, byref(raw)))
            problems.append(_problem(raw))
        end = RunEnd(outcome.end)
        return RbtscriptReport(device=text(outcome.device), syntax_errors=bool(outcome.syntax_errors),
                               problems=tuple(problems), moves_planned=outcome.moves_planned,
                               pass_seconds=outcome.pass_seconds, end=end, statements_run=outcome.statements_run,
                               passes=outcome.passes,
                               failure=_problem(outcome.failure) if end == RunEnd.FAILED else None)
    finally:
        lib.robotd_rbtscript_report_free(handle)


def move(call_move, timing, stop):
    """Runs a move, call_move(options, report) making the C call and checking it, with the C options
    for `timing` (t, v, a, func), so that Ctrl-C or `stop` end it with the arm held; its MoveReport."""
    stop_flag = c_int(0)
    options = _move_options(*timing, stop_flag)
    raw = _native.MoveReportStruct()
    stoppable(lambda: call_move(options, raw), stop_flag, stop)
    return move_report(raw)
