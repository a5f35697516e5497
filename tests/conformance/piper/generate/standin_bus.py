"""A python-can bus over robotd's stand-in CAN socket (a unix SOCK_SEQPACKET socket carrying one
Linux `struct can_frame` per datagram, drivers/common/src/standin_can_transport.cpp), so the
vendor SDK can drive robotd-piper-sim as it would drive a SocketCAN interface."""
import select
import socket
import struct
import time

import can

BUS_TYPE = "robotd_standin"

_CAN_FRAME = struct.Struct("=IB3x8s")  # can_id, len, pad/res0/len8_dlc, data: CAN_MTU = 16 bytes
_CAN_EFF_FLAG = 0x80000000
_CAN_ERR_FLAG = 0x20000000
_CAN_SFF_MASK = 0x7FF
_CAN_EFF_MASK = 0x1FFFFFFF


class StandInBus(can.BusABC):
    """`channel` is the stand-in socket path robotd-piper-sim listens on (--standin PATH).
    Every frame sent and received is kept in `transcript` as (time s, "tx"/"rx", id, hex data)
    when `record` is true."""

    def __init__(self, channel=None, record=True, **kwargs):
        super().__init__(channel=channel, **kwargs)
        self.channel_info = f"robotd stand-in CAN {channel}"
        self._socket = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        self._socket.connect(channel)
        self._record = record
        self.transcript = []

    def _note(self, direction, message):
        if self._record:
            self.transcript.append((time.monotonic(), direction, message.arbitration_id, bytes(message.data).hex(" ")))

    def send(self, msg, timeout=None):
        can_id = msg.arbitration_id | (_CAN_EFF_FLAG if msg.is_extended_id else 0)
        self._socket.send(_CAN_FRAME.pack(can_id, len(msg.data), bytes(msg.data).ljust(8, b"\0")))
        self._note("tx", msg)

    def _recv_internal(self, timeout):
        ready, _, _ = select.select([self._socket], [], [], timeout)
        if not ready:
            return None, False
        datagram = self._socket.recv(72)
        if len(datagram) != _CAN_FRAME.size:
            return None, False  # CAN FD is not the PiPER's
        can_id, length, data = _CAN_FRAME.unpack(datagram)
        extended = bool(can_id & _CAN_EFF_FLAG)
        message = can.Message(timestamp=time.time(),
                              arbitration_id=can_id & (_CAN_EFF_MASK if extended else _CAN_SFF_MASK),
                              is_extended_id=extended, is_error_frame=bool(can_id & _CAN_ERR_FLAG),
                              data=data[:length])
        self._note("rx", message)
        return message, False

    def shutdown(self):
        self._socket.close()
        super().shutdown()
