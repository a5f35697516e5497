"""robotd for Python: sessions, commands, joint states, safety and device operations, over the
robotd C API (librobotd_c) with ctypes. docs/clients.md ("Python") is the guide.

    import robotd

    with robotd.Session(device="arm", motors=[0, 1, 2]) as session:
        session.command(positions=[0.5, 0.0, 0.3])
"""
from ._native import C_API_VERSION, lib as _lib, text as _text
from .client import Client
from .errors import (InternalError, InvalidArgument, NotAvailable, NotPermitted, Refused, RobotdError, Timeout,
                     TransportError)
from .session import Session
from .subscription import Subscription
from .types import Behavior, DeviceInfo, DeviceState, DeviceStatus, JointState, Mode

__version__ = _text(_lib.robotd_version())

__all__ = ["C_API_VERSION", "Behavior", "Client", "DeviceInfo", "DeviceState", "DeviceStatus", "InternalError",
           "InvalidArgument", "JointState", "Mode", "NotAvailable", "NotPermitted", "Refused", "RobotdError",
           "Session", "Subscription", "Timeout", "TransportError"]
