"""A python-can bus that records what the PiPER SDK sends instead of reaching a CAN interface.

The SDK opens its bus with `can.interface.Bus(channel=..., bustype=..., bitrate=...)`
(hardware_port/can_encapsulation_v0_4_0.py). `install()` routes the bus type "robotd_capture"
there to `CaptureBus`; every other bus type still reaches python-can.
"""
import can

BUS_TYPE = "robotd_capture"


class CaptureBus(can.BusABC):
    """Keeps every sent frame in `sent`; receives nothing (feedback is fed to ParseCANFrame)."""

    def __init__(self, channel=None, **kwargs):
        super().__init__(channel=channel, **kwargs)
        self.channel_info = f"robotd capture bus {channel}"
        self.sent = []

    def send(self, msg, timeout=None):
        self.sent.append(msg)

    def _recv_internal(self, timeout):
        return None, False

    def take(self):
        """The frames sent since the last take, as {"id", "data"} with data in hex."""
        frames = [{"id": m.arbitration_id, "extended": bool(m.is_extended_id), "data": bytes(m.data).hex(" ")}
                  for m in self.sent]
        self.sent.clear()
        return frames


def install(bus_types):
    """Makes can.interface.Bus build our own buses: `bus_types` maps a bus type to a factory
    taking (channel, **kwargs)."""
    python_can_bus = can.interface.Bus

    def bus(channel=None, bustype=None, interface=None, **kwargs):
        kind = interface or bustype
        if kind in bus_types:
            kwargs.pop("bitrate", None)
            return bus_types[kind](channel=channel, **kwargs)
        return python_can_bus(channel=channel, interface=kind, **kwargs)

    can.interface.Bus = bus
