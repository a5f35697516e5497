"""robotd for Python: sessions, commands, joint states, safety and device operations, and motion
planned here (run_rbtscript, Session.move_joints, Session.move_cartesian), over the robotd C API
(librobotd_c) with ctypes. docs/clients.md ("Python") is the guide.

    import robotd

    with robotd.Session(device="arm", motors=[0, 1, 2]) as session:
        session.command(positions=[0.5, 0.0, 0.3])

The C library loads on first use of one of these names, so that robotd.recording and
robotd.plot (recordings made by robotctl record) work where only this package is installed.
"""
import importlib

# Public name: the module that defines it.
_EXPORTS = {
    "C_API_VERSION": "._native",
    "Behavior": ".types", "DeviceInfo": ".types", "DeviceState": ".types", "DeviceStatus": ".types",
    "JointState": ".types", "LowRateAction": ".types", "Mode": ".types", "SessionInfo": ".types",
    "TickState": ".types", "Shape": ".types", "RunEnd": ".types", "MoveReport": ".types",
    "RbtscriptProblem": ".types", "RbtscriptReport": ".types",
    "run_rbtscript": ".motion",
    "Client": ".client",
    "Session": ".session",
    "Subscription": ".subscription",
    "InternalError": ".errors", "InvalidArgument": ".errors", "NotAvailable": ".errors", "NotPermitted": ".errors",
    "Refused": ".errors", "RobotdError": ".errors", "Timeout": ".errors", "TransportError": ".errors",
}

__all__ = sorted(_EXPORTS)


def __getattr__(name):
    if name == "__version__":
        from ._native import lib, text
        value = text(lib.robotd_version())
    elif name in _EXPORTS:
        value = getattr(importlib.import_module(_EXPORTS[name], __name__), name)
    else:
        raise AttributeError(f"module 'robotd' has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_EXPORTS) | {"__version__"})
