"""The exceptions robotd raises: one per status of the C API, each carrying robotd's message."""


class RobotdError(Exception):
    """A call failed. `status` is the C API's status name (e.g. "ROBOTD_REFUSED"), `message` the
    reason, in robotd's own words when robotd refused."""

    def __init__(self, status, message):
        super().__init__(message)
        self.status = status
        self.message = message


class Timeout(RobotdError, TimeoutError):
    """No answer or sample within the deadline."""


class NotAvailable(RobotdError, ConnectionError):
    """robotd (or the service) is not reachable on this DDS domain."""


class Refused(RobotdError):
    """robotd answered and said no: the message says why (e.g. who holds the motors)."""


class InvalidArgument(RobotdError, ValueError):
    """The caller passed something malformed; nothing was sent."""


class TransportError(RobotdError):
    """The DDS layer failed."""


class NotPermitted(RobotdError, PermissionError):
    """DDS Security: this participant's permissions do not allow it."""


class InternalError(RobotdError):
    """Out of memory, or a failure inside the library."""


BY_STATUS = {
    1: Timeout,
    2: NotAvailable,
    3: Refused,
    4: InvalidArgument,
    5: TransportError,
    6: NotPermitted,
    8: InternalError,
}
