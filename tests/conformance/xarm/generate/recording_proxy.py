"""A TCP proxy that records every byte between a client and a server, per connection and per
direction, split into the protocol's frames: command-port frames (6-byte header + length) and
report packets (u32 big-endian size prefix). Ours; it knows nothing of the vendor's code."""
import socket
import struct
import threading
import time


def split_command_frames(buffer):
    """Complete frames at the front of `buffer` (header: tid, protocol, length; then length bytes)."""
    frames = []
    while len(buffer) >= 6:
        length = struct.unpack('>H', buffer[4:6])[0]
        if len(buffer) < 6 + length:
            break
        frames.append(bytes(buffer[:6 + length]))
        del buffer[:6 + length]
    return frames


def split_report_packets(buffer):
    packets = []
    while len(buffer) >= 4:
        size = struct.unpack('>I', buffer[:4])[0]
        if size < 8 or len(buffer) < size:
            break
        packets.append(bytes(buffer[:size]))
        del buffer[:size]
    return packets


class Connection:
    def __init__(self, number, listen_port, kind):
        self.number = number
        self.port = listen_port
        self.kind = kind  # "command" or a report kind
        self.frames = []  # (seconds since the proxy started, direction, bytes, step)
        self.lock = threading.Lock()


class RecordingProxy:
    """Listens on 127.0.0.1:`port` for each (port, target_port, kind) and relays to the target."""

    def __init__(self, routes, report_packets_kept):
        self.routes = routes
        self.report_packets_kept = report_packets_kept
        self.connections = []
        self.step = 'connect'
        self.started = time.monotonic()
        self.lock = threading.Lock()
        self.listeners = []

    def start(self):
        for port, target, kind in self.routes:
            listener = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
            listener.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            listener.bind(('127.0.0.1', port))
            listener.listen(8)
            listener.settimeout(None)
            self.listeners.append(listener)
            threading.Thread(target=self._accept, args=(listener, port, target, kind), daemon=True).start()

    def _accept(self, listener, port, target, kind):
        while True:
            try:
                client, _ = listener.accept()
            except OSError:
                return
            server = socket.create_connection(('127.0.0.1', target))
            for sock in (client, server):
                sock.settimeout(None)  # the SDK sets a 1 s default timeout for every new socket
                sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
            with self.lock:
                connection = Connection(len(self.connections), port, kind)
                self.connections.append(connection)
            threading.Thread(target=self._relay, args=(client, server, connection, 'request'), daemon=True).start()
            threading.Thread(target=self._relay, args=(server, client, connection, 'reply'), daemon=True).start()

    def _relay(self, source, sink, connection, direction):
        buffer = bytearray()
        is_command = connection.kind == 'command'
        kept = 0
        while True:
            try:
                data = source.recv(65536)
            except OSError:
                data = b''
            if not data:
                for sock in (source, sink):
                    try:
                        sock.shutdown(socket.SHUT_RDWR)
                    except OSError:
                        pass
                return
            # Recorded before it is forwarded, so that a reply is never listed before its request.
            buffer.extend(data)
            units = split_command_frames(buffer) if is_command else split_report_packets(buffer)
            now = time.monotonic() - self.started
            with connection.lock:
                for unit in units:
                    if not is_command:
                        if kept >= self.report_packets_kept:
                            continue
                        kept += 1
                    connection.frames.append((now, direction, unit, self.step))
            try:
                sink.sendall(data)
            except OSError:
                return

    def requests_sent(self, kind):
        """How many requests the connections of `kind` carried so far."""
        with self.lock:
            connections = [c for c in self.connections if c.kind == kind]
        return sum(sum(1 for frame in c.frames if frame[1] == 'request') for c in connections)

    def close(self):
        for listener in self.listeners:
            listener.close()
