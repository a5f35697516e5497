"""A recording proxy between a RealMan client (the vendor SDK) and a controller (robotd-realman-sim).

TCP: every client connection gets its own upstream connection; bytes are forwarded as they come,
chunk by chunk (so a client's batching reaches the controller unchanged), and every CR LF
terminated line is recorded with its connection, its direction and the time it was read.

UDP push: the controller pushes to whatever `set_realtime_push` names. When the client asks for
a push to `ip`:`port`, the proxy forwards that request with the port (and ip) replaced by its
own UDP port, relays each datagram to the client's port and records it. The client listens on
the port the controller reports, so `get_realtime_push` replies go back to it with the client's
port again. These two replacements are the only changes the proxy makes to what passes; the
transcript has each line as its sender wrote it.
"""

import json
import selectors
import socket
import threading
import time


class Transcript:
    """Every message seen, in the order the proxy read them (thread-safe)."""

    def __init__(self):
        self._lock = threading.Lock()
        self._start = time.monotonic()
        self.entries = []

    def add(self, **entry):
        with self._lock:
            entry["t_ms"] = round((time.monotonic() - self._start) * 1000.0, 3)
            self.entries.append(entry)


class _Lines:
    """Splits a byte stream at CR LF, as the controller does."""

    def __init__(self):
        self._pending = b""

    def feed(self, data):
        self._pending += data
        lines = []
        while True:
            end = self._pending.find(b"\r\n")
            if end < 0:
                return lines
            lines.append(self._pending[:end].decode("utf-8", errors="backslashreplace"))
            self._pending = self._pending[end + 2:]


class RecordingProxy:
    def __init__(self, upstream_port, transcript, host="127.0.0.1"):
        self.transcript = transcript
        self._host = host
        self._upstream_port = upstream_port
        self._listener = socket.create_server((host, 0))
        self.port = self._listener.getsockname()[1]
        self._udp = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self._udp.bind((host, 0))
        self.udp_port = self._udp.getsockname()[1]
        self._push_target = None  # (ip, port) the client asked for
        self._connections = 0
        self._stop = threading.Event()
        self._threads = [threading.Thread(target=self._accept_loop, daemon=True),
                         threading.Thread(target=self._udp_loop, daemon=True)]
        for thread in self._threads:
            thread.start()

    def close(self):
        self._stop.set()
        self._listener.close()
        self._udp.close()

    def _accept_loop(self):
        while not self._stop.is_set():
            try:
                client, _ = self._listener.accept()
            except OSError:
                return
            self._connections += 1
            connection = self._connections
            upstream = socket.create_connection((self._host, self._upstream_port))
            # The proxy adds no delay of its own: what it reads it writes at once.
            upstream.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
            client.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
            self.transcript.add(connection=connection, event="open")
            threading.Thread(target=self._pump, args=(connection, client, upstream), daemon=True).start()

    def _pump(self, connection, client, upstream):
        requests, replies = _Lines(), _Lines()
        selector = selectors.DefaultSelector()
        selector.register(client, selectors.EVENT_READ, "request")
        selector.register(upstream, selectors.EVENT_READ, "reply")
        open_ = True
        while open_ and not self._stop.is_set():
            for key, _ in selector.select(timeout=0.1):
                try:
                    data = key.fileobj.recv(65536)
                except OSError:
                    data = b""
                if not data:
                    open_ = False
                    break
                direction = key.data
                splitter = requests if direction == "request" else replies
                lines = splitter.feed(data)
                if direction == "request" and len(lines) > 1:
                    self.transcript.add(connection=connection, event="segment", direction=direction,
                                        lines=len(lines))
                # Whole lines only (both ends split at CR LF); a batch stays one write.
                rewrite, peer = (self._to_controller, upstream) if direction == "request" else (self._to_client, client)
                if lines:
                    peer.sendall(b"".join(rewrite(line) + b"\r\n" for line in lines))
                for line in lines:
                    self.transcript.add(connection=connection, direction=direction, text=line)
        selector.close()
        client.close()
        upstream.close()
        self.transcript.add(connection=connection, event="close")

    @staticmethod
    def _push_message(line, command):
        """`line` as a dict if it is `command`'s message with a "port", else None."""
        try:
            message = json.loads(line)
        except ValueError:
            return None
        if isinstance(message, dict) and message.get("command") == command and "port" in message:
            return message
        return None

    def _to_controller(self, line):
        """A client's line as the controller gets it: a push request is pointed at the proxy."""
        message = self._push_message(line, "set_realtime_push")
        if message is None:
            return line.encode("utf-8", errors="surrogateescape")
        self._push_target = (message.get("ip") or self._host, message["port"])
        message["port"] = self.udp_port
        message["ip"] = self._host
        return json.dumps(message, separators=(",", ":")).encode()

    def _to_client(self, line):
        """A controller's line as the client gets it: the push settings name the client's port."""
        message = self._push_message(line, "get_realtime_push")
        if message is None or self._push_target is None or message["port"] != self.udp_port:
            return line.encode("utf-8", errors="surrogateescape")
        message["ip"], message["port"] = self._push_target
        return json.dumps(message, separators=(",", ":")).encode()

    def _udp_loop(self):
        while not self._stop.is_set():
            try:
                data, _ = self._udp.recvfrom(65536)
            except OSError:
                return
            self.transcript.add(direction="push", text=data.rstrip(b"\r\n").decode("utf-8", errors="backslashreplace"))
            if self._push_target is not None:
                try:
                    self._udp.sendto(data, self._push_target)
                except OSError:
                    pass
